#include "decomposition/passages.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/ray_triangle.h"

namespace cpgi::decomp {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool inside(const Bounds& b, const glm::vec3& p) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z;
}

// The point a share `at` of the way through the floors' cumulative area: in its triangle, the rest of the
// area along one side and the k-th of a golden-ratio sequence along the other (folded into the triangle),
// so that a hall's floor of two triangles is sampled all over, not at two centroids.
glm::vec3 floorPoint(const Scene& scene, const std::vector<uint32_t>& floors,
                     const std::vector<double>& cumulative, double at, int k) {
  const double total = cumulative.back();
  const size_t f = std::min(
      size_t(std::lower_bound(cumulative.begin(), cumulative.end(), at * total) - cumulative.begin()),
      floors.size() - 1);
  const double before = f == 0 ? 0.0 : cumulative[f - 1];
  float u = float(std::clamp((at * total - before) / std::max(cumulative[f] - before, 1e-30), 0.0, 1.0));
  float v = float(std::fmod(0.5 + 0.6180339887 * k, 1.0));
  if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
  const Triangle& t = scene.triangles[floors[f]];
  return t.p[0] + u * (t.p[1] - t.p[0]) + v * (t.p[2] - t.p[0]);
}

}  // namespace

PassageWidths measurePassages(const Scene& scene, const Bounds& box, const PassageParams& params) {
  PassageWidths out;
  std::vector<uint32_t> floors;
  std::vector<double> cumulative;
  double total = 0.0;
  const float cosFloor = std::cos(25.0f * 3.14159265f / 180.0f);
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const Triangle& tri = scene.triangles[t];
    if (tri.geometricNormal().y > cosFloor && inside(box, tri.centroid())) {
      total += tri.area();
      floors.push_back(t), cumulative.push_back(total);
    }
  }
  if (floors.empty() || !(total > 0.0) || params.samples <= 0) return out;
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const glm::vec3 directions[4] = {
      {1, 0, 0}, {0, 0, 1}, {0.70710678f, 0, 0.70710678f}, {0.70710678f, 0, -0.70710678f}};
  std::vector<float> widths;
  std::vector<uint32_t> spanning;  // the triangles across the ray's height: the only ones it can meet
  for (int k = 0; k < params.samples; ++k) {
    const glm::vec3 o = floorPoint(scene, floors, cumulative, (k + 0.5) / params.samples, k) +
                        glm::vec3(0.0f, params.height, 0.0f);
    spanning.clear();
    float ceiling = kInfinity;
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
      const Triangle& tri = scene.triangles[t];
      const float lo = std::min({tri.p[0].y, tri.p[1].y, tri.p[2].y});
      const float hi = std::max({tri.p[0].y, tri.p[1].y, tri.p[2].y});
      if (lo <= o.y && hi >= o.y) spanning.push_back(t);
      if (hi > o.y && lo < o.y + params.minClearance)
        ceiling = std::min(ceiling, rayTriangleDistance(o, up, tri));
    }
    if (ceiling + params.height < params.minClearance) continue;  // under a table, a low ledge
    float narrowest = kInfinity;
    for (const glm::vec3& d : directions) {
      float ahead = kInfinity, behind = kInfinity;
      for (uint32_t t : spanning) {
        ahead = std::min(ahead, rayTriangleDistance(o, d, scene.triangles[t]));
        behind = std::min(behind, rayTriangleDistance(o, -d, scene.triangles[t]));
      }
      narrowest = std::min(narrowest, ahead + behind);
    }
    if (std::isfinite(narrowest)) widths.push_back(narrowest);
  }
  out.measured = int(widths.size());
  if (out.measured < params.samples / 10) return out;
  const auto q = widths.begin() + std::ptrdiff_t(params.quantile * double(widths.size() - 1));
  std::nth_element(widths.begin(), q, widths.end());
  out.narrow = *q;
  return out;
}

}  // namespace cpgi::decomp
