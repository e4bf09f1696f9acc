// Two atlases of one scene at different texel sizes (issue 13: the light solved where it varies, written
// at the output's resolution): what a fine texel is in the coarse atlas. Each valid fine texel lies on a
// scene triangle, which lies on one chart of the coarse atlas; its centre in that chart's coordinates
// carries values across either way: down as area-weighted means over the coarse texel it falls in (power
// kept exactly), up by bilinear interpolation between coarse texel centres within the chart.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

struct AtlasMapping {
  /// Per fine atlas texel: its coarse patch (−1 for padding, or a triangle the coarse atlas lacks) and
  /// its centre in that chart's texel coordinates (texel (i, j) spans [i, i+1] × [j, j+1]).
  std::vector<int32_t> coarsePatch;
  std::vector<glm::vec2> chartPoint;
  /// Per fine texel, the coarse atlas texel its centre falls in (−1 where coarsePatch is −1).
  std::vector<int64_t> coarseTexel;
  /// Per fine texel, −1, or where a solid runs through its chart between its sample point and some of the
  /// coarse texels it would be interpolated from (a reveal through a pane, a wall through a slab), its
  /// entry in `sideTaps`: the coarse texels on its own side of the solid, renormalised (none when there is
  /// none near it). Empty when mapAtlas was given no ray scene.
  std::vector<int32_t> sideTapsOf;
  std::vector<BilinearTaps> sideTaps;
};

/// Maps `fine` onto `coarse`; both must be atlases of the same scene (same triangle count).
/// Throws std::invalid_argument otherwise. With `solids` (the scene's rays), the light interpolated onto
/// a fine texel comes only from coarse texels whose sample points it sees along its surface, so that the
/// light of one side of a solid that a face runs through stays on that side.
AtlasMapping mapAtlas(const LightmapAtlas& fine, const LightmapAtlas& coarse,
                      const RayScene* solids = nullptr);

/// Per coarse texel, the area-weighted mean of `values` over the fine texels that fall in it (0 where
/// none does), each chart scaled so that Σ value × area over it is what its fine texels held.
std::vector<glm::vec3> downsample(const AtlasMapping& m, const LightmapAtlas& fine,
                                  const LightmapAtlas& coarse, std::span<const glm::vec3> values);

/// Per fine texel, `values` (per coarse texel) interpolated bilinearly between the centres of the coarse
/// texels of its chart around its centre, extrapolated (never below 0) in the half texel beyond the outer
/// centres, the nearest valid ones where a loose triangle's empty corner leaves fewer than four; 0 on fine
/// padding.
std::vector<glm::vec3> upsample(const AtlasMapping& m, const LightmapAtlas& fine, const LightmapAtlas& coarse,
                                std::span<const glm::vec3> values);

/// Chart coordinates of world point `x` on chart `p` (texel (i, j) spans [i, i+1] × [j, j+1]): origin +
/// i texelU + j texelV, least squares in its plane.
glm::vec2 chartCoordinates(const Patch& p, const glm::vec3& x);

/// The valid texels of chart `patch` of `atlas` that interpolate it at chart point `at`, and their weights
/// (summing to 1; one below 0 where the point lies beyond the chart's outer centres and is extrapolated,
/// within their half texel): the four around it, or where a loose triangle's empty corner leaves fewer
/// valid, those of the four clamped into the chart, renormalised, or else the valid texel nearest it.
BilinearTaps chartTaps(const LightmapAtlas& atlas, int32_t patch, glm::vec2 at);

/// The coarse texels upsample() interpolates fine texel `t` from: chartTaps at its centre's point on its
/// coarse chart, or its side's taps where a solid runs between (AtlasMapping::sideTaps); none on fine
/// padding.
BilinearTaps bilinearTaps(const AtlasMapping& m, const LightmapAtlas& coarse, size_t t);

/// Per fine texel, 1 where `values` (per coarse texel) cannot be interpolated to it: a coarse texel it
/// would be interpolated from is one where linear interpolation misses by more than `tolerance` × (its
/// value + `floor`) in R + G + B, judged by the second difference along its chart's axes (a shadow's or a
/// beam's edge, a steep fall-off near a lamp), or is flagged non-zero in `flags` (per coarse texel; empty:
/// none). 0 elsewhere and on padding.
std::vector<uint8_t> texelsToRefine(const AtlasMapping& m, const LightmapAtlas& fine,
                                    const LightmapAtlas& coarse, std::span<const glm::vec3> values,
                                    std::span<const uint8_t> flags, float relative, float floor);

}  // namespace cpgi
