#include "decomposition/classify.h"

#include <deque>

namespace cpgi::decomp {

SpaceGrid classifySpace(const Scene& scene, const SolidGrid& solid, const ClassifyParams& params, Context& ctx) {
  auto timer = ctx.time("classify");
  SpaceGrid out;
  const GridFrame& f = solid.frame;
  out.frame = f;
  constexpr uint8_t kUnset = 255;
  std::vector<uint8_t> cls(f.count(), kUnset);
  for (size_t i = 0; i < cls.size(); ++i)
    if (solid.solid[i]) cls[i] = uint8_t(Space::Solid);

  // Breadth-first fill of unset voxels from `seeds`, calling visit(i) on each; returns the voxel list.
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

  const double minVoxels = params.minComponentVolume / f.voxelVolume();
  constexpr uint8_t kPending = 254;
  for (size_t i = 0; i < cls.size(); ++i) {
    if (cls[i] != kUnset) continue;
    queue.clear();
    queue.push_back(i);
    cls[i] = kPending;
    fill(kPending);
    // Vote by the nearest triangle's winding; each near-surface voxel counts once.
    double front = 0.0, back = 0.0;
    for (size_t v : queue) {
      const int t = solid.nearestTriangle[v];
      if (t < 0) continue;
      const Triangle& tri = scene.triangles[size_t(t)];
      const glm::vec3 n = tri.geometricNormal();
      const float side = glm::dot(f.centre(v) - tri.centroid(), n);
      if (side > 0.0f) front += 1.0;
      else if (side < 0.0f) back += 1.0;
    }
    const bool inside = front > back && double(queue.size()) >= minVoxels;
    const Space s = inside ? Space::Inside : Space::Void;
    (inside ? out.insideComponents : out.voidComponents) += 1;
    for (size_t v : queue) cls[v] = uint8_t(s);
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
