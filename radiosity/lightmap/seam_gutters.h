// What a chart's gutter holds where its surface goes on in another chart. A lightmap is read bilinearly
// between texel centres, so within half a texel of a chart's edge the lookup blends the edge texel with
// the gutter texel beyond it. Filled with the edge texel's own value (dilate's nearest fill), the light
// stops changing there: two charts of one floor meet with a step of about a texel's worth of gradient
// on each side, and one at 4 texels a metre beside one at 40 shows it (house-spiral's floors, view-living).
// Filled instead with the neighbouring chart's light at the gutter texel's own point on the surface, both
// sides interpolate towards the same light and the seam closes (exactly where the light is linear).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// Per gutter texel of `atlas` (not valid, in the `padding` ring around a chart or in a loose triangle's
/// empty corner) whose point, on its chart's plane, lies on another chart of the same surface (same
/// material, same plane: normals within 0.5°, 1 mm apart): the valid texels of that chart interpolated
/// there (bilinear between their centres, extrapolated within the half texel beyond the outer ones) and
/// their weights. Gutter texels over no such chart get none (dilate fills them from their own chart).
/// Past `deadline` (looked at before each chart) throws AtlasLayoutStopped: a large atlas's gutters take
/// seconds (3.6 M texels: 3 s of one core).
std::vector<GutterTap> seamGutters(
    const LightmapAtlas& atlas, const Scene& scene, int padding,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

}  // namespace cpgi
