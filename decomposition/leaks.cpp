#include "decomposition/leaks.h"

#include <algorithm>
#include <map>
#include <set>

#include "decomposition/sections.h"

namespace cpgi::decomp {
namespace {

// Turns a portal whose cells were renumbered so that cellA < cellB again, its normal from A into B.
void orderCells(PortalQuad& q) {
  if (q.cellA < q.cellB) return;
  std::swap(q.cellA, q.cellB);
  std::swap(q.corners[1], q.corners[3]);
  q.normal = -q.normal;
}

// The quad grown by `by` metres on every side, in its plane, its normal kept.
PortalQuad grownQuad(const PortalQuad& q, float by) {
  if (by <= 0.0f) return q;
  PortalQuad g = q;
  const glm::vec3 e1 = q.corners[1] - q.corners[0], e2 = q.corners[3] - q.corners[0];
  const float l1 = glm::length(e1), l2 = glm::length(e2);
  if (l1 <= 0.0f || l2 <= 0.0f) return q;
  const glm::vec3 u = by * e1 / l1, v = by * e2 / l2;
  g.corners = {q.corners[0] - u - v, q.corners[1] + u - v, q.corners[2] + u + v, q.corners[3] - u + v};
  computePortalFrame(g);
  g.normal = q.normal;
  return g;
}

// Every cell's voxels connected: each piece of a cell but its largest joins the cell it shares most
// voxel faces with (a pocket a relabelling cut off, the head of a door's reveal left to the storey
// above). Returns the voxels moved.
size_t absorbFragments(const GridFrame& f, std::vector<int32_t>& cell) {
  const size_t n = cell.size();
  std::vector<int32_t> piece(n, -1);
  std::vector<size_t> size;    // per piece
  std::vector<int32_t> owner;  // per piece: its cell
  std::vector<size_t> queue;
  const ptrdiff_t strides[3] = {1, f.dims.x, ptrdiff_t(f.dims.x) * f.dims.y};
  auto neighbours = [&](size_t i, auto&& visit) {
    const glm::ivec3 c = f.coord(i);
    for (int k = 0; k < 3; ++k) {
      if (c[k] > 0) visit(size_t(ptrdiff_t(i) - strides[k]));
      if (c[k] + 1 < f.dims[k]) visit(size_t(ptrdiff_t(i) + strides[k]));
    }
  };
  for (size_t s = 0; s < n; ++s) {
    if (cell[s] < 0 || piece[s] >= 0) continue;
    const int32_t id = int32_t(size.size());
    size.push_back(0), owner.push_back(cell[s]);
    queue.assign(1, s);
    piece[s] = id;
    for (size_t head = 0; head < queue.size(); ++head) {
      ++size.back();
      neighbours(queue[head], [&](size_t j) {
        if (piece[j] < 0 && cell[j] == owner[size_t(id)]) piece[j] = id, queue.push_back(j);
      });
    }
  }
  std::map<int32_t, int32_t> largest;  // per cell: its largest piece
  for (int32_t p = 0; p < int32_t(size.size()); ++p) {
    auto it = largest.find(owner[size_t(p)]);
    if (it == largest.end() || size[size_t(p)] > size[size_t(it->second)]) largest[owner[size_t(p)]] = p;
  }
  // Per stray piece, the faces it shares with each other cell.
  std::map<int32_t, std::map<int32_t, size_t>> shared;
  for (size_t i = 0; i < n; ++i) {
    const int32_t p = piece[i];
    if (p < 0 || largest[owner[size_t(p)]] == p) continue;
    neighbours(i, [&](size_t j) {
      if (cell[j] >= 0 && cell[j] != cell[i]) ++shared[p][cell[j]];
    });
  }
  std::map<int32_t, int32_t> target;
  for (const auto& [p, counts] : shared) {
    size_t best = 0;
    for (const auto& [c, k] : counts)
      if (k > best) best = k, target[p] = c;
  }
  size_t moved = 0;
  for (size_t i = 0; i < n; ++i)
    if (piece[i] >= 0)
      if (const auto it = target.find(piece[i]); it != target.end()) cell[i] = it->second, ++moved;
  return moved;
}

// Relabels cells `first` and `second` to meet on `quads` (relabelAcrossPortals), trying them as they are,
// then grown by up to maxGrow voxels on every side and moved along their normals by up to maxShift voxels
// either way: of those that part the two, the one that moves the fewest voxels from one cell to the
// other. On success `quads` holds the ones used. A quad that stops a voxel short of a door's jamb lets the
// flood round its edge (the wall takes the extra rim); one pushed past the wall by furniture in front of
// the door leaves a slab of relabelled voxels that meets the room beyond it edge on. Each placement costs
// its flood (floodSideOfPortals), not a pass over the grid: a level's pair is tried up to 38 times.
// `placements` counts the placements flooded.
bool partOnMovedPortals(const GridFrame& f, std::vector<int32_t>& cell, int first, int second, size_t seedA,
                        size_t seedB, std::vector<PortalQuad>& quads, int maxGrow, int maxShift,
                        size_t& placements) {
  auto candidate = [&](int grow, int shift) {
    std::vector<PortalQuad> q;
    for (const PortalQuad& p : quads) {
      PortalQuad g = grownQuad(p, float(grow * f.voxel));
      for (glm::vec3& c : g.corners) c += float(shift * f.voxel) * g.normal;
      q.push_back(g);
    }
    return q;
  };
  auto barrier = [](const std::vector<PortalQuad>& q) {
    std::vector<const PortalQuad*> out;
    for (const PortalQuad& x : q) out.push_back(&x);
    return out;
  };
  ++placements;
  if (relabelAcrossPortals(f, cell, first, second, seedA, seedB, barrier(quads))) return true;
  // A placement moves the second cell's voxels on the first's side and the first's voxels off it.
  size_t firstVoxels = 0;
  for (const int32_t c : cell) firstVoxels += c == first;
  std::vector<char> reached(f.count(), 0);
  std::vector<size_t> side;
  size_t fewest = SIZE_MAX;
  std::vector<PortalQuad> best;
  for (int grow = 0; grow <= maxGrow; ++grow)
    for (int shift = -maxShift; shift <= maxShift; ++shift) {
      if (grow == 0 && shift == 0) continue;
      const std::vector<PortalQuad> q = candidate(grow, shift);
      ++placements;
      const bool parts = floodSideOfPortals(f, cell, first, second, seedA, seedB, barrier(q), reached, side);
      size_t firstOnSide = 0;
      for (const size_t i : side) firstOnSide += cell[i] == first, reached[i] = 0;
      if (!parts) continue;
      const size_t moved = (side.size() - firstOnSide) + (firstVoxels - firstOnSide);
      if (moved < fewest) fewest = moved, best = q;
    }
  if (best.empty()) return false;
  relabelAcrossPortals(f, cell, first, second, seedA, seedB, barrier(best));
  quads = std::move(best);
  return true;
}

// closeLeaks's state: the portal set being closed, the cells still alive, the pairs the leak rounds moved
// onto their portals, and what it did.
class LeakCloser {
 public:
  LeakCloser(PortalSet& set, const DistanceGrid& distance, int cellCount, int outsideCell,
             const LeakParams& params)
      : set(set),
        distance(distance),
        f(distance.frame),
        cellCount(cellCount),
        outsideCell(outsideCell),
        params(params),
        alive(size_t(cellCount), 1) {
    out.cellOf.resize(size_t(cellCount));
    for (int c = 0; c < cellCount; ++c) out.cellOf[size_t(c)] = c;
  }

  ClosedLeaks run() {
    // Cells in one piece, then no portal between cells that do not touch.
    absorbFragments(f, set.cell);
    dropUntouching();
    if (params.dropRedundant) dropRedundant(false);
    leakRounds();
    // Relabelling may have moved a pair onto fewer of its portals: drop the others, then make sure.
    if (params.dropRedundant && !relabelled.empty()) {
      dropRedundant(true);
      leakRounds();
    }
    renumber();
    set.leakingFaces = countLeakingFaces(f, set.cell, quads());
    return out;
  }

 private:
  std::vector<PortalQuad> quads() const {
    std::vector<PortalQuad> q;
    for (const FittedPortal& p : set.portals) q.push_back(p.quad);
    return q;
  }

  // Each cell's deepest voxel (SIZE_MAX: none).
  std::vector<size_t> deepestVoxels() const {
    std::vector<size_t> deepest(size_t(cellCount), SIZE_MAX);
    for (size_t i = 0; i < set.cell.size(); ++i) {
      const int c = set.cell[i];
      if (c >= 0 && (deepest[size_t(c)] == SIZE_MAX || distance.d2[i] > distance.d2[deepest[size_t(c)]]))
        deepest[size_t(c)] = i;
    }
    return deepest;
  }

  void merge(int a, int b) {
    const int keep = b == outsideCell ? b : a == outsideCell ? a : std::min(a, b);
    const int gone = keep == a ? b : a;
    for (int32_t& l : set.cell)
      if (l == gone) l = keep;
    std::vector<FittedPortal> kept;
    for (FittedPortal& p : set.portals) {
      PortalQuad& q = p.quad;
      const bool between = (q.cellA == a && q.cellB == b) || (q.cellA == b && q.cellB == a);
      if (between) continue;
      if (q.cellA == gone) q.cellA = keep;
      if (q.cellB == gone) q.cellB = keep;
      orderCells(q);
      kept.push_back(p);
    }
    set.portals = std::move(kept);
    for (int32_t& c : out.cellOf)
      if (c == gone) c = keep;
    alive[size_t(gone)] = 0;
    ++out.mergedPairs;
  }

  void dropUntouching() {
    std::set<std::pair<int, int>> touching;
    const ptrdiff_t strides[3] = {1, f.dims.x, ptrdiff_t(f.dims.x) * f.dims.y};
    for (size_t i = 0; i < set.cell.size(); ++i) {
      const int a = set.cell[i];
      if (a < 0) continue;
      const glm::ivec3 c = f.coord(i);
      for (int k = 0; k < 3; ++k) {
        if (c[k] + 1 >= f.dims[k]) continue;
        const int b = set.cell[size_t(ptrdiff_t(i) + strides[k])];
        if (b >= 0 && b != a) touching.insert({std::min(a, b), std::max(a, b)});
      }
    }
    std::vector<FittedPortal> kept;
    for (const FittedPortal& p : set.portals)
      if (touching.count({std::min(p.quad.cellA, p.quad.cellB), std::max(p.quad.cellA, p.quad.cellB)}))
        kept.push_back(p);
      else
        ++out.droppedPortals;
    set.portals = std::move(kept);
  }

  // Redundant portals: a pair joined by several portals whose largest one to three alone cut the two
  // apart (relabelled to meet on them) keeps only those; the others are slivers of the interface that
  // the earlier rounds of fitPortals covered (a stair's landing edge beside its hole's portal), or fringe
  // portals a moved door portal no longer needs.
  void dropRedundant(bool onlyRelabelled) {
    std::map<std::pair<int, int>, std::vector<size_t>> byPair;
    for (size_t k = 0; k < set.portals.size(); ++k) {
      const PortalQuad& q = set.portals[k].quad;
      byPair[{std::min(q.cellA, q.cellB), std::max(q.cellA, q.cellB)}].push_back(k);
    }
    const std::vector<size_t> deepest = deepestVoxels();
    std::vector<char> dropped(set.portals.size(), 0);
    for (auto& [pair, list] : byPair) {
      if (list.size() < 2 || (onlyRelabelled && !relabelled.count(pair))) continue;
      const auto [a, b] = pair;
      if (deepest[size_t(a)] == SIZE_MAX || deepest[size_t(b)] == SIZE_MAX) continue;
      std::sort(list.begin(), list.end(),
                [&](size_t x, size_t y) { return set.portals[x].quad.area > set.portals[y].quad.area; });
      const int first = a == outsideCell ? b : a, second = first == a ? b : a;
      for (size_t keep = 1; keep < list.size() && keep <= 3; ++keep) {
        // Only slivers: what would go is under a quarter of what stays (a pair's several doors are
        // not tried, which spares a flood per door on a game level); after the leak rounds, any of the
        // portals of a pair they moved.
        float stays = 0.0f, goes = 0.0f;
        for (size_t n = 0; n < list.size(); ++n) (n < keep ? stays : goes) += set.portals[list[n]].quad.area;
        if (!onlyRelabelled && goes > 0.25f * stays) continue;
        // The largest alone may also be grown by a voxel or moved by up to two (a door portal past its
        // wall, its jamb covered by a fringe portal or two beside it; pairs with more portals, a game
        // level's, are not searched: each try floods the pair).
        std::vector<PortalQuad> quads;
        for (size_t n = 0; n < keep; ++n) quads.push_back(set.portals[list[n]].quad);
        if (!partOnMovedPortals(f, set.cell, first, second, deepest[size_t(first)], deepest[size_t(second)],
                                quads, keep == 1 && list.size() <= 3 ? 1 : 0,
                                keep == 1 && list.size() <= 3 ? 2 : 0, out.placements))
          continue;
        for (size_t n = 0; n < keep; ++n) set.portals[list[n]].quad = quads[n];
        for (size_t n = keep; n < list.size(); ++n) dropped[list[n]] = 1, ++out.droppedPortals;
        break;
      }
    }
    std::vector<FittedPortal> kept;
    for (size_t k = 0; k < set.portals.size(); ++k)
      if (!dropped[k]) kept.push_back(set.portals[k]);
    set.portals = std::move(kept);
  }

  void leakRounds() {
    for (int round = 0; round < std::max(1, params.rounds); ++round) {
      const std::map<std::pair<int, int>, size_t> leaks = leakingFacesByPair(f, set.cell, quads());
      if (leaks.empty()) break;
      const bool last = params.merge && round + 1 >= std::max(1, params.rounds);
      const std::vector<size_t> deepest = deepestVoxels();  // the seeds of the relabelling flood
      std::vector<std::pair<size_t, std::pair<int, int>>> order;
      for (const auto& [pair, faces] : leaks) order.push_back({faces, pair});
      std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      std::set<int> touched;
      for (const auto& [faces, pair] : order) {
        const auto [a, b] = pair;
        if (!alive[size_t(a)] || !alive[size_t(b)] || touched.count(a) || touched.count(b)) continue;
        touched.insert(a), touched.insert(b);
        std::vector<size_t> own;
        for (size_t k = 0; k < set.portals.size(); ++k) {
          const PortalQuad& q = set.portals[k].quad;
          if ((q.cellA == a && q.cellB == b) || (q.cellA == b && q.cellB == a)) own.push_back(k);
        }
        // The outside's deepest voxel may lie anywhere round the building: flood from the room's.
        const int first = a == outsideCell ? b : a, second = first == a ? b : a;
        bool separated = false;
        if (!last && !own.empty() && deepest[size_t(a)] != SIZE_MAX && deepest[size_t(b)] != SIZE_MAX) {
          std::vector<PortalQuad> quads;
          for (size_t k : own) quads.push_back(set.portals[k].quad);
          if (partOnMovedPortals(f, set.cell, first, second, deepest[size_t(first)], deepest[size_t(second)],
                                 quads, 2, 6, out.placements)) {
            for (size_t n = 0; n < own.size(); ++n) set.portals[own[n]].quad = quads[n];
            separated = true;
          }
        }
        if (separated) {
          relabelled.insert({a, b});
          ++out.relabelledPairs;
          continue;
        }
        if (params.merge) merge(a, b);
      }
    }
  }

  void renumber() {
    // Dense numbering in the old order; the outside, last before, stays last.
    std::vector<int32_t> index(size_t(cellCount), -1);
    for (int c = 0; c < cellCount; ++c)
      if (alive[size_t(c)]) index[size_t(c)] = out.cellCount++, out.keptCell.push_back(c);
    for (int32_t& l : set.cell)
      if (l >= 0) l = index[size_t(l)];
    for (FittedPortal& p : set.portals)
      p.quad.cellA = index[size_t(p.quad.cellA)], p.quad.cellB = index[size_t(p.quad.cellB)];
    for (int32_t& c : out.cellOf) c = index[size_t(c)];
    out.outsideCell = outsideCell >= 0 ? index[size_t(outsideCell)] : -1;
  }

  PortalSet& set;
  const DistanceGrid& distance;
  const GridFrame& f;
  const int cellCount, outsideCell;
  const LeakParams& params;
  std::vector<char> alive;
  std::set<std::pair<int, int>> relabelled;  // pairs the leak rounds moved onto their portals
  ClosedLeaks out;
};

}  // namespace

ClosedLeaks closeLeaks(PortalSet& set, const DistanceGrid& distance, int cellCount, int outsideCell,
                       const LeakParams& params, Context& ctx) {
  auto timer = ctx.time("leaks");
  return LeakCloser(set, distance, cellCount, outsideCell, params).run();
}

}  // namespace cpgi::decomp
