#include "radiosity/lightmap/seam_gutters.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <unordered_map>

#include "radiosity/lightmap/atlas_resample.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {
namespace {

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()}, hi{std::numeric_limits<float>::lowest()};
  void add(const glm::vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  bool overlaps(const Box& o, float slack) const {
    return glm::all(glm::lessThanEqual(lo - slack, o.hi)) && glm::all(glm::lessThanEqual(o.lo - slack, hi));
  }
};

// One surface, as radiosity/lightmap/light_density.h's evenOverSurfaces has it: a material, normals
// within 0.5°, planes 1 mm apart. Across anything else the light may step, and the gutter keeps its own.
bool sameSurface(const Patch& a, const Patch& b) {
  return a.material == b.material && glm::dot(a.normal, b.normal) >= 0.99996f &&
         std::abs(glm::dot(b.origin - a.origin, a.normal)) <= 1e-3f;
}

// Whether chart point `g` of patch `p` lies on its surface: its rectangle, or a loose triangle's half of
// its square (texelU and texelV run along the triangle's two edges from its origin).
bool onChart(const Patch& p, glm::vec2 g) {
  const float slack = 1e-3f;
  if (g.x < -slack || g.y < -slack) return false;
  if (p.quad >= 0) return g.x <= float(p.w) + slack && g.y <= float(p.h) + slack;
  return g.x + g.y <= float(p.w) + slack;
}

// Charts by the cells of a uniform grid over the scene that their surfaces touch, to find a chart's
// neighbours without comparing every pair.
class ChartGrid {
 public:
  explicit ChartGrid(const std::vector<Box>& boxes) {
    Box all;
    for (const Box& b : boxes) all.add(b.lo), all.add(b.hi);
    lo_ = all.lo;
    const glm::vec3 extent = glm::max(all.hi - all.lo, glm::vec3(1e-3f));
    // About 64 cells along the longest side: a chart meets a few, a large floor a few hundred.
    cell_ = std::max({extent.x, extent.y, extent.z}) / 64.0f;
    for (size_t c = 0; c < boxes.size(); ++c)
      forCells(boxes[c], [&](int64_t key) { cells_[key].push_back(int32_t(c)); });
  }
  template <class F>
  void forCells(const Box& b, F&& f) const {
    const glm::ivec3 a = cellOf(b.lo), z = cellOf(b.hi);
    for (int x = a.x; x <= z.x; ++x)
      for (int y = a.y; y <= z.y; ++y)
        for (int k = a.z; k <= z.z; ++k) f((int64_t(x) << 42) | (int64_t(y) << 21) | int64_t(k));
  }
  /// The grid cells box `b` spans (forCells' calls).
  double cellCount(const Box& b) const {
    const glm::dvec3 span = glm::dvec3(cellOf(b.hi) - cellOf(b.lo)) + 1.0;
    return span.x * span.y * span.z;
  }
  const std::vector<int32_t>* at(int64_t key) const {
    const auto it = cells_.find(key);
    return it == cells_.end() ? nullptr : &it->second;
  }

 private:
  glm::ivec3 cellOf(const glm::vec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - lo_) / cell_)), glm::ivec3(0), glm::ivec3((1 << 20) - 1));
  }
  glm::vec3 lo_{0.0f};
  float cell_ = 1.0f;
  std::unordered_map<int64_t, std::vector<int32_t>> cells_;
};

// The point of p's surface nearest chart point g (p's own coordinates).
glm::vec3 nearestOnChart(const Patch& p, glm::vec2 g) {
  g = glm::clamp(g, glm::vec2(0.0f), glm::vec2(float(p.w), float(p.h)));
  if (p.quad < 0 && g.x + g.y > float(p.w)) {  // beyond a loose triangle's long edge: onto it
    g -= 0.5f * (g.x + g.y - float(p.w));
    g = glm::max(g, glm::vec2(0.0f));
  }
  return p.origin + g.x * p.texelU + g.y * p.texelV;
}

// The world point of chart texel (i, j) of p (outside the chart too: its plane goes on).
glm::vec3 texelPoint(const Patch& p, int i, int j) {
  return p.origin + (float(i) + 0.5f) * p.texelU + (float(j) + 0.5f) * p.texelV;
}

}  // namespace

std::vector<GutterTap> seamGutters(const LightmapAtlas& atlas, const Scene& scene, int padding,
                                   std::chrono::steady_clock::time_point deadline) {
  const size_t charts = atlas.patches.size();
  std::vector<Box> surface(charts), reach(charts);
  for (size_t c = 0; c < charts; ++c) {
    const Patch& p = atlas.patches[c];
    for (int32_t t : p.triangles)
      for (const glm::vec3& v : scene.triangles[size_t(t)].p) surface[c].add(v);
    // The chart's texels with their gutter, in the chart's plane.
    for (int j : {-padding, p.h + padding})
      for (int i : {-padding, p.w + padding})
        reach[c].add(p.origin + float(i) * p.texelU + float(j) * p.texelV);
  }
  const ChartGrid grid(surface);
  std::vector<GutterTap> taps;
  // Each tap's way from its chart's edge to its point, a millimetre or so above the surface: a wall
  // standing on the seam (two rooms' floors meeting under a partition of no thickness) hides the
  // neighbour's light, which must not leak in through the gutter.
  std::vector<RayScene::Segment> ways;
  std::unique_ptr<RayScene> rays;
  float lift = 0.0f;
  std::vector<int32_t> seen(charts, -1), near;
  for (size_t c = 0; c < charts; ++c) {
    if (std::chrono::steady_clock::now() >= deadline)
      throw AtlasLayoutStopped(atlas.texelCount(), atlas.texelCount());
    const Patch& p = atlas.patches[c];
    near.clear();
    auto consider = [&](int32_t q) {
      if (seen[size_t(q)] != int32_t(c) && q != int32_t(c)) {
        seen[size_t(q)] = int32_t(c);
        if (surface[size_t(q)].overlaps(reach[c], 1e-3f) && sameSurface(p, atlas.patches[size_t(q)]))
          near.push_back(q);
      }
    };
    // A sliver's chart reaches far along its plane at a few texels a quad: its box can span the whole
    // grid, whose cells then cost more to visit than every chart (2 000 slivers of a fan: 100 s).
    if (grid.cellCount(reach[c]) > double(charts)) {
      for (size_t q = 0; q < charts; ++q) consider(int32_t(q));
    } else {
      grid.forCells(reach[c], [&](int64_t key) {
        if (const std::vector<int32_t>* in = grid.at(key))
          for (int32_t q : *in) consider(q);
      });
    }
    if (near.empty()) continue;
    if (!rays) {
      rays = std::make_unique<RayScene>(scene);
      lift = 1e-4f * rays->diagonal();
    }
    for (int j = -padding; j < p.h + padding; ++j)
      for (int i = -padding; i < p.w + padding; ++i) {
        const int x = p.x + i, y = p.y + j;
        if (x < 0 || y < 0 || x >= atlas.width || y >= atlas.height) continue;
        const size_t t = size_t(y) * size_t(atlas.width) + size_t(x);
        if (atlas.patch[t] >= 0) continue;
        const glm::vec3 point = texelPoint(p, i, j);
        for (int32_t q : near) {
          const glm::vec2 g = chartCoordinates(atlas.patches[size_t(q)], point);
          if (!onChart(atlas.patches[size_t(q)], g)) continue;
          const BilinearTaps from = chartTaps(atlas, q, g);
          if (from.count == 0) break;
          const glm::vec3 start = nearestOnChart(p, chartCoordinates(p, point)) + lift * p.normal;
          const glm::vec3 way = point + lift * p.normal - start;
          const float length = glm::length(way);
          taps.push_back({t, from});
          ways.push_back({start, length, length > 0.0f ? way / length : p.normal});
          break;
        }
      }
  }
  if (taps.empty()) return taps;
  std::vector<uint8_t> hidden(ways.size(), 0);
  rays->occluded(ways, hidden);
  size_t kept = 0;
  for (size_t k = 0; k < taps.size(); ++k)
    if (!hidden[k]) taps[kept++] = taps[k];
  taps.resize(kept);
  return taps;
}

}  // namespace cpgi
