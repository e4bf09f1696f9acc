#include "core/cell_palette.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cpgi {

glm::vec3 cellColour(int index) {
  if (index < 0) return glm::vec3(0.35f);
  const float hue = std::fmod(0.11f + 0.61803398875f * float(index), 1.0f);
  // HSV with s = 0.55, v = 0.95, to linear (approximately: square the sRGB-ish value).
  const float s = 0.55f, val = 0.95f;
  const float hh = hue * 6.0f;
  const int sector = int(hh) % 6;
  const float frac = hh - std::floor(hh);
  const float p = val * (1 - s), q = val * (1 - s * frac), t = val * (1 - s * (1 - frac));
  const glm::vec3 bySector[6] = {{val, t, p}, {q, val, p}, {p, val, t},
                                 {p, q, val}, {t, p, val}, {val, p, q}};
  const glm::vec3 rgb = bySector[sector];
  return rgb * rgb;
}

std::string cellColourHex(int index) {
  const glm::vec3 linear = cellColour(index);
  auto encode = [](float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return int(std::lround(255.0f * srgb));
  };
  char hex[8];
  std::snprintf(hex, sizeof hex, "#%02x%02x%02x", encode(linear.r), encode(linear.g), encode(linear.b));
  return hex;
}

}  // namespace cpgi
