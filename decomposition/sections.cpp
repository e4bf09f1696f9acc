#include "decomposition/sections.h"

#include <algorithm>
#include <limits>

#include "decomposition/portals.h"

namespace cpgi::decomp {
namespace {

constexpr size_t kOpen = std::numeric_limits<size_t>::max();

// The 2D flood of one layer across `axis`: voxels of a or b connected within the layer to the seeds.
// Returns their count, or kOpen when the flood passes maxArea voxels or reaches the grid's border.
// `stamp`/`mark` give each flood its own visited marks without clearing; `out`, when given, receives
// the voxels.
size_t floodLayer(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b, int axis, int layer,
                  const std::vector<glm::ivec2>& seeds, size_t maxArea, std::vector<uint32_t>& stamp,
                  uint32_t mark, std::vector<glm::ivec2>& queue, std::vector<size_t>* out) {
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const int n1 = f.dims[a1], n2 = f.dims[a2];
  auto voxel = [&](glm::ivec2 p) {
    glm::ivec3 c;
    c[axis] = layer, c[a1] = p.x, c[a2] = p.y;
    return f.index(c);
  };
  auto member = [&](size_t i) { return cell[i] == a || cell[i] == b; };
  queue.clear();
  for (const glm::ivec2& s : seeds) {
    const size_t k = size_t(s.y) * size_t(n1) + size_t(s.x);
    if (stamp[k] == mark || !member(voxel(s))) continue;
    stamp[k] = mark;
    queue.push_back(s);
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    if (queue.size() > maxArea) return kOpen;
    const glm::ivec2 p = queue[head];
    if (out) out->push_back(voxel(p));
    for (const glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
      const glm::ivec2 q = p + d;
      if (q.x < 0 || q.y < 0 || q.x >= n1 || q.y >= n2) return kOpen;
      const size_t k = size_t(q.y) * size_t(n1) + size_t(q.x);
      if (stamp[k] == mark || !member(voxel(q))) continue;
      if (q.x == 0 || q.y == 0 || q.x == n1 - 1 || q.y == n2 - 1) return kOpen;  // the padding: not closed
      stamp[k] = mark;
      queue.push_back(q);
    }
  }
  return queue.size();
}

}  // namespace

std::vector<Section> closedSections(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b,
                                    const std::vector<size_t>& interfaceVoxels, int searchVoxels,
                                    size_t maxArea, size_t maxCandidates) {
  if (interfaceVoxels.empty() || maxCandidates == 0) return {};
  struct Layer {
    size_t area;
    int axis, layer;
  };
  std::vector<Layer> closed;
  std::vector<size_t> areas[3];  // per axis, per layer: kOpen when open or empty
  std::vector<glm::ivec2> seeds[3];
  std::vector<glm::ivec2> queue;
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    int lo = f.dims[axis], hi = -1;
    for (size_t i : interfaceVoxels) {
      const glm::ivec3 c = f.coord(i);
      seeds[axis].emplace_back(c[a1], c[a2]);
      lo = std::min(lo, c[axis]), hi = std::max(hi, c[axis]);
    }
    std::vector<glm::ivec2>& sd = seeds[axis];
    std::sort(sd.begin(), sd.end(),
              [](glm::ivec2 p, glm::ivec2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
    sd.erase(std::unique(sd.begin(), sd.end()), sd.end());
    std::vector<uint32_t> stamp(size_t(f.dims[a1]) * size_t(f.dims[a2]), 0);
    areas[axis].assign(size_t(f.dims[axis]), kOpen);
    uint32_t mark = 0;
    for (int layer = std::max(1, lo - searchVoxels); layer <= std::min(f.dims[axis] - 2, hi + searchVoxels);
         ++layer) {
      const size_t area = floodLayer(f, cell, a, b, axis, layer, sd, maxArea, stamp, ++mark, queue, nullptr);
      if (area == 0 || area == kOpen) continue;
      areas[axis][size_t(layer)] = area;
      closed.push_back({area, axis, layer});
    }
  }
  std::stable_sort(closed.begin(), closed.end(),
                   [](const Layer& x, const Layer& y) { return x.area < y.area; });

  // Each candidate: the run of near-equal layers around a narrowest layer not yet in a chosen run, and
  // its middle (a floor's mid-plane).
  std::vector<Section> out;
  std::vector<std::pair<int, int>> runs[3];
  for (const Layer& c : closed) {
    if (out.size() >= maxCandidates) break;
    const std::vector<size_t>& ar = areas[c.axis];
    bool taken = false;
    for (const auto& [first, last] : runs[c.axis])
      taken = taken || (c.layer >= first - 1 && c.layer <= last + 1);
    if (taken) continue;
    const size_t limit = c.area + std::max<size_t>(1, c.area / 50);
    int first = c.layer, last = c.layer;
    while (first > 0 && ar[size_t(first - 1)] <= limit) --first;
    while (last + 1 < int(ar.size()) && ar[size_t(last + 1)] <= limit) ++last;
    runs[c.axis].push_back({first, last});
    Section s;
    s.axis = c.axis;
    s.layer = (first + last) / 2;
    const int a1 = (s.axis + 1) % 3, a2 = (s.axis + 2) % 3;
    std::vector<uint32_t> stamp(size_t(f.dims[a1]) * size_t(f.dims[a2]), 0);
    if (floodLayer(f, cell, a, b, s.axis, s.layer, seeds[s.axis], maxArea, stamp, 1, queue, &s.voxels) ==
            kOpen ||
        s.voxels.empty())
      continue;
    out.push_back(std::move(s));
  }
  return out;
}

std::optional<Section> narrowestSection(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b,
                                        const std::vector<size_t>& interfaceVoxels, int searchVoxels,
                                        size_t maxArea) {
  std::vector<Section> s = closedSections(f, cell, a, b, interfaceVoxels, searchVoxels, maxArea, 1);
  if (s.empty()) return std::nullopt;
  return std::move(s.front());
}

bool floodSideOfPortals(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b, size_t seedA,
                        size_t seedB, const std::vector<const PortalQuad*>& portals,
                        std::vector<char>& reached, std::vector<size_t>& side) {
  side.clear();
  // Portal boxes in voxels (grown by one): only moves touching them need the crossing test.
  struct Near {
    glm::ivec3 lo, hi;
    const PortalQuad* portal;
  };
  std::vector<Near> near;
  for (const PortalQuad* q : portals) {
    Bounds box;
    for (const glm::vec3& c : q->corners) box.extend(c);
    near.push_back({f.voxelOf(box.lo) - 1, f.voxelOf(box.hi) + 1, q});
  }
  const float tolerance = 0.5f * float(f.voxel);
  auto blocked = [&](size_t i, size_t j) {
    const glm::ivec3 ci = f.coord(i);
    for (const Near& n : near) {
      if (glm::any(glm::lessThan(ci, n.lo)) || glm::any(glm::greaterThan(ci, n.hi))) continue;
      if (segmentCrossesPortal(*n.portal, f.centre(i), f.centre(j), tolerance)) return true;
    }
    return false;
  };
  // Seeds that are not the pair's own voxels tell no side from the other: the flood would hand all of
  // one cell to the other.
  if (seedA >= cell.size() || seedB >= cell.size() || cell[seedA] != a || cell[seedB] != b) return false;
  side.push_back(seedA);
  reached[seedA] = 1;
  const ptrdiff_t strides[3] = {1, f.dims.x, ptrdiff_t(f.dims.x) * f.dims.y};
  for (size_t head = 0; head < side.size(); ++head) {
    const size_t i = side[head];
    if (i == seedB) return false;
    const glm::ivec3 c = f.coord(i);
    for (int k = 0; k < 3; ++k)
      for (int dir : {-1, 1}) {
        if ((dir < 0 && c[k] == 0) || (dir > 0 && c[k] == f.dims[k] - 1)) continue;
        const size_t j = size_t(ptrdiff_t(i) + dir * strides[k]);
        if (reached[j] || (cell[j] != a && cell[j] != b) || blocked(i, j)) continue;
        reached[j] = 1;
        side.push_back(j);
      }
  }
  return true;
}

bool relabelAcrossPortals(const GridFrame& f, std::vector<int32_t>& cell, int a, int b, size_t seedA,
                          size_t seedB, const std::vector<const PortalQuad*>& portals) {
  std::vector<char> reached(f.count(), 0);
  std::vector<size_t> side;
  if (!floodSideOfPortals(f, cell, a, b, seedA, seedB, portals, reached, side)) return false;
  for (size_t i = 0; i < cell.size(); ++i)
    if (cell[i] == a || cell[i] == b) cell[i] = reached[i] ? a : b;
  return true;
}

}  // namespace cpgi::decomp
