#include "radiosity/reference/noisy_cells.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace cpgi {

void mergeReference(ReferenceResult& into, std::vector<int>& paths, const ReferenceResult& more,
                    std::span<const int> morePaths) {
  for (size_t i = 0; i < paths.size(); ++i) {
    const double n2 = morePaths[i];
    if (!(n2 > 0.0)) continue;
    const double n1 = paths[i], n = n1 + n2;
    // Both hold E + mean, so the path-weighted mean of the two is E + the mean of all paths.
    into.radiosity[i] =
        glm::vec3((n1 * glm::dvec3(into.radiosity[i]) + n2 * glm::dvec3(more.radiosity[i])) / n);
    const glm::dvec3 s1(into.standardError[i]), s2(more.standardError[i]);
    into.standardError[i] = glm::vec3(glm::sqrt(n1 * n1 * s1 * s1 + n2 * n2 * s2 * s2) / n);
    paths[i] = int(n);
  }
  into.rays += more.rays;
}

namespace {

std::vector<float> sigmaNorm(const ReferenceResult& r) {
  std::vector<float> s(r.standardError.size());
  for (size_t i = 0; i < s.size(); ++i) s[i] = glm::length(r.standardError[i]);
  return s;
}

// The smallest power-of-two factor on a cell's paths expected to bring its mean noise to the target
// (with a 10 % margin), within the cap.
int pathFactor(double noise, double target, int paths, int maxSpp) {
  const double wanted = 1.1 * (noise / target) * (noise / target);
  int factor = 2;
  while (factor < wanted && 2 * factor * paths <= maxSpp) factor *= 2;
  return factor * paths <= maxSpp ? factor : 1;
}

}  // namespace

RefinedReference traceToCellNoise(const Scene& scene, const LightmapAtlas& atlas,
                                  const ReferenceParams& params, std::span<const size_t> ranks,
                                  std::span<const float> cell, std::span<const float> weight,
                                  const std::vector<std::string>& names, const CellNoiseTarget& target,
                                  Context& ctx) {
  RefinedReference out;
  out.result = traceReference(scene, atlas, params, ctx, ranks);
  out.baseSpp = out.result.spp;
  out.paths.assign(atlas.texelCount(), 0);
  // The traced texels and their ranks among the valid ones (the streams a retrace must draw from).
  std::vector<size_t> tracedTexel, tracedRank;
  {
    size_t rank = 0, next = 0;
    for (size_t i = 0; i < atlas.texelCount(); ++i) {
      if (atlas.patch[i] < 0) continue;
      if (ranks.empty() || (next < ranks.size() && ranks[next] == rank)) {
        tracedTexel.push_back(i), tracedRank.push_back(rank), out.paths[i] = out.result.spp;
        if (!ranks.empty()) ++next;
      }
      ++rank;
    }
  }
  const int maxSpp = target.maxSpp > 0 ? target.maxSpp : 16 * out.result.spp;
  for (;;) {
    out.cells = referenceCellNoise(out.result.radiosity, sigmaNorm(out.result), weight, cell, names);
    if (!(target.meanNoise > 0.0)) return out;
    // Cells above the target, grouped by the paths to add (their paths so far × (factor − 1)): one trace
    // per group.
    std::vector<int> cellPaths(names.size(), 0), extraOfCell(names.size(), 0);
    auto cellOf = [&](size_t texel) -> long {
      const float c = cell[texel];
      return std::isfinite(c) && c >= 0.0f && size_t(c) < names.size() ? long(c) : -1;
    };
    for (size_t t : tracedTexel)
      if (const long c = cellOf(t); c >= 0)
        cellPaths[size_t(c)] = std::max(cellPaths[size_t(c)], out.paths[t]);
    for (size_t c = 0; c < names.size(); ++c)
      if (out.cells[c].meanNoise > target.meanNoise)
        extraOfCell[c] =
            (pathFactor(out.cells[c].meanNoise, target.meanNoise, cellPaths[c], maxSpp) - 1) * cellPaths[c];
    std::map<int, std::vector<size_t>> groups;  // paths to add → ranks (increasing) to retrace
    for (size_t k = 0; k < tracedTexel.size(); ++k)
      if (const long c = cellOf(tracedTexel[k]);
          c >= 0 && extraOfCell[size_t(c)] > 0 && weight[tracedTexel[k]] > 0.0f)
        groups[extraOfCell[size_t(c)]].push_back(tracedRank[k]);
    if (groups.empty()) return out;
    ++out.passes;
    for (const auto& [extraPaths, group] : groups) {
      ReferenceParams more = params;
      // Independent of every earlier pass: each texel's stream stays its rank, the seed moves on.
      more.seed = params.seed + 0x9E3779B97F4A7C15ull * uint64_t(out.passes) + uint64_t(extraPaths);
      more.spp = extraPaths;
      const ReferenceResult extra = traceReference(scene, atlas, more, ctx, group);
      std::vector<int> morePaths(atlas.texelCount(), 0);
      for (size_t k = 0; k < tracedTexel.size(); ++k)
        if (std::binary_search(group.begin(), group.end(), tracedRank[k]))
          morePaths[tracedTexel[k]] = extra.spp;
      mergeReference(out.result, out.paths, extra, morePaths);
    }
    out.result.spp = *std::max_element(out.paths.begin(), out.paths.end());
  }
}

}  // namespace cpgi
