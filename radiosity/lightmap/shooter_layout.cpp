#include "radiosity/lightmap/shooter_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cpgi {
namespace {

// Möller–Trumbore; the distance along `d` (unit) to the triangle, or +inf.
float hitDistance(const glm::vec3& o, const glm::vec3& d, const Triangle& t) {
  const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
  const glm::vec3 p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return std::numeric_limits<float>::infinity();
  const float inv = 1.0f / det;
  const glm::vec3 s = o - t.p[0];
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return std::numeric_limits<float>::infinity();
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return std::numeric_limits<float>::infinity();
  const float dist = glm::dot(e2, q) * inv;
  return dist > 0.0f ? dist : std::numeric_limits<float>::infinity();
}

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  void add(const glm::vec3& q) { lo = glm::min(lo, q), hi = glm::max(hi, q); }
  bool overlaps(const Box& o) const {
    return glm::all(glm::lessThanEqual(lo, o.hi)) && glm::all(glm::lessThanEqual(o.lo, hi));
  }
};

// The scene's triangle boxes binned in a uniform grid, so that a region asks only the triangles near it:
// every region scanning every triangle was 18 480 patches × 36 398 triangles on the furnished house, 17–22 s
// of one core, most of a two-level solve's set-up. A triangle spanning many cells (a floor) is kept in a
// list every query scans; a query wider than the triangles scans them all. Its answer is exactly the boxes
// that overlap, as the scan's.
class TriangleGrid {
 public:
  explicit TriangleGrid(const std::vector<Box>& boxes) : boxes_(boxes) {
    Box all;
    for (const Box& b : boxes) all.add(b.lo), all.add(b.hi);
    if (boxes.empty()) return;
    lo_ = all.lo;
    const glm::vec3 size =
        glm::max(all.hi - all.lo, glm::vec3(1e-3f * std::max(glm::length(all.hi - all.lo), 1e-3f)));
    // About two cells a triangle, at most kMostCells along an axis.
    const float cell = std::cbrt(size.x * size.y * size.z / (2.0f * float(boxes.size())));
    for (int k = 0; k < 3; ++k) {
      const float n = std::ceil(size[k] / cell);
      dims_[k] = n >= 1.0f ? int(std::min(n, float(kMostCells))) : 1;  // 1 where the sizes are not finite
    }
    inverse_ = glm::vec3(dims_) / size;
    std::vector<uint32_t> counts(cellCount() + 1, 0);
    for (uint32_t t = 0; t < boxes.size(); ++t)
      if (!forEachCell(boxes[t], [&](size_t c) { ++counts[c + 1]; })) large_.push_back(t);
    for (size_t c = 1; c < counts.size(); ++c) counts[c] += counts[c - 1];
    first_ = counts;
    members_.resize(counts.back());
    for (uint32_t t = 0; t < boxes.size(); ++t)
      forEachCell(boxes[t], [&](size_t c) { members_[counts[c]++] = t; });
  }

  // Calls `visit` once for every triangle whose box overlaps `query` (in no set order).
  template <typename Visit>
  void near(const Box& query, std::vector<uint32_t>& stamp, uint32_t mark, Visit&& visit) const {
    const glm::ivec3 a = cellOf(query.lo), b = cellOf(query.hi);
    const size_t span = size_t(b.x - a.x + 1) * size_t(b.y - a.y + 1) * size_t(b.z - a.z + 1);
    if (span > boxes_.size() / 4) {  // as many cells as triangles: the scan is cheaper
      for (uint32_t t = 0; t < boxes_.size(); ++t)
        if (boxes_[t].overlaps(query)) visit(t);
      return;
    }
    auto test = [&](uint32_t t) {
      if (stamp[t] == mark) return;
      stamp[t] = mark;
      if (boxes_[t].overlaps(query)) visit(t);
    };
    for (uint32_t t : large_) test(t);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) {
          const size_t c = index(x, y, z);
          for (uint32_t k = first_[c]; k < first_[c + 1]; ++k) test(members_[k]);
        }
  }

 private:
  static constexpr int kMostCells = 256;
  static constexpr size_t kMostCellsATriangle = 64;  // past it, the triangle joins large_
  size_t cellCount() const { return size_t(dims_.x) * size_t(dims_.y) * size_t(dims_.z); }
  size_t index(int x, int y, int z) const {
    return (size_t(z) * size_t(dims_.y) + size_t(y)) * size_t(dims_.x) + size_t(x);
  }
  glm::ivec3 cellOf(const glm::vec3& q) const {
    const glm::vec3 f = (q - lo_) * inverse_;
    glm::ivec3 c(0);
    for (int k = 0; k < 3; ++k)  // outside the grid (or not a number): its edge cell
      c[k] = f[k] >= 0.0f ? (f[k] < float(dims_[k]) ? int(f[k]) : dims_[k] - 1) : 0;
    return c;
  }
  // Calls `cell` for each cell `box` overlaps; none, and false, for a box over more than
  // kMostCellsATriangle cells (a large triangle, scanned by every query).
  template <typename Cell>
  bool forEachCell(const Box& box, Cell&& cell) const {
    const glm::ivec3 a = cellOf(box.lo), b = cellOf(box.hi);
    const size_t span = size_t(b.x - a.x + 1) * size_t(b.y - a.y + 1) * size_t(b.z - a.z + 1);
    if (span > kMostCellsATriangle) return false;
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) cell(index(x, y, z));
    return true;
  }

  const std::vector<Box>& boxes_;
  glm::vec3 lo_{0.0f}, inverse_{1.0f};
  glm::ivec3 dims_{1};
  std::vector<uint32_t> first_, members_, large_;
};

// One patch's layout: its regions, and in each the most open of its candidate eyes.
ShooterLayout layoutPatch(const Scene& scene, const LightmapAtlas& atlas, const LayoutParams& params,
                          const std::vector<Box>& boxes, const TriangleGrid& grid, size_t pi,
                          std::vector<uint32_t>& stamp, uint32_t& mark) {
  const Patch& p = atlas.patches[pi];
  std::vector<int32_t> own = p.triangles;  // the patch's own triangles never block its probes
  std::sort(own.begin(), own.end());
  ShooterLayout l;
  l.normal = p.normal;
  const glm::vec3 u = p.texelU - glm::dot(p.texelU, p.normal) * p.normal;
  l.tangent = glm::normalize(glm::length(u) > 0.0f ? u : glm::cross(glm::vec3(0.6f, 0.8f, 0.0f), p.normal));
  l.bitangent = glm::cross(l.normal, l.tangent);
  l.texelRadius = 0.5f * std::max(glm::length(p.texelU + p.texelV), glm::length(p.texelU - p.texelV));
  const bool opening = pi < params.openings.size() && params.openings[pi] != 0;
  auto regionsAlong = [&](float length, int texels) {
    if (opening) return std::clamp(params.openingRegions, 1, std::max(texels, 1));
    const int n = static_cast<int>(std::ceil(length / params.regionSize - 1e-3f));
    return std::clamp(n, 1, std::min(params.maxRegions, texels));
  };
  l.regions = {regionsAlong(glm::length(p.texelU) * p.w, p.w),
               regionsAlong(glm::length(p.texelV) * p.h, p.h)};
  // Probe directions: the normal and four 60° tilts.
  const float c = 0.5f, s = 0.8660254f;
  const glm::vec3 rays[5] = {l.normal, c * l.normal + s * l.tangent, c * l.normal - s * l.tangent,
                             c * l.normal + s * l.bitangent, c * l.normal - s * l.bitangent};
  std::vector<uint32_t> near;
  for (int ry = 0; ry < l.regions.y; ++ry)
    for (int rx = 0; rx < l.regions.x; ++rx) {
      const int x0 = p.w * rx / l.regions.x, x1 = p.w * (rx + 1) / l.regions.x;
      const int y0 = p.h * ry / l.regions.y, y1 = p.h * (ry + 1) / l.regions.y;
      l.rects.push_back({x0, y0, x1, y1});
      auto texelAt = [&](int x, int y) { return size_t(p.y + y) * atlas.width + p.x + x; };
      // Candidates: the centre texel first, then a 3×3 grid; only valid texels of this patch.
      std::vector<glm::vec3> candidates;
      auto consider = [&](int x, int y) {
        const size_t t = texelAt(std::clamp(x, x0, x1 - 1), std::clamp(y, y0, y1 - 1));
        if (atlas.patch[t] == int(pi)) candidates.push_back(atlas.position[t]);
      };
      consider((x0 + x1) / 2, (y0 + y1) / 2);
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          consider(x0 + (x1 - x0) * (2 * i + 1) / 6, y0 + (y1 - y0) * (2 * j + 1) / 6);
      if (candidates.empty()) {  // a loose triangle's region without valid texels: never shoots
        l.eyes.push_back(p.origin);
        continue;
      }
      // The triangles that could block a probe: near the region, in front of it.
      const float reach =
          std::max(glm::length(p.texelU) * float(x1 - x0), glm::length(p.texelV) * float(y1 - y0));
      Box region;
      for (const glm::vec3& q : candidates) region.add(q), region.add(q + reach * l.normal);
      region.lo -= glm::vec3(reach), region.hi += glm::vec3(reach);
      near.clear();
      grid.near(region, stamp, ++mark, [&](uint32_t t) {
        if (!std::binary_search(own.begin(), own.end(), int32_t(t))) near.push_back(t);
      });
      float bestScore = -1.0f;
      glm::vec3 best = candidates.front();
      for (const glm::vec3& q : candidates) {
        const glm::vec3 origin = q + 1e-4f * reach * l.normal;
        float score = reach;  // the nearest hit over every near triangle: the same in any order
        for (uint32_t t : near) {
          // A triangle whose box lies beyond the nearest hit so far cannot be nearer along any ray.
          const glm::vec3 gap =
              glm::max(glm::max(boxes[t].lo - origin, origin - boxes[t].hi), glm::vec3(0.0f));
          if (glm::dot(gap, gap) >= score * score) continue;
          for (const glm::vec3& d : rays) score = std::min(score, hitDistance(origin, d, scene.triangles[t]));
        }
        if (score > bestScore * 1.0001f)
          bestScore = score, best = q;  // strictly better: keeps the centre on ties
      }
      l.eyes.push_back(best);
    }
  return l;
}

}  // namespace

std::vector<ShooterLayout> layoutShooters(const Scene& scene, const LightmapAtlas& atlas,
                                          const LayoutParams& params,
                                          std::chrono::steady_clock::time_point deadline) {
  std::vector<Box> triangleBoxes(scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i)
    for (const glm::vec3& q : scene.triangles[i].p) triangleBoxes[i].add(q);
  const TriangleGrid grid(triangleBoxes);

  // Batches of patches between deadline checks; each patch's layout on its own, so any order gives the same.
  constexpr size_t kBatch = 256, kGrain = 16;
  std::vector<ShooterLayout> layouts(atlas.patches.size());
  for (size_t begin = 0; begin < layouts.size(); begin += kBatch) {
    if (std::chrono::steady_clock::now() >= deadline) {
      layouts.resize(begin);
      break;
    }
    const size_t end = std::min(layouts.size(), begin + kBatch);
    tbb::parallel_for(
        tbb::blocked_range<size_t>(begin, end, kGrain), [&](const tbb::blocked_range<size_t>& r) {
          std::vector<uint32_t> stamp(scene.triangles.size(), 0);
          uint32_t mark = 0;
          for (size_t pi = r.begin(); pi < r.end(); ++pi)
            layouts[pi] = layoutPatch(scene, atlas, params, triangleBoxes, grid, pi, stamp, mark);
        });
  }
  return layouts;
}

}  // namespace cpgi
