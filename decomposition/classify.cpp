#include "decomposition/classify.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace cpgi::decomp {
namespace {

// Generalized winding number of the triangle soup about p (Jacobson et al. 2013): the signed solid angle
// over 4π, by Van Oosterom & Strackee's formula per triangle. +1 inside a closed outward-facing mesh,
// 0 outside it, fractional near open ones.
double windingNumber(const Scene& scene, const glm::dvec3& p) {
  double total = 0.0;
  for (const Triangle& t : scene.triangles) {
    const glm::dvec3 a = glm::dvec3(t.p[0]) - p, b = glm::dvec3(t.p[1]) - p, c = glm::dvec3(t.p[2]) - p;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = glm::dot(a, glm::cross(b, c));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    total += 2.0 * std::atan2(num, den);
  }
  return total / (4.0 * M_PI);
}

}  // namespace

SpaceGrid classifySpace(const Scene& scene, const SolidGrid& solid, const ClassifyParams& params, Context& ctx) {
  auto timer = ctx.time("classify");
  SpaceGrid out;
  const GridFrame& f = solid.frame;
  out.frame = f;
  constexpr uint8_t kUnset = 255;
  std::vector<uint8_t> cls(f.count(), kUnset);
  for (size_t i = 0; i < cls.size(); ++i)
    if (solid.solid[i]) cls[i] = uint8_t(Space::Solid);

  // Breadth-first fill from the voxels in `queue`: every unset face neighbour gets `value` and joins the
  // queue, which ends up holding the whole component.
  std::vector<size_t> queue;
  auto fill = [&](uint8_t value) {
    for (size_t head = 0; head < queue.size(); ++head) {
      const glm::ivec3 c = f.coord(queue[head]);
      for (const auto& d : kFaceNeighbours) {
        const glm::ivec3 n(c.x + d[0], c.y + d[1], c.z + d[2]);
        if (!f.contains(n)) continue;
        const size_t j = f.index(n);
        if (cls[j] != kUnset) continue;
        cls[j] = value;
        queue.push_back(j);
      }
    }
  };

  queue.clear();
  for (int z = 0; z < f.dims.z; ++z)
    for (int y = 0; y < f.dims.y; ++y)
      for (int x = 0; x < f.dims.x; ++x) {
        if (x > 0 && y > 0 && z > 0 && x < f.dims.x - 1 && y < f.dims.y - 1 && z < f.dims.z - 1) continue;
        const size_t i = f.index(x, y, z);
        if (cls[i] == kUnset) cls[i] = uint8_t(Space::Outside), queue.push_back(i);
      }
  fill(uint8_t(Space::Outside));

  // Components first, judged afterwards (in parallel: the winding number visits every triangle).
  const double minVoxels = params.minComponentVolume / f.voxelVolume();
  constexpr uint8_t kPending = 254;
  std::vector<std::vector<size_t>> components;
  for (size_t i = 0; i < cls.size(); ++i) {
    if (cls[i] != kUnset) continue;
    queue.clear();
    queue.push_back(i);
    cls[i] = kPending;
    fill(kPending);
    components.push_back(queue);
  }
  std::vector<char> isInside(components.size(), 0);
  tbb::parallel_for(size_t(0), components.size(), [&](size_t k) {
    const std::vector<size_t>& comp = components[k];
    if (double(comp.size()) < minVoxels) return;
    // By the winding of the nearest triangles: in front of them is a room, behind them the inside of an
    // open-backed shell.
    double front = 0.0, back = 0.0;
    for (size_t v : comp) {
      const int t = solid.nearestTriangle[v];
      if (t < 0) continue;
      const Triangle& tri = scene.triangles[size_t(t)];
      const float side = glm::dot(f.centre(v) - tri.centroid(), tri.geometricNormal());
      if (side > 0.0f) front += 1.0;
      else if (side < 0.0f) back += 1.0;
    }
    if (front <= back) return;
    // In front of its nearest faces yet inside a closed outward-facing solid (a box's inside seen through
    // a coincident floor face): void too. The median of three voxels spread through the component guards
    // against one unlucky sample; only components that passed the vote pay for the winding number.
    double w[3];
    for (int s = 0; s < 3; ++s) w[s] = windingNumber(scene, glm::dvec3(f.centre(comp[comp.size() * size_t(s) / 3])));
    std::sort(w, w + 3);
    isInside[k] = w[1] <= 0.5;
  });
  for (size_t k = 0; k < components.size(); ++k) {
    const Space s = isInside[k] ? Space::Inside : Space::Void;
    (isInside[k] ? out.insideComponents : out.voidComponents) += 1;
    for (size_t v : components[k]) cls[v] = uint8_t(s);
  }

  out.space.resize(cls.size());
  for (size_t i = 0; i < cls.size(); ++i) {
    out.space[i] = Space(cls[i]);
    switch (out.space[i]) {
      case Space::Solid: ++out.solidVoxels; break;
      case Space::Inside: ++out.insideVoxels; break;
      case Space::Outside: ++out.outsideVoxels; break;
      case Space::Void: ++out.voidVoxels; break;
    }
  }
  ctx.progress("classify", 1.0);
  return out;
}

}  // namespace cpgi::decomp
