// Linear float images (OpenEXR) and tone-mapped pictures (PNG).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cpgi {

struct ImageRGB {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;  ///< row-major, row 0 at the top
  glm::vec3& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

void writeExr(const std::string& path, const ImageRGB& image);  ///< 32-bit float RGB, atomically
ImageRGB readExr(const std::string& path);                       ///< throws InputError
/// sRGB PNG; `exposure` scales linear values before a Reinhard-free clamp + sRGB curve.
void writePng(const std::string& path, const ImageRGB& image, float exposure = 1.0f);
/// Encodes to PNG bytes in memory (for embedding in glTF).
std::string encodePng(const ImageRGB& image, float exposure = 1.0f);

}  // namespace cpgi
