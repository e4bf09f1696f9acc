// Linear float images (OpenEXR) and tone-mapped pictures (PNG).
#pragma once

#include <cstdint>
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

/// An extra float channel stored beside R, G, B (e.g. the lightmap's per-texel area, "area").
struct ExrChannel {
  std::string name;
  std::vector<float> values;  ///< width × height, row-major
};

/// How an EXR stores its pixels: 32-bit float (exact, the books' lightmaps and views) or 16-bit half, which
/// engines and GPUs sample directly (values clamped to half's largest, 65504).
enum class ExrPrecision { Float, Half };

/// RGB plus optional extra channels, written atomically.
void writeExr(const std::string& path, const ImageRGB& image, const std::vector<ExrChannel>& extra = {},
              ExrPrecision precision = ExrPrecision::Float);
/// Reads R, G, B (and any extra channels into `extra` when given). Throws InputError.
ImageRGB readExr(const std::string& path, std::vector<ExrChannel>* extra = nullptr);
/// sRGB PNG; `exposure` scales linear values before a Reinhard-free clamp + sRGB curve.
void writePng(const std::string& path, const ImageRGB& image, float exposure = 1.0f);
/// Encodes to PNG bytes in memory (for embedding in glTF).
std::string encodePng(const ImageRGB& image, float exposure = 1.0f);
/// PNG bytes of 8-bit pixels as they are (no curve): `channels` 1–4 a pixel, width × height × channels
/// bytes, row-major (an RGBM lightmap's linear rgb and multiplier).
std::string encodePng8(int width, int height, int channels, const std::vector<uint8_t>& pixels);

}  // namespace cpgi
