#include "decomposition/merge.h"

#include <cmath>
#include <queue>
#include <unordered_map>

namespace cpgi::decomp {
namespace {

struct Interface {
  float saddle = 0.0f;
  uint64_t faces = 0;
  uint64_t facesUp = 0;  // crossed along y: the interface seen from above
};

struct Group {
  float peak = 0.0f;
  double volume = 0.0;  // voxels
  std::unordered_map<int, Interface> neighbours;
  int version = 0;
  bool alive = true;
  bool outside = false;  // holds the outside marker basin: infinitely high, never the "smaller" room
  double sumY = 0.0, sumY2 = 0.0;             // of its voxels' heights (y index), for the storey rule
  double floorSumY = 0.0, floorVoxels = 0.0;  // of its voxels resting on the geometry, for the gallery rule
  double meanY() const { return volume > 0.0 ? sumY / volume : 0.0; }
  double floorY() const { return floorVoxels > 0.0 ? floorSumY / floorVoxels : 0.0; }
  double spreadY() const {
    if (volume <= 0.0) return 0.0;
    const double m = meanY();
    return std::sqrt(std::max(0.0, sumY2 / volume - m * m) + 1.0 / 12.0);  // a voxel's own spread
  }
};

struct Candidate {
  float saddle;
  int a, b, versionA, versionB;
  bool operator<(const Candidate& o) const { return saddle < o.saddle; }
};

// Against the outside, the rules ask whether the other group is a room of its own: its own volume and
// peak decide (the outside's are those of the padded grid, not of the world around the building).
bool shouldMerge(const Group& x, const Group& y, const Interface& iface, const MergeParams& params,
                 double minVoxels, double h) {
  const Group& small = x.outside ? y : y.outside ? x : x.volume <= y.volume ? x : y;
  const float lowPeak = x.outside ? y.peak : y.outside ? x.peak : std::min(x.peak, y.peak);
  if (small.volume < minVoxels) return true;
  // Two floors joined through a hole: only a shallow dip merges them.
  if (!x.outside && !y.outside && params.storeySpread > 0.0 &&
      std::abs(x.meanY() - y.meanY()) > params.storeySpread * (x.spreadY() + y.spreadY())) {
    const double floorArea = small.volume / (small.spreadY() * std::sqrt(12.0));  // voxel faces
    if (double(iface.facesUp) < params.storeyOpening * floorArea)
      return std::min(x.peak, y.peak) - iface.saddle < params.minDepth;
  }
  // A gallery: side by side, their floors a storey apart, the higher one roofed at a storey's height.
  bool gallery = false;
  if (!x.outside && !y.outside && params.galleryFloorRise > 0.0 && x.floorVoxels > 0.0 &&
      y.floorVoxels > 0.0) {
    const Group& upper = x.floorY() > y.floorY() ? x : y;
    const Group& lower = &upper == &x ? y : x;
    gallery = (upper.floorY() - lower.floorY()) * h > params.galleryFloorRise &&
              (upper.meanY() - upper.floorY()) * h < params.galleryHeadroom;
  }
  const double ratio = x.outside || y.outside ? params.outsideSaddleRatio : params.saddleRatio;
  if (lowPeak <= 0.0f || iface.saddle / lowPeak > ratio) return true;
  if (lowPeak - iface.saddle < params.minDepth) return true;
  const double crossSection = std::pow(small.volume, 2.0 / 3.0) * h * h;
  return !gallery && params.openingRatio > 0.0 &&
         double(iface.faces) * h * h > params.openingRatio * crossSection;
}

// Group `gone` folded into `keep`: its interfaces (the deepest saddle, the faces added), peak, volume and
// height moments.
void fold(std::vector<Group>& groups, int keep, int gone) {
  Group& k = groups[size_t(keep)];
  Group& g = groups[size_t(gone)];
  for (const auto& [other, iface] : g.neighbours) {
    if (other == keep) continue;
    Interface& merged = k.neighbours[other];
    merged.saddle = std::max(merged.saddle, iface.saddle);
    merged.faces += iface.faces;
    merged.facesUp += iface.facesUp;
    auto& back = groups[size_t(other)].neighbours;
    back.erase(gone);
    back[keep] = merged;
  }
  k.neighbours.erase(gone);
  k.peak = std::max(k.peak, g.peak);
  k.volume += g.volume;
  k.outside = k.outside || g.outside;
  k.sumY += g.sumY, k.sumY2 += g.sumY2;
  k.floorSumY += g.floorSumY, k.floorVoxels += g.floorVoxels;
  ++k.version;
  g.alive = false;
  g.neighbours.clear();
}

}  // namespace

CellLabels mergeBasins(WatershedLabels basins, const MergeParams& params, Context& ctx) {
  auto timer = ctx.time("merge");
  const GridFrame& f = basins.frame;
  const double h = f.voxel;
  const int count = basins.basinCount();
  std::vector<Group> groups(static_cast<size_t>(count));
  for (int b = 0; b < count; ++b)
    groups[size_t(b)].peak = basins.peak[size_t(b)], groups[size_t(b)].volume = basins.volume[size_t(b)];
  if (basins.outsideBasin >= 0) groups[size_t(basins.outsideBasin)].outside = true;
  {
    // A voxel over one of no basin (solid, or void) rests on the geometry: its group's floor.
    const size_t below = size_t(f.dims.x);
    size_t i = 0;
    for (int z = 0; z < f.dims.z; ++z)
      for (int y = 0; y < f.dims.y; ++y)
        for (int x = 0; x < f.dims.x; ++x, ++i)
          if (const int b = basins.basin[i]; b >= 0) {
            Group& g = groups[size_t(b)];
            g.sumY += y, g.sumY2 += double(y) * y;
            if (y > 0 && basins.basin[i - below] < 0) g.floorSumY += y, ++g.floorVoxels;
          }
  }
  for (const BasinContact& c : basins.contacts) {
    groups[size_t(c.a)].neighbours[c.b] = {c.saddle, c.faces, c.facesUp};
    groups[size_t(c.b)].neighbours[c.a] = {c.saddle, c.faces, c.facesUp};
  }

  std::priority_queue<Candidate> queue;
  auto pushAll = [&](int g) {
    for (const auto& [other, iface] : groups[size_t(g)].neighbours)
      queue.push({iface.saddle, g, other, groups[size_t(g)].version, groups[size_t(other)].version});
  };
  for (int b = 0; b < count; ++b) pushAll(b);

  const double minVoxels = params.minCellVolume / f.voxelVolume();
  std::vector<int> mergedInto(static_cast<size_t>(count));
  for (int b = 0; b < count; ++b) mergedInto[size_t(b)] = b;
  while (!queue.empty()) {
    const Candidate c = queue.top();
    queue.pop();
    Group& ga = groups[size_t(c.a)];
    Group& gb = groups[size_t(c.b)];
    if (!ga.alive || !gb.alive || ga.version != c.versionA || gb.version != c.versionB) continue;
    const auto it = ga.neighbours.find(c.b);
    if (it == ga.neighbours.end() || !shouldMerge(ga, gb, it->second, params, minVoxels, h)) continue;
    // Keep the group with more neighbours, fold the other into it.
    const int keep = ga.neighbours.size() >= gb.neighbours.size() ? c.a : c.b;
    const int gone = keep == c.a ? c.b : c.a;
    fold(groups, keep, gone);
    mergedInto[size_t(gone)] = keep;
    pushAll(keep);
  }

  auto root = [&](int b) {
    while (mergedInto[size_t(b)] != b) b = mergedInto[size_t(b)];
    return b;
  };
  // The outside is kept only where it meets a room (an open door, a window): around a closed building
  // it stays unlabelled, as before the outside was a region. With no room at all it is the one cell.
  const int outsideRoot = basins.outsideBasin >= 0 ? root(basins.outsideBasin) : -1;
  bool anyRoom = false;
  for (int b = 0; b < count; ++b)
    anyRoom = anyRoom || (root(b) != outsideRoot && groups[size_t(root(b))].volume >= minVoxels);
  // A closed group too thin for a room. The peak is measured to the nearest solid voxel's centre; the
  // surface lies about half a voxel nearer, so a cavity one voxel thick reads as h deep at any voxel
  // (0.4 m at a game level's 0.4 m).
  auto tooThin = [&](const Group& g) {
    return g.neighbours.empty() &&
           (g.peak - 0.5 * h < params.minClosedPeak || g.peak < params.minClosedPeakVoxels * h);
  };
  // Unless every room is: then they are what space the scene has (a decomposition of no cell says nothing).
  bool anyThickRoom = false;
  for (int b = 0; b < count; ++b)
    anyThickRoom = anyThickRoom || (root(b) != outsideRoot && groups[size_t(root(b))].volume >= minVoxels &&
                                    !tooThin(groups[size_t(root(b))]));
  auto kept = [&](int r) {
    if (r == outsideRoot) return !anyRoom || !groups[size_t(r)].neighbours.empty();
    const Group& g = groups[size_t(r)];
    return g.volume >= minVoxels && !(anyThickRoom && tooThin(g));
  };
  CellLabels out;
  out.frame = f;
  out.cellOfBasin.assign(size_t(count), -1);
  std::vector<int> cellOfGroup(size_t(count), -1);
  for (int b = 0; b < count; ++b)
    if (root(b) != outsideRoot && !kept(root(b))) ++out.droppedBasins;
  // Rooms numbered by their lowest voxel, the outside last.
  std::vector<int> rootOf(static_cast<size_t>(count));
  for (int b = 0; b < count; ++b) rootOf[size_t(b)] = root(b);
  for (size_t i = 0; i < basins.basin.size(); ++i) {
    const int b = basins.basin[i];
    if (b < 0) continue;
    const int r = rootOf[size_t(b)];
    if (r == outsideRoot || !kept(r) || cellOfGroup[size_t(r)] >= 0) continue;
    cellOfGroup[size_t(r)] = out.cellCount();
    out.peak.push_back(groups[size_t(r)].peak);
    out.volume.push_back(0);
  }
  if (outsideRoot >= 0 && kept(outsideRoot)) {
    out.outsideCell = cellOfGroup[size_t(outsideRoot)] = out.cellCount();
    out.peak.push_back(groups[size_t(outsideRoot)].peak);
    out.volume.push_back(0);
  }
  for (int b = 0; b < count; ++b) out.cellOfBasin[size_t(b)] = cellOfGroup[size_t(rootOf[size_t(b)])];
  // The basins' labels become the cells', in place.
  out.cell = std::move(basins.basin);
  for (int32_t& label : out.cell) {
    if (label < 0) continue;
    label = out.cellOfBasin[size_t(label)];
    if (label >= 0) ++out.volume[size_t(label)];
  }
  ctx.progress("merge", 1.0);
  return out;
}

}  // namespace cpgi::decomp
