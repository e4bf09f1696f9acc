#include "decomposition/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "decomposition/classify.h"
#include "decomposition/volume_cells.h"
#include "decomposition/voxelize.h"

namespace cpgi::decomp {
namespace {

double choose2(double n) {
  return 0.5 * n * (n - 1.0);
}

}  // namespace

VoxelSpace buildVoxelSpace(const Scene& scene, double voxelSize, Context& ctx, uint64_t memoryLimit,
                           const Bounds& extent) {
  VoxelizeParams vp;
  vp.extent = extent;
  vp.voxelSize = voxelSize;
  vp.memoryLimit = memoryLimit;
  const SolidGrid solid = voxelize(scene, vp, ctx);
  SpaceGrid space = classifySpace(scene, solid, {}, ctx);
  return {solid.frame, std::move(space.space)};
}

std::vector<int32_t> labelsFromCells(const Scene& scene, const CellGraph& graph, const GridFrame& f,
                                     const std::vector<Space>& space) {
  std::vector<int32_t> label(f.count(), -1);
  const float h = float(f.voxel);
  std::vector<char> blocked(f.count(), 0);
  // A graph with an "outside" cell models the exterior and has portals on the openings, so its cells grow
  // through all empty space (the rooms of an open building are reachable from its bounds: enclosed space
  // alone is a few litres of it); without one, only through enclosed space, which a room's facade
  // triangles would otherwise flood from outside.
  const bool modelsOutside = graph.findCell("outside") >= 0;
  for (size_t i = 0; i < space.size(); ++i)
    blocked[i] = !(space[i] == Space::Inside || (modelsOutside && space[i] == Space::Outside));

  // Portal quads as walls half a voxel thick.
  std::vector<char> portalVoxel(f.count(), 0);
  for (const PortalQuad& q : graph.portals) {
    Bounds box;
    for (const glm::vec3& c : q.corners) box.extend(c - h * q.normal), box.extend(c + h * q.normal);
    const glm::ivec3 lo = glm::max(f.voxelOf(box.lo) - 1, glm::ivec3(0)),
                     hi = glm::min(f.voxelOf(box.hi) + 1, f.dims - 1);
    const glm::vec3 o = q.corners[0], eu = q.corners[1] - o, ev = q.corners[3] - o;
    const float lu = glm::length(eu), lv = glm::length(ev);
    if (lu <= 0.0f || lv <= 0.0f) continue;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const glm::vec3 p = f.centre(glm::ivec3(x, y, z));
          if (std::abs(glm::dot(p - q.centre(), q.normal)) > 0.5f * h * 1.001f) continue;
          const float pu = glm::dot(p - o, eu / lu), pv = glm::dot(p - o, ev / lv);
          if (pu < -0.5f * h || pu > lu + 0.5f * h || pv < -0.5f * h || pv > lv + 0.5f * h) continue;
          const size_t i = f.index(x, y, z);
          if (!blocked[i]) portalVoxel[i] = 1, blocked[i] = 1;
        }
  }

  std::vector<size_t> queue;
  for (size_t c = 0; c < graph.cells.size(); ++c) {
    const Cell& cell = graph.cells[c];
    if (!cell.volume.empty()) {
      labelVolumeVoxels(cell.volume, f, space, int32_t(c), label);
      continue;
    }
    for (uint32_t t : cell.triangles) {
      if (t >= scene.triangles.size()) continue;
      const Triangle& tri = scene.triangles[t];
      const glm::vec3 n = tri.geometricNormal();
      if (n == glm::vec3(0.0f)) continue;
      // A few points over the triangle (its centroid and the midpoints towards each corner).
      const glm::vec3 g = tri.centroid();
      for (const glm::vec3& p : {g, 0.5f * (g + tri.p[0]), 0.5f * (g + tri.p[1]), 0.5f * (g + tri.p[2])})
        for (float step : {1.0f, 1.5f, 2.0f, 3.0f}) {
          const glm::ivec3 v = f.voxelOf(p + step * h * n);
          if (!f.contains(v)) break;
          const size_t i = f.index(v);
          if (blocked[i]) continue;
          if (label[i] < 0) label[i] = int(c), queue.push_back(i);
          break;
        }
    }
  }
  queue.clear();
  for (size_t i = 0; i < label.size(); ++i)
    if (label[i] >= 0) queue.push_back(i);

  // Grow, first around the portals, then through them (so each portal voxel joins a neighbour).
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      queue.clear();
      for (size_t i = 0; i < label.size(); ++i)
        if (label[i] >= 0) queue.push_back(i);
      for (size_t i = 0; i < label.size(); ++i)
        if (portalVoxel[i]) blocked[i] = 0;
    }
    for (size_t head = 0; head < queue.size(); ++head) {
      const glm::ivec3 c = f.coord(queue[head]);
      for (const auto& d : kFaceNeighbours) {
        const glm::ivec3 nb(c.x + d[0], c.y + d[1], c.z + d[2]);
        if (!f.contains(nb)) continue;
        const size_t j = f.index(nb);
        if (blocked[j] || label[j] >= 0) continue;
        label[j] = label[queue[head]];
        queue.push_back(j);
      }
    }
  }
  return label;
}

double adjustedRandIndex(const std::vector<int32_t>& a, const std::vector<int32_t>& b) {
  std::unordered_map<uint64_t, double> joint;
  std::unordered_map<int32_t, double> rows, cols;
  double n = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (a[i] < 0 || b[i] < 0) continue;
    joint[(uint64_t(uint32_t(a[i])) << 32) | uint32_t(b[i])] += 1.0;
    rows[a[i]] += 1.0;
    cols[b[i]] += 1.0;
    n += 1.0;
  }
  if (n < 2.0) return 1.0;
  double sumJoint = 0.0, sumRows = 0.0, sumCols = 0.0;
  for (const auto& [k, c] : joint) sumJoint += choose2(c);
  for (const auto& [k, c] : rows) sumRows += choose2(c);
  for (const auto& [k, c] : cols) sumCols += choose2(c);
  const double expected = sumRows * sumCols / choose2(n);
  const double maximum = 0.5 * (sumRows + sumCols);
  if (maximum == expected) return 1.0;  // both labellings a single cluster (or all singletons)
  return (sumJoint - expected) / (maximum - expected);
}

std::vector<double> bestMatchIoU(const std::vector<int32_t>& a, int countA, const std::vector<int32_t>& b,
                                 int countB, int unmatchable) {
  std::map<std::pair<int, int>, double> joint;
  std::vector<double> sizeA(size_t(std::max(countA, 0)), 0.0), sizeB(size_t(std::max(countB, 0)), 0.0);
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (a[i] < 0 || b[i] < 0 || a[i] >= countA || b[i] >= countB) continue;
    joint[{a[i], b[i]}] += 1.0;
    sizeA[size_t(a[i])] += 1.0;
    sizeB[size_t(b[i])] += 1.0;
  }
  std::vector<double> best(sizeA.size(), 0.0);
  for (const auto& [key, inter] : joint) {
    if (key.second == unmatchable) continue;
    const double iou = inter / (sizeA[size_t(key.first)] + sizeB[size_t(key.second)] - inter);
    best[size_t(key.first)] = std::max(best[size_t(key.first)], iou);
  }
  return best;
}

InteriorLabels interiorLabels(const std::vector<int32_t>& a, int countA, int outsideA,
                              const std::vector<int32_t>& b, int countB, int outsideB) {
  InteriorLabels out;
  const size_t n = std::min(a.size(), b.size());
  out.a.assign(n, -1), out.b.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const bool roomA = a[i] >= 0 && a[i] < countA && a[i] != outsideA;
    const bool roomB = b[i] >= 0 && b[i] < countB && b[i] != outsideB;
    if (!roomA && !roomB) continue;
    ++out.interior, out.roomA += roomA, out.roomB += roomB, out.both += roomA && roomB;
    out.a[i] = roomA ? a[i] : countA;
    out.b[i] = roomB ? b[i] : countB;
  }
  return out;
}

std::vector<PortalMatch> matchPortals(const std::vector<PortalQuad>& reference,
                                      const std::vector<PortalQuad>& candidate) {
  std::vector<PortalMatch> out;
  for (size_t r = 0; r < reference.size(); ++r) {
    PortalMatch m;
    m.reference = int(r);
    float best = std::numeric_limits<float>::max();
    for (size_t c = 0; c < candidate.size(); ++c) {
      const float d = glm::length(candidate[c].centre() - reference[r].centre());
      if (d < best) best = d, m.candidate = int(c);
    }
    if (m.candidate >= 0) {
      const PortalQuad& c = candidate[size_t(m.candidate)];
      m.centreDistance = best;
      const float cosine = std::min(1.0f, std::abs(glm::dot(c.normal, reference[r].normal)));
      m.normalAngle = float(std::acos(cosine) * 180.0 / M_PI);
      m.areaRatio = reference[r].area > 0.0f ? c.area / reference[r].area : 0.0f;
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace cpgi::decomp
