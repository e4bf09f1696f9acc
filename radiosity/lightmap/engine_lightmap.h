// The lightmap an engine takes as it is (issue 48): the light arriving at each texel, irradiance E in W/m²,
// without the surface's albedo, so that the material's own base colour and textures multiply it at run
// time (three.js's lightMap, Godot's and Unity's baked lightmaps). lightmap.exr keeps radiosity B for the
// books; E is read from it per texel: B = Le + ρ·E (the solver's every shot adds ρ times the light it
// brings), so E = (B − Le) / ρ.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// Per atlas texel, the irradiance E = (B − Le) / ρ per channel, W/m² (`radiosity` is B, undilated; padding
/// texels stay 0). A channel whose albedo is 0 reflects nothing, so its light arriving cannot be read from
/// B: it is written 0 (an engine multiplies it by that 0 albedo anyway), and the valid texels with such a
/// channel are counted in `unknownTexels` when it is not null.
std::vector<glm::vec3> irradianceFromRadiosity(const LightmapAtlas& atlas,
                                               const std::vector<glm::vec3>& radiosity,
                                               size_t* unknownTexels = nullptr);

/// RGBM in 8 bits a channel: value = rgb · a · range, rgb and a linear (no sRGB curve). RGBM rather than
/// RGBD: it is Unity's and Bakery's lightmap encoding, decoded by one multiply; its precision is about 1/255
/// of a texel's own value down to range/255, and steps of range/255² below that.
struct RgbmImage {
  int width = 0, height = 0;
  float range = 1.0f;         ///< the largest value held: rgb = a = 1
  std::vector<uint8_t> rgba;  ///< width × height × 4, row-major
};

/// Encodes `values` (width × height, ≥ 0) with `range` (> 0; values above it are clipped to it): a is the
/// smallest of the 255 steps that holds the texel's largest channel, rgb rounded to the nearest step.
RgbmImage encodeRgbm(int width, int height, const std::vector<glm::vec3>& values, float range);
/// The value of texel `i` of `image`: rgb · a · range.
glm::vec3 decodeRgbm(const RgbmImage& image, size_t i);
/// The most a decoded channel may differ from the value encoded (below `range`): half an rgb step at the
/// texel's alpha, plus float rounding.
float rgbmTolerance(const RgbmImage& image, size_t i);

/// The ranges of an HDR lightmap's 8-bit encodings. The plain sRGB lightmap in the glb has value 1 =
/// `ldrScale` W/m²: the level that `ldrQuantile` of the valid texels' area lies under (their largest
/// channel), so that the bright spots right under a lamp clip rather than darken every wall into the PNG's
/// few lowest steps. RGBM's range is the largest channel of any valid texel, but at most kRgbmHeadroom
/// times ldrScale: a lamp shade lit at a thousand times the walls would otherwise leave the walls steps
/// of range/255² that are a few per cent of their light (the EXR keeps every value exactly).
inline constexpr float kRgbmHeadroom = 64.0f;
struct LightmapRange {
  float max = 0.0f;
  float ldrScale = 1.0f;
  double clippedArea = 0.0;  ///< the share of the valid texels' area above ldrScale
  float rgbmRange = 1.0f;
  double rgbmClippedArea = 0.0;  ///< the share of the valid texels' area above rgbmRange
};
LightmapRange lightmapRange(const LightmapAtlas& atlas, const std::vector<glm::vec3>& irradiance,
                            double ldrQuantile = 0.995);

}  // namespace cpgi
