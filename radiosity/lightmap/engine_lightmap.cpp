#include "radiosity/lightmap/engine_lightmap.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace cpgi {

namespace {

// Below this a channel's albedo is taken as 0: what it reflects is float noise, not light read back.
constexpr float kMinAlbedo = 1e-6f;

}  // namespace

std::vector<glm::vec3> irradianceFromRadiosity(const LightmapAtlas& atlas,
                                               const std::vector<glm::vec3>& radiosity,
                                               size_t* unknownTexels) {
  if (radiosity.size() != atlas.texelCount())
    throw std::invalid_argument("irradianceFromRadiosity: one radiosity per atlas texel");
  std::vector<glm::vec3> irradiance(radiosity.size(), glm::vec3(0.0f));
  size_t unknown = 0;
  for (size_t i = 0; i < radiosity.size(); ++i) {
    if (atlas.patch[i] < 0) continue;
    bool known = true;
    for (int c = 0; c < 3; ++c) {
      const float albedo = atlas.albedo[i][c];
      if (!(albedo > kMinAlbedo)) {
        known = false;
        continue;
      }
      irradiance[i][c] = std::max(0.0f, radiosity[i][c] - atlas.emission[i][c]) / albedo;
    }
    unknown += !known;
  }
  if (unknownTexels) *unknownTexels = unknown;
  return irradiance;
}

RgbmImage encodeRgbm(int width, int height, const std::vector<glm::vec3>& values, float range) {
  if (width <= 0 || height <= 0 || values.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("encodeRgbm: the values do not match the size");
  if (!(range > 0.0f) || !std::isfinite(range)) throw std::invalid_argument("encodeRgbm: range must be > 0");
  RgbmImage image{width, height, range, std::vector<uint8_t>(values.size() * 4, 0)};
  for (size_t i = 0; i < values.size(); ++i) {
    glm::vec3 v = glm::clamp(values[i], glm::vec3(0.0f), glm::vec3(range)) / range;
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(v[c])) v[c] = 0.0f;
    const float peak = std::max({v.r, v.g, v.b});
    // The smallest alpha step that holds the peak, at least one (a black texel decodes to 0 whatever a).
    const int alpha = std::clamp(int(std::ceil(peak * 255.0f - 1e-4f)), 1, 255);
    const float m = float(alpha) / 255.0f;
    for (int c = 0; c < 3; ++c)
      image.rgba[4 * i + size_t(c)] = uint8_t(std::clamp(int(std::lround(v[c] / m * 255.0f)), 0, 255));
    image.rgba[4 * i + 3] = uint8_t(alpha);
  }
  return image;
}

glm::vec3 decodeRgbm(const RgbmImage& image, size_t i) {
  const uint8_t* p = &image.rgba[4 * i];
  const float m = float(p[3]) / 255.0f * image.range;
  return glm::vec3(p[0], p[1], p[2]) / 255.0f * m;
}

float rgbmTolerance(const RgbmImage& image, size_t i) {
  const float m = float(image.rgba[4 * i + 3]) / 255.0f * image.range;
  return 0.5f / 255.0f * m * (1.0f + 1e-4f) + 1e-7f * image.range;
}

LightmapRange lightmapRange(const LightmapAtlas& atlas, const std::vector<glm::vec3>& irradiance,
                            double ldrQuantile) {
  std::vector<std::pair<float, float>> levels;  // (largest channel, area) per valid texel
  for (size_t i = 0; i < irradiance.size(); ++i)
    if (atlas.patch[i] >= 0) {
      const glm::vec3& e = irradiance[i];
      levels.emplace_back(std::max({e.r, e.g, e.b}), atlas.area[i]);
    }
  LightmapRange range;
  if (levels.empty()) return range;
  std::sort(levels.begin(), levels.end());
  range.max = levels.back().first;
  const double total =
      std::accumulate(levels.begin(), levels.end(), 0.0,
                      [](double s, const std::pair<float, float>& l) { return s + l.second; });
  double below = 0.0;
  size_t k = 0;
  while (k + 1 < levels.size() && below + levels[k].second < ldrQuantile * total) below += levels[k++].second;
  range.ldrScale = levels[k].first;
  if (!(range.ldrScale > 0.0f)) range.ldrScale = range.max > 0.0f ? range.max : 1.0f;
  if (!(range.max > 0.0f)) range.max = 1.0f;
  range.rgbmRange = std::min(range.max, kRgbmHeadroom * range.ldrScale);
  double clipped = 0.0, rgbmClipped = 0.0;
  for (const auto& [level, area] : levels) {
    clipped += level > range.ldrScale ? area : 0.0f;
    rgbmClipped += level > range.rgbmRange ? area : 0.0f;
  }
  range.clippedArea = total > 0.0 ? clipped / total : 0.0;
  range.rgbmClippedArea = total > 0.0 ? rgbmClipped / total : 0.0;
  return range;
}

}  // namespace cpgi
