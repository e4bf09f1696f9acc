#include "decomposition/behind.h"

#include <algorithm>
#include <numeric>

namespace cpgi::decomp {
namespace {

// Per cell, the voxels in front of and behind their nearest face, and the voxel faces each cell shares
// with every other and with the outside (the node `cellCount`: the outside's cell, or its unlabelled
// voxels when it is none), counted from both sides.
struct CellContacts {
  std::vector<double> front, back;
  std::vector<size_t> faces;  ///< (cellCount + 1)², row-major
  int nodes = 0;
  size_t& at(int a, int b) { return faces[size_t(a) * size_t(nodes) + size_t(b)]; }
};

CellContacts countContacts(const CellLabels& cells, const Scene& scene, const SolidGrid& solid,
                           const std::vector<Space>& space) {
  const GridFrame& f = cells.frame;
  const int n = cells.cellCount();
  CellContacts k;
  k.nodes = n + 1;
  k.front.assign(size_t(n), 0.0), k.back.assign(size_t(n), 0.0);
  k.faces.assign(size_t(k.nodes) * size_t(k.nodes), 0);
  auto node = [&](size_t j) {
    const int c = cells.cell[j];
    if (c >= 0) return c == cells.outsideCell ? n : c;
    return space[j] == Space::Outside ? n : -1;
  };
  for (size_t i = 0; i < cells.cell.size(); ++i) {
    const int c = cells.cell[i];
    if (c < 0) continue;
    const int t = solid.nearestTriangle[i];
    if (t >= 0) {
      const Triangle& tri = scene.triangles[size_t(t)];
      const float side = glm::dot(f.centre(i) - tri.centroid(), tri.geometricNormal());
      (side > 0.0f ? k.front : k.back)[size_t(c)] += side != 0.0f ? 1.0 : 0.0;
    }
    const int a = node(i);
    const glm::ivec3 q = f.coord(i);
    for (const auto& d : kFaceNeighbours) {
      const glm::ivec3 r(q.x + d[0], q.y + d[1], q.z + d[2]);
      if (!f.contains(r)) continue;
      const int b = node(f.index(r));
      if (b >= 0 && b != a) ++k.at(a, b), ++k.at(b, a);
    }
  }
  return k;
}

// Groups of cells behind the geometry that touch each other, by union-find over their contacts.
std::vector<int> groupsOf(CellContacts& k, const std::vector<char>& behind) {
  const int n = int(behind.size());
  std::vector<int> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int a) {
    while (parent[size_t(a)] != a) a = parent[size_t(a)] = parent[size_t(parent[size_t(a)])];
    return a;
  };
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if (behind[size_t(a)] && behind[size_t(b)] && k.at(a, b) > 0) parent[size_t(root(b))] = root(a);
  std::vector<int> group(static_cast<size_t>(n));
  for (int a = 0; a < n; ++a) group[size_t(a)] = root(a);
  return group;
}

// Cells that meet no room, by contact (union-find over the cells' voxel faces, the outside left out):
// per cell, its group's root, and whether the group lies apart from the rooms — closed (it meets nothing),
// or meeting only the outside in a level whose largest group of rooms does not meet the outside (a sealed
// level: the void round it reaches that group only through gaps behind the walls). The largest group is
// never apart.
std::vector<char> apartFromTheRooms(CellContacts& k, const CellLabels& cells, std::vector<int>& group) {
  const int n = cells.cellCount();
  std::vector<char> room(size_t(n), 0);
  for (int c = 0; c < n; ++c) room[size_t(c)] = c != cells.outsideCell;
  group = groupsOf(k, room);
  std::vector<double> volume(size_t(n), 0.0);
  std::vector<char> meetsOutside(size_t(n), 0);
  for (int c = 0; c < n; ++c) {
    if (!room[size_t(c)]) continue;
    volume[size_t(group[size_t(c)])] += cells.volume[size_t(c)];
    meetsOutside[size_t(group[size_t(c)])] |= k.at(c, n) > 0 ? 1 : 0;
  }
  const int largest = int(std::max_element(volume.begin(), volume.end()) - volume.begin());
  const bool sealedLevel = !meetsOutside[size_t(largest)];
  std::vector<char> apart(size_t(n), 0);
  for (int c = 0; c < n; ++c) {
    const int g = group[size_t(c)];
    apart[size_t(c)] = room[size_t(c)] && g != largest && (!meetsOutside[size_t(g)] || sealedLevel);
  }
  return apart;
}

// Folds the cells marked `behind` (with the groups they form by contact) into the outside when a group
// meets it, else into the room it shares the most voxel faces with, else drops them; renumbers the rest.
FoldedCells foldMarkedCells(CellLabels& cells, CellContacts& k, const std::vector<char>& behind) {
  FoldedCells out;
  const int n = cells.cellCount();
  const std::vector<int> group = groupsOf(k, behind);
  // Where each group goes: the outside (kFolded marks it, the outside may be no cell), a room, or nowhere.
  constexpr int kOutside = -2;
  std::vector<int> target(size_t(n), -1);
  for (int g = 0; g < n; ++g) {
    if (!behind[size_t(g)] || group[size_t(g)] != g) continue;
    size_t toOutside = 0;
    std::vector<size_t> toRoom(size_t(n), 0);
    for (int m = 0; m < n; ++m) {
      if (group[size_t(m)] != g || !behind[size_t(m)]) continue;
      toOutside += k.at(m, n);
      for (int r = 0; r < n; ++r)
        if (!behind[size_t(r)] && r != cells.outsideCell) toRoom[size_t(r)] += k.at(m, r);
    }
    const auto best = std::max_element(toRoom.begin(), toRoom.end());
    target[size_t(g)] = toOutside > 0 ? kOutside : *best > 0 ? int(best - toRoom.begin()) : -1;
  }
  // The rooms left, in their order; does the outside still meet one (directly or through a pocket)?
  std::vector<int> newIndex(size_t(n), -1);
  int kept = 0;
  bool outsideMeetsRoom = false;
  for (int c = 0; c < n; ++c) {
    if (behind[size_t(c)] || c == cells.outsideCell) continue;
    newIndex[size_t(c)] = kept++;
    outsideMeetsRoom = outsideMeetsRoom || k.at(c, n) > 0;
    for (int m = 0; m < n; ++m)
      outsideMeetsRoom = outsideMeetsRoom || (behind[size_t(m)] &&
                                              target[size_t(group[size_t(m)])] == kOutside && k.at(c, m) > 0);
  }
  int outsideAfter = -1;
  if (cells.outsideCell >= 0 && (outsideMeetsRoom || kept == 0)) outsideAfter = kept;
  out.outsideDropped = cells.outsideCell >= 0 && outsideAfter < 0;
  if (cells.outsideCell >= 0) newIndex[size_t(cells.outsideCell)] = outsideAfter;
  for (int c = 0; c < n; ++c) {
    if (!behind[size_t(c)]) continue;
    ++out.folded;
    const int t = target[size_t(group[size_t(c)])];
    newIndex[size_t(c)] = t == kOutside ? outsideAfter : t >= 0 ? newIndex[size_t(t)] : -1;
  }
  if (out.folded == 0 && !out.outsideDropped) return out;

  std::vector<float> peak(size_t(kept + (outsideAfter >= 0 ? 1 : 0)), 0.0f);
  std::vector<uint32_t> volume(peak.size(), 0);
  for (int c = 0; c < n; ++c)
    if (newIndex[size_t(c)] >= 0)
      peak[size_t(newIndex[size_t(c)])] = std::max(peak[size_t(newIndex[size_t(c)])], cells.peak[size_t(c)]);
  for (int32_t& label : cells.cell) {
    if (label < 0) continue;
    label = newIndex[size_t(label)];
    if (label >= 0) ++volume[size_t(label)];
  }
  for (int32_t& c : cells.cellOfBasin)
    if (c >= 0) c = newIndex[size_t(c)];
  cells.peak = std::move(peak);
  cells.volume = std::move(volume);
  cells.outsideCell = outsideAfter;
  return out;
}

}  // namespace

FoldedCells foldCellsBehindGeometry(CellLabels& cells, const Scene& scene, const SolidGrid& solid,
                                    const std::vector<Space>& space, const BehindParams& params,
                                    Context& ctx) {
  auto timer = ctx.time("behind");
  FoldedCells out;
  if (!(params.backToFront > 0.0) || cells.cellCount() == 0) return out;
  // Only beside a room that faces the right way: in a model whose faces all point away from its rooms
  // (a flipped export) every room would look behind the geometry, and nothing is folded.
  auto anyBehindBesideARoom = [&](const std::vector<char>& behind) {
    bool anyBehind = false, anyRoom = false;
    for (int c = 0; c < cells.cellCount(); ++c)
      if (c != cells.outsideCell) (behind[size_t(c)] ? anyBehind : anyRoom) = true;
    return anyBehind && anyRoom;
  };
  CellContacts k = countContacts(cells, scene, solid, space);
  std::vector<char> behind(size_t(cells.cellCount()), 0);
  for (int c = 0; c < cells.cellCount(); ++c)
    behind[size_t(c)] = c != cells.outsideCell && k.back[size_t(c)] > params.backToFront * k.front[size_t(c)];
  if (anyBehindBesideARoom(behind)) out = foldMarkedCells(cells, k, behind);
  if (!(params.apartBackToFront > 0.0) || cells.cellCount() == 0) return out;

  // Then the groups apart from the rooms, with what was folded into them, by the lower share.
  k = countContacts(cells, scene, solid, space);
  std::vector<int> group;
  const std::vector<char> apart = apartFromTheRooms(k, cells, group);
  std::vector<double> front(size_t(cells.cellCount()), 0.0), back(front.size(), 0.0);
  for (int c = 0; c < cells.cellCount(); ++c)
    if (apart[size_t(c)])
      front[size_t(group[size_t(c)])] += k.front[size_t(c)],
          back[size_t(group[size_t(c)])] += k.back[size_t(c)];
  behind.assign(size_t(cells.cellCount()), 0);
  for (int c = 0; c < cells.cellCount(); ++c) {
    const int g = group[size_t(c)];
    behind[size_t(c)] = apart[size_t(c)] && back[size_t(g)] > params.apartBackToFront * front[size_t(g)];
  }
  if (!anyBehindBesideARoom(behind)) return out;
  const FoldedCells apartFolded = foldMarkedCells(cells, k, behind);
  out.folded += apartFolded.folded;
  out.outsideDropped = out.outsideDropped || apartFolded.outsideDropped;
  return out;
}

}  // namespace cpgi::decomp
