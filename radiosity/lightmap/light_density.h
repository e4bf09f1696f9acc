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
/// density of its triangles where that takes at most `maxGrowth` times the texels its triangles' own
/// densities do; 0 (not in the atlas) stays 0. One density over a room's floor and walls costs little and
/// holds their bounced light, which the pilot does not see (seed3's room B, openings' room C lit through
/// doors: 3.31 / 4.68 % against 3.50 / 6.07 % with a density per quad). A level whose floors are one plane
/// from end to end took 40 texels a metre everywhere for a sun shadow somewhere on them (OpenArena's
/// oa_dm4: 7.05 M texels, 1.81 M with a density per quad); there the charts keep their own, and the seam
/// gutters (seam_gutters.h) join them without a step.
void evenOverSurfaces(const Scene& scene, std::vector<float>& density, double maxGrowth = 2.0);

}  // namespace cpgi
