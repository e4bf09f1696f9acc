#include "radiosity/cpu/shooter_clusters.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace cpgi {
namespace {

struct ChartDisk {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

// The disk round a patch's chart (its texel rectangle, valid or not).
ChartDisk chartDisk(const Patch& p) {
  const glm::vec3 u = float(p.w) * p.texelU, v = float(p.h) * p.texelV;
  return {p.origin + 0.5f * (u + v), 0.5f * std::max(glm::length(u + v), glm::length(u - v))};
}

// The box round a patch's chart.
std::pair<glm::vec3, glm::vec3> chartBox(const Patch& p) {
  const glm::vec3 u = float(p.w) * p.texelU, v = float(p.h) * p.texelV;
  const glm::vec3 a = p.origin, b = a + u, c = a + v, d = a + u + v;
  return {glm::min(glm::min(a, b), glm::min(c, d)), glm::max(glm::max(a, b), glm::max(c, d))};
}

// A point's place along a 3D Z-order curve of unit cells (21 bits an axis, offset to stay positive).
uint64_t zOrder3(const glm::vec3& at) {
  auto spread = [](uint64_t v) {
    v &= 0x1FFFFFu;
    v = (v | (v << 32)) & 0x1F00000000FFFFull;
    v = (v | (v << 16)) & 0x1F0000FF0000FFull;
    v = (v | (v << 8)) & 0x100F00F00F00F00Full;
    v = (v | (v << 4)) & 0x10C30C30C30C30C3ull;
    return (v | (v << 2)) & 0x1249249249249249ull;
  };
  const glm::vec3 c = glm::clamp(glm::floor(at) + 1048576.0f, glm::vec3(0.0f), glm::vec3(2097151.0f));
  return spread(uint64_t(c.x)) | (spread(uint64_t(c.y)) << 1) | (spread(uint64_t(c.z)) << 2);
}

}  // namespace

ShooterClusters clusterShooters(const LightmapAtlas& atlas, const ShooterClusterParams& params,
                                std::span<const uint8_t> exclude) {
  const size_t n = atlas.patches.size();
  ShooterClusters out;
  out.clusterOf.assign(n, -1);
  std::vector<ChartDisk> disks(n);
  // Candidates by plane: the normal to 1/64 and the plane's offset to the gap. Two patches on either side
  // of a step land apart and shoot alone, which costs shots, never light.
  using PlaneKey = std::tuple<int, int, int, int64_t>;
  std::map<PlaneKey, std::vector<int32_t>> planes;
  for (size_t p = 0; p < n; ++p) {
    const Patch& patch = atlas.patches[p];
    disks[p] = chartDisk(patch);
    const bool excluded = p < exclude.size() && exclude[p] != 0;
    if (excluded || !(patch.area > 0.0f) || !(disks[p].radius <= params.radius)) continue;
    const glm::ivec3 nq = glm::ivec3(glm::round(patch.normal * 64.0f));
    const double offset = double(glm::dot(patch.normal, disks[p].centre));
    planes[{nq.x, nq.y, nq.z, int64_t(std::floor(offset / double(params.planeGap)))}].push_back(int32_t(p));
  }
  for (auto& [key, patches] : planes) {
    // Seeds in Z-order of where the patches are, at the radius's scale, so that each cluster takes a
    // compact block of its plane's patches (in index order, a 0.25 m tile's cluster was two tiles).
    std::vector<std::pair<uint64_t, int32_t>> order;
    for (int32_t p : patches) order.push_back({zOrder3(disks[size_t(p)].centre / params.radius), p});
    std::sort(order.begin(), order.end());
    for (size_t i = 0; i < order.size(); ++i) {
      const int32_t seed = order[i].second;
      if (out.clusterOf[size_t(seed)] >= 0) continue;
      const int32_t cluster = int32_t(out.members.size());
      out.members.push_back({seed});
      out.clusterOf[size_t(seed)] = cluster;
      const Patch& s = atlas.patches[size_t(seed)];
      glm::vec3 lo = chartBox(atlas.patches[size_t(seed)]).first,
                hi = chartBox(atlas.patches[size_t(seed)]).second;
      for (size_t j = i + 1; j < order.size(); ++j) {
        const int32_t q = order[j].second;
        if (out.clusterOf[size_t(q)] >= 0) continue;
        const Patch& patch = atlas.patches[size_t(q)];
        const auto [qlo, qhi] = chartBox(patch);
        const glm::vec3 ulo = glm::min(lo, qlo), uhi = glm::max(hi, qhi);
        if (glm::dot(s.normal, patch.normal) < params.normalCosine ||
            std::abs(glm::dot(s.normal, disks[size_t(q)].centre - disks[size_t(seed)].centre)) >
                params.planeGap ||
            0.5f * glm::length(uhi - ulo) > params.radius)
          continue;
        out.members.back().push_back(q);
        out.clusterOf[size_t(q)] = cluster;
        lo = ulo, hi = uhi;
      }
    }
  }
  for (size_t p = 0; p < n; ++p)
    if (out.clusterOf[p] < 0) {
      out.clusterOf[p] = int32_t(out.members.size());
      out.members.push_back({int32_t(p)});
    }
  for (auto& m : out.members) std::sort(m.begin(), m.end());
  return out;
}

}  // namespace cpgi
