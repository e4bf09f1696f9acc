// How many texels each surface's light needs (issue 13, `bake --density auto`): a lightmap is read by
// bilinear interpolation between texel centres, which misses a curved light by about h² |B''| / 8 at
// texel spacing h. From the light on a pilot atlas of a fixed density (B'' from its second differences
// along each chart's axes), each quad gets the coarsest spacing at which that miss, as an RMS over the
// quad, stays within a tolerance of its RMS light: the measure compare-light's per-cell error takes, so
// a small shadow on a large floor asks for what it costs the floor, not for the finest texels over all
// of it. Shadow and beam edges and the fall-off near a lamp come out fine, evenly lit walls coarse.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

struct LightDensityParams {
  float minDensity = 4.0f;   ///< texels per metre where the light is flat
  float maxDensity = 40.0f;  ///< the most, at shadow edges (a step needs ever more)
  /// The interpolation's RMS miss allowed over a quad, a share of its RMS light plus `floorShare` × the
  /// mean light over the pilot's lit texels (a dark corner's small wiggles need no texels).
  float tolerance = 0.01f;
  float floorShare = 0.05f;
};

/// Per scene triangle (`triangleCount` of them), the texels per metre its quad needs, from `light` (per
/// texel of `pilot`, W/m²: the light whose detail the output must keep) by the rule above, at most
/// maxDensity and at least minDensity; a quad's two triangles alike; 0 for triangles the pilot lacks.
/// A texel's B'' is the larger of its second differences along its chart's two axes (those with both
/// neighbours on the chart) over the spacing squared; the quad's need is
/// √(RMS B'' / (8 tolerance RMS(B + floor))).
std::vector<float> lightDensity(const LightmapAtlas& pilot, std::span<const glm::vec3> light, size_t triangleCount,
                                const LightDensityParams& params);

/// Gives every flat surface (triangles of one material in one plane, joined at their corners) the largest
/// density of its triangles: neighbouring charts of one surface at different texel sizes meet with a step
/// where each chart's bilinear lookups clamp at its edge, a seam across a floor (house-spiral's floors and
/// walls at 4 and 12 texels a metre side by side). 0 (not in the atlas) stays 0.
void evenOverSurfaces(const Scene& scene, std::vector<float>& density);

}  // namespace cpgi
