// More paths where a cell's reference is too noisy to measure a bias (issue 11 item 7): a room lit only
// through two doors gets a fraction of a lamp-lit room's paths' worth of signal, so the same paths per
// texel leave its mean several times noisier, and a 3 % bias of a bake there is lost in the noise. After
// the first trace, the texels of every cell whose mean is noisier than the target are traced again with
// more paths from independent streams, and the two estimates merged per texel, until every cell meets the
// target or reaches the paths' cap.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/metrics/cell_metrics.h"
#include "radiosity/reference/reference_tracer.h"

namespace cpgi {

struct CellNoiseTarget {
  double meanNoise = 0.01;  ///< relative standard error of each cell's mean to reach; ≤ 0: off
  int maxSpp = 0;           ///< paths per texel at most, counting the first trace's
};

/// A traced reference and its per-texel path counts (they differ between cells once refined).
struct RefinedReference {
  ReferenceResult result;
  std::vector<int> paths;        ///< per atlas texel, 0 where not traced
  std::vector<CellNoise> cells;  ///< each cell's noise after the last pass
  int passes = 0;                ///< extra passes traced
  int baseSpp = 0;               ///< paths a texel of the first trace
};

/// Traces `ranks` (all valid texels when empty) with `params`, then again the texels of cells whose mean
/// noise exceeds `target` (texel `cell` indices into `names`, −1 for none; `weight` = area × sample
/// weight), each pass multiplying a noisy cell's paths by a power of two from its measured noise (noise
/// falls as 1/√paths). Deterministic: the same inputs give the same result.
RefinedReference traceToCellNoise(const Scene& scene, const LightmapAtlas& atlas,
                                  const ReferenceParams& params, std::span<const size_t> ranks,
                                  std::span<const float> cell, std::span<const float> weight,
                                  const std::vector<std::string>& names, const CellNoiseTarget& target,
                                  Context& ctx);

/// Merges `more` (traced with `morePaths` paths a texel, where > 0) into `into` (with `paths`), per
/// texel: the path-weighted mean and its standard error.
void mergeReference(ReferenceResult& into, std::vector<int>& paths, const ReferenceResult& more,
                    std::span<const int> morePaths);

}  // namespace cpgi
