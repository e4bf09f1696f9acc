// Two atlases of one scene at different texel sizes (issue 13: the light solved where it varies, written
// at the output's resolution): what a fine texel is in the coarse atlas. Each valid fine texel lies on a
// scene triangle, which lies on one chart of the coarse atlas; its centre in that chart's coordinates
// carries values across either way: down as area-weighted means over the coarse texel it falls in (power
// kept exactly), up by bilinear interpolation between coarse texel centres within the chart.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"

namespace cpgi {

struct AtlasMapping {
  /// Per fine atlas texel: its coarse patch (−1 for padding, or a triangle the coarse atlas lacks) and
  /// its centre in that chart's texel coordinates (texel (i, j) spans [i, i+1] × [j, j+1]).
  std::vector<int32_t> coarsePatch;
  std::vector<glm::vec2> chartPoint;
  /// Per fine texel, the coarse atlas texel its centre falls in (−1 where coarsePatch is −1).
  std::vector<int64_t> coarseTexel;
};

/// Maps `fine` onto `coarse`; both must be atlases of the same scene (same triangle count).
/// Throws std::invalid_argument otherwise.
AtlasMapping mapAtlas(const LightmapAtlas& fine, const LightmapAtlas& coarse);

/// Per coarse texel, the area-weighted mean of `values` over the fine texels that fall in it (0 where
/// none does), each chart scaled so that Σ value × area over it is what its fine texels held.
std::vector<glm::vec3> downsample(const AtlasMapping& m, const LightmapAtlas& fine,
                                  const LightmapAtlas& coarse, std::span<const glm::vec3> values);

/// Per fine texel, `values` (per coarse texel) interpolated bilinearly between the centres of the valid
/// coarse texels of its chart around its centre (nearest valid ones where the chart's edge or a loose
/// triangle's empty corner leaves fewer than four); 0 on fine padding.
std::vector<glm::vec3> upsample(const AtlasMapping& m, const LightmapAtlas& fine, const LightmapAtlas& coarse,
                                std::span<const glm::vec3> values);

}  // namespace cpgi
