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
  // Classes are written straight into the output; two values past Space's mark what is not judged yet.
  constexpr Space kUnset = Space(255), kPending = Space(254);
  std::vector<Space>& cls = out.space;
  cls.resize(f.count());
  for (size_t i = 0; i < cls.size(); ++i) cls[i] = solid.solid[i] ? Space::Solid : kUnset;

  // Calls visit(j) for every unset face neighbour j of voxel i, which may lie on the grid's border.
  auto forUnsetNeighboursOfBorder = [&](size_t i, auto&& visit) {
    const glm::ivec3 c = f.coord(i);
    for (const auto& d : kFaceNeighbours) {
      const glm::ivec3 n(c.x + d[0], c.y + d[1], c.z + d[2]);
      if (!f.contains(n)) continue;
      const size_t j = f.index(n);
      if (cls[j] == kUnset) visit(j);
    }
  };
  // The same for a voxel off the border, by index offsets. Once the border is classified (solid or
  // outside, below), every unset voxel is off it.
  const ptrdiff_t sy = f.dims.x, sz = ptrdiff_t(f.dims.x) * f.dims.y;
  const ptrdiff_t offsets[6] = {-1, 1, -sy, sy, -sz, sz};
  auto forUnsetNeighbours = [&](size_t i, auto&& visit) {
    for (ptrdiff_t o : offsets) {
      const size_t j = size_t(ptrdiff_t(i) + o);
      if (cls[j] == kUnset) visit(j);
    }
  };

  // The outside, front by front from the grid's border: only the front is held, not the whole outside.
  std::vector<size_t> front, next;
  for (int z = 0; z < f.dims.z; ++z)
    for (int y = 0; y < f.dims.y; ++y)
      for (int x = 0; x < f.dims.x; ++x) {
        if (x > 0 && y > 0 && z > 0 && x < f.dims.x - 1 && y < f.dims.y - 1 && z < f.dims.z - 1) continue;
        const size_t i = f.index(x, y, z);
        if (cls[i] == kUnset) cls[i] = Space::Outside, front.push_back(i);
      }
  auto toOutside = [&](size_t j) { cls[j] = Space::Outside, next.push_back(j); };
  for (size_t i : front) forUnsetNeighboursOfBorder(i, toOutside);
  std::swap(front, next);
  while (!front.empty()) {
    next.clear();
    for (size_t i : front) forUnsetNeighbours(i, toOutside);
    std::swap(front, next);
  }

  // Components first, judged afterwards (in parallel: the winding number visits every triangle).
  const double minVoxels = params.minComponentVolume / f.voxelVolume();
  std::vector<std::vector<size_t>> components;
  for (size_t i = 0; i < cls.size(); ++i) {
    if (cls[i] != kUnset) continue;
    // Breadth-first: the component ends up whole in its own list.
    std::vector<size_t>& component = components.emplace_back(1, i);
    cls[i] = kPending;
    for (size_t head = 0; head < component.size(); ++head)
      forUnsetNeighbours(component[head], [&](size_t j) { cls[j] = kPending, component.push_back(j); });
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
    for (size_t v : components[k]) cls[v] = s;
  }

  for (const Space s : cls) {
    switch (s) {
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
