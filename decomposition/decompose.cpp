#include "decomposition/decompose.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "decomposition/distance.h"
#include "decomposition/voxelize.h"
#include "decomposition/wall_portals.h"

namespace cpgi::decomp {
namespace {

std::string metres(double v) {
  std::ostringstream s;
  s << v << " m";
  return s.str();
}

}  // namespace

void checkDecomposeInput(const Scene& scene, const DecomposeParams& p) {
  if (scene.triangles.empty()) throw InputError(p.sourceName, "the scene has no triangles");
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    for (const glm::vec3& q : scene.triangles[t].p)
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        throw InputError(p.sourceName, "triangle " + std::to_string(t) + " has a non-finite coordinate");
  if (p.voxelSize < 0.0 || p.voxelSize > 10.0 || !std::isfinite(p.voxelSize))
    throw InputError("voxel size", "must be in (0, 10] metres (0 chooses from the scene)");
  if (p.sealRadius < 0.0 || p.sealRadius > 1.0 || !std::isfinite(p.sealRadius))
    throw InputError("seal radius", "must be in [0, 1] metres");
  if (p.merge.saddleRatio < 0.0 || p.merge.saddleRatio > 1.0)
    throw InputError("saddle ratio", "must be in [0, 1]");
  if (!(p.merge.outsideSaddleRatio >= 0.0 && p.merge.outsideSaddleRatio <= 1.0))
    throw InputError("outside saddle ratio", "must be in [0, 1]");
  if (p.merge.minDepth < 0.0) throw InputError("minimum depth", "must be ≥ 0");
  if (p.merge.minCellVolume < 0.0) throw InputError("minimum cell volume", "must be ≥ 0");
  if (p.merge.openingRatio < 0.0) throw InputError("opening ratio", "must be ≥ 0");
  if (!(p.merge.galleryFloorRise >= 0.0)) throw InputError("gallery floor rise", "must be ≥ 0 metres");
  if (!(p.merge.galleryHeadroom >= 0.0)) throw InputError("gallery headroom", "must be ≥ 0 metres");
}

namespace {

// The automatic voxel for a grid over `size` metres: max(minAutoVoxel, cbrt(padded volume / budget)),
// rounded up to a whole millimetre; `volume` gets the padded volume.
double autoVoxel(glm::dvec3 size, const DecomposeParams& params, double& volume) {
  size += 0.5;  // padded so flat scenes get a volume
  volume = size.x * size.y * size.z;
  const double fromBudget = std::cbrt(volume / params.autoVoxelBudget);
  return std::ceil(std::max(params.minAutoVoxel, fromBudget) * 1000.0) / 1000.0;
}

// Where the budget's voxel would leave the level's narrow passages fewer than voxelsAcrossPassage voxels
// across, the voxel that spans them, no finer than maxAutoVoxels over `volume` (nor memoryLimit) allows;
// sets grid.voxel and grid.passage, returns the rule's words ("" when the budget's voxel stays).
std::string finerForThePassages(const Scene& scene, double volume, const DecomposeParams& params,
                                GridChoice& grid, Context& ctx) {
  auto timer = ctx.time("voxelize.passages");
  grid.passage = measurePassages(scene, grid.extent.box, params.passages).narrow;
  const double fromPassages = grid.passage / params.voxelsAcrossPassage;
  if (!(grid.passage > 0.0) || fromPassages >= grid.voxel) return "";
  double most = params.maxAutoVoxels;
  if (params.memoryLimit > 0) most = std::min(most, double(params.memoryLimit) / kDecompositionBytesPerVoxel);
  const double fromMemory = std::cbrt(volume / std::max(most, params.autoVoxelBudget));
  const double finer = std::ceil(std::max({params.minAutoVoxel, fromMemory, fromPassages}) * 1000.0) / 1000.0;
  if (finer >= grid.voxel) return "";
  grid.voxel = finer;
  std::ostringstream s;
  s << "; finer for the passages: " << params.voxelsAcrossPassage << " voxels across " << grid.passage
    << " m (the narrowest " << params.passages.quantile * 100.0
    << " % of the floor's widths), within cbrt(volume / " << most << " voxels) = " << fromMemory << " m";
  return s.str();
}

}  // namespace

GridChoice chooseGrid(const Scene& scene, const DecomposeParams& params, Context& ctx) {
  GridChoice out;
  double boundsVolume = 0.0;
  autoVoxel(glm::dvec3(scene.bounds().size()), params, boundsVolume);
  // The coarse pass costs its band (surface / voxel²) and its columns (footprint / voxel²): as fine as
  // extentBudget of each allows, so a house's 3 m rooms on a square kilometre of terrain are still seen.
  double area = 0.0;
  for (const Triangle& t : scene.triangles) area += double(t.area());
  const glm::dvec3 size = glm::dvec3(scene.bounds().size());
  RoomExtentParams ep;
  ep.voxel =
      std::max(params.minExtentVoxel, std::sqrt(std::max(area, size.x * size.z) / params.extentBudget));
  ep.coverHeight = VoxelizeParams().coverHeight;
  ep.margin = params.outsideMargin;
  ep.minPartShare = params.minPartShare;
  out.extent = findRoomExtent(scene, ep, ctx);
  double volume = 0.0;
  const double fromBudget = autoVoxel(glm::dvec3(out.extent.box.size()), params, volume);
  std::ostringstream s;
  if (params.voxelSize > 0.0) {
    out.voxel = params.voxelSize;
    s << "given";
  } else {
    out.voxel = fromBudget;
    s << "auto: max(" << params.minAutoVoxel << " m, cbrt(padded "
      << (out.extent.trimmed ? "rooms'" : "bounds") << " volume " << volume << " m3 / "
      << params.autoVoxelBudget << " voxels) = " << std::cbrt(volume / params.autoVoxelBudget)
      << " m), rounded up to 1 mm";
    if (fromBudget > params.passageCheckVoxel) s << finerForThePassages(scene, volume, params, out, ctx);
  }
  if (out.extent.trimmed) {
    const Bounds& b = out.extent.box;
    s << "; the grid spans where the rooms are, " << out.extent.keptParts << " of " << out.extent.parts
      << " parts of covered ground (x " << b.lo.x << "…" << b.hi.x << ", y " << b.lo.y << "…" << b.hi.y
      << ", z " << b.lo.z << "…" << b.hi.z << " m; the bounds' padded volume " << boundsVolume << " m3), "
      << out.extent.farTriangles << " triangles wholly past it";
  }
  out.how = s.str();
  return out;
}

double chooseVoxelSize(const Scene& scene, const DecomposeParams& params, std::string* how) {
  Context ctx;
  GridChoice g = chooseGrid(scene, params, ctx);
  if (how) *how = std::move(g.how);
  return g.voxel;
}

Scene withUnseenSurfaces(const Scene& scene) {
  Scene out;
  if (!hasUnseenSurfaces(scene)) return out;
  out.triangles.reserve(scene.triangles.size() + scene.buriedPieces.size() + scene.seal.size());
  out.triangles = scene.triangles;
  out.triangles.insert(out.triangles.end(), scene.buriedPieces.begin(), scene.buriedPieces.end());
  out.triangles.insert(out.triangles.end(), scene.seal.begin(), scene.seal.end());
  return out;
}

EmptySpace voxelizeEmptySpace(const Scene& scene, const DecomposeParams& params, Context& ctx) {
  EmptySpace e;
  const GridChoice grid = chooseGrid(scene, params, ctx);
  e.voxelSize = grid.voxel;
  e.voxelChoice = grid.how;
  if (grid.extent.farTriangles > 0)
    ctx.warn("decompose: " + params.sourceName + ": " + std::to_string(grid.extent.farTriangles) +
             " triangles lie past the grid round the rooms (far scenery, " +
             std::to_string(grid.extent.parts - grid.extent.keptParts) +
             " parts of covered ground left out): each goes to the nearest cell");
  VoxelizeParams vp;
  vp.voxelSize = e.voxelSize;
  vp.sealRadius = params.sealRadius;
  vp.memoryLimit = params.memoryLimit;
  vp.outsideMargin = params.outsideMargin;
  if (grid.extent.trimmed) vp.extent = grid.extent.box;
  e.solid = voxelize(scene, vp, ctx);
  e.space = classifySpace(scene, e.solid, params.classify, ctx);
  e.distance = distanceToGeometry(e.solid, e.space, ctx);
  return e;
}

std::vector<std::string> roomNames(const std::vector<CellStats>& stats, int outsideCell) {
  // Storeys: the cells' floors (the bottom of their empty voxels) sorted, a new storey wherever one
  // floor stands 1.5 m or more above the one below it, as decomposition.png's plans are cut.
  std::vector<size_t> order;
  for (size_t c = 0; c < stats.size(); ++c)
    if (int(c) != outsideCell) order.push_back(c);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return stats[a].bounds.lo.y < stats[b].bounds.lo.y; });
  std::vector<int> storey(stats.size(), 0);
  for (size_t k = 0; k < order.size(); ++k)
    storey[order[k]] = k == 0 ? 1
                              : storey[order[k - 1]] +
                                    (stats[order[k]].bounds.lo.y - stats[order[k - 1]].bounds.lo.y >= 1.5f);
  std::vector<std::string> names(stats.size());
  std::map<std::string, int> taken;
  for (size_t c = 0; c < stats.size(); ++c) {
    if (int(c) == outsideCell) continue;
    const double height = std::max(1e-6, double(stats[c].bounds.size().y));
    const long area = std::lround(stats[c].volume / height);
    const std::string name = "s" + std::to_string(storey[c]) + "-" + std::to_string(area) + "m2";
    const int seen = ++taken[name];
    names[c] = seen == 1 ? name : name + "-" + std::to_string(seen);
  }
  return names;
}

Decomposition decompose(const Scene& scene, const DecomposeParams& params, Context& ctx) {
  checkDecomposeInput(scene, params);
  const Scene withUnseen = withUnseenSurfaces(scene);
  const Scene& surfaces = hasUnseenSurfaces(scene) ? withUnseen : scene;
  EmptySpace empty = voxelizeEmptySpace(surfaces, params, ctx);
  const double h = empty.voxelSize;
  const SolidGrid& solid = empty.solid;
  SpaceGrid& space = empty.space;
  // The watershed runs over all empty space, the outside included (its basin grows from the grid's
  // border); interior cells meet the outside at exterior doors and open windows.
  const DistanceGrid& distance = empty.distance;
  WatershedLabels basins = floodWatershed(distance, params.watershed, ctx);
  const int basinCount = basins.basinCount();
  CellLabels cells = mergeBasins(std::move(basins), params.merge, ctx);
  const FoldedCells folded = foldCellsBehindGeometry(cells, surfaces, solid, space.space, params.behind, ctx);
  std::vector<std::string> names;
  for (int c = 0; c < cells.cellCount(); ++c)
    names.push_back(c == cells.outsideCell ? std::string("outside") : "c" + std::to_string(c));
  if (cells.roomCount() == 0)
    ctx.warn("decompose: " + params.sourceName + ": " +
             (space.insideVoxels == 0 && cells.cellCount() <= 1
                  ? "no enclosed empty space"
                  : "no room larger than the minimum cell volume") +
             " at " + metres(h) + " voxels; the whole scene is one outside cell");
  Decomposition out = finishDecomposition(scene, surfaces, params, solid, std::move(space.space), distance,
                                          std::move(cells), names, ctx);
  // Named once merged (the leak pass merges too): by storey and floor area, as a person would find them.
  const std::vector<std::string> rooms = roomNames(out.cellStats, out.outsideCell);
  for (size_t c = 0; c < out.graph.cells.size(); ++c)
    if (int(c) != out.outsideCell) out.graph.cells[c].name = rooms[c];
  for (PortalQuad& q : out.graph.portals)
    q.name = "portal:" + out.graph.cells[size_t(q.cellA)].name + ":" + out.graph.cells[size_t(q.cellB)].name;
  out.covered = coveredSpace(out.frame, out.space, out.voxelCell, out.outsideCell);
  if (out.covered.outsideShare() > kLeakedOutsideShare)
    ctx.warn("decompose: " + params.sourceName + ": the outside holds " +
             std::to_string(std::lround(100.0 * out.covered.outsideShare())) +
             " % of the empty space under a roof: the faces do not close this level and the outside "
             "flooded its rooms through a gap; give the scene its seal (a seal: mesh of the solids that "
             "close it, as q3bsp_to_obj writes a map's brushes) or close the gap (--seal METRES)");
  out.voxelChoice = std::move(empty.voxelChoice);
  out.basins = basinCount;
  out.foldedBehind = folded.folded;
  return out;
}

namespace {

// Each cell's voxels and their extent in voxel coordinates, walked in storage order (no division per
// voxel), then its bounds from the extreme voxels' cubes and its volume.
void measureCells(Decomposition& out, int cellCount, double h) {
  std::vector<glm::ivec3> lowest(size_t(cellCount), glm::ivec3(INT32_MAX)),
      highest(size_t(cellCount), glm::ivec3(-1));
  const GridFrame& f = out.frame;
  size_t i = 0;
  for (int z = 0; z < f.dims.z; ++z)
    for (int y = 0; y < f.dims.y; ++y)
      for (int x = 0; x < f.dims.x; ++x, ++i) {
        const int c = out.voxelCell[i];
        if (c < 0 || c >= cellCount) continue;
        ++out.cellStats[size_t(c)].voxels;
        lowest[size_t(c)] = glm::min(lowest[size_t(c)], glm::ivec3(x, y, z));
        highest[size_t(c)] = glm::max(highest[size_t(c)], glm::ivec3(x, y, z));
      }
  const glm::vec3 half(float(0.5 * h));
  for (int c = 0; c < cellCount; ++c)
    if (out.cellStats[size_t(c)].voxels > 0) {
      Bounds& b = out.cellStats[size_t(c)].bounds;
      b.extend(f.centre(lowest[size_t(c)]) - half), b.extend(f.centre(highest[size_t(c)]) + half);
    }
  for (CellStats& s : out.cellStats) s.volume = double(s.voxels) * out.frame.voxelVolume();
}

// The parts of the portal graph (Decomposition::regions): closed rooms are parts of their own; the
// outside's part, when it holds no other, is the outside and its pockets (outsidePocket, connectedOpen).
void markParts(Decomposition& out, int cellCount) {
  std::vector<int> part(size_t(cellCount), -1);
  int parts = 0;
  for (int c = 0; c < cellCount; ++c) {
    if (part[size_t(c)] >= 0) continue;
    std::vector<int> todo{c};
    part[size_t(c)] = parts;
    while (!todo.empty()) {
      const int x = todo.back();
      todo.pop_back();
      for (int p : out.graph.portalsOf(x)) {
        const PortalQuad& q = out.graph.portals[size_t(p)];
        const int y = q.cellA == x ? q.cellB : q.cellA;
        if (y >= 0 && part[size_t(y)] < 0) part[size_t(y)] = parts, todo.push_back(y);
      }
    }
    ++parts;
  }
  out.regions = parts;
  int closedParts = 0;
  for (int c = 0; c < cellCount; ++c) closedParts += out.closedRoom[size_t(c)] ? 1 : 0;
  out.outsidePocket.assign(size_t(cellCount), 0);
  const int openParts = parts - closedParts;
  if (out.outsideCell >= 0 && openParts > 1) {
    // The outside's part is apart from the rooms: it and its pockets are not counted against them.
    for (int c = 0; c < cellCount; ++c)
      out.outsidePocket[size_t(c)] = c != out.outsideCell && part[size_t(c)] == part[size_t(out.outsideCell)];
    out.connectedOpen = openParts - 1 <= 1;
  } else {
    out.connectedOpen = openParts <= 1;
  }
  std::vector<double> volume(size_t(parts), 0.0);
  for (int c = 0; c < cellCount; ++c)
    if (c != out.outsideCell) volume[size_t(part[size_t(c)])] += out.cellStats[size_t(c)].volume;
  const int mainPart = int(std::max_element(volume.begin(), volume.end()) - volume.begin());
  out.reachable.assign(size_t(cellCount), 0);
  out.reachableOrClosed = true;
  for (int c = 0; c < cellCount; ++c) {
    out.reachable[size_t(c)] = !out.closedRoom[size_t(c)] && part[size_t(c)] == mainPart;
    out.reachableOrClosed = out.reachableOrClosed && (out.reachable[size_t(c)] || out.closedRoom[size_t(c)]);
  }
}

// Drops the closed cells (no portal, not the outside) that no triangle was given to, unless that would
// leave no room: their voxels become unlabelled and the cells after each move down. Run once the
// triangles are assigned and the portals made; returns how many were dropped.
int dropUnfacedClosedCells(Decomposition& out) {
  const int n = int(out.graph.cells.size());
  std::vector<int> newIndex(size_t(n), -1);
  int kept = 0, rooms = 0;
  for (int c = 0; c < n; ++c) {
    const bool unfaced = c != out.outsideCell && out.graph.cells[size_t(c)].triangles.empty() &&
                         out.graph.portalsOf(c).empty();
    if (!unfaced) newIndex[size_t(c)] = kept++, rooms += c != out.outsideCell;
  }
  if (kept == n || rooms == 0) return 0;
  for (int c = n; c-- > 0;)
    if (newIndex[size_t(c)] < 0) {
      out.graph.cells.erase(out.graph.cells.begin() + c);
      out.cellStats.erase(out.cellStats.begin() + c);
    }
  for (int32_t& c : out.voxelCell)
    if (c >= 0) c = newIndex[size_t(c)];
  for (PortalQuad& q : out.graph.portals)
    q.cellA = newIndex[size_t(q.cellA)], q.cellB = newIndex[size_t(q.cellB)];
  for (FittedPortal& fp : out.portals)
    fp.quad.cellA = newIndex[size_t(fp.quad.cellA)], fp.quad.cellB = newIndex[size_t(fp.quad.cellB)];
  if (out.outsideCell >= 0) out.outsideCell = newIndex[size_t(out.outsideCell)];
  return n - kept;
}

}  // namespace

Decomposition finishDecomposition(const Scene& scene, const Scene& surfaces, const DecomposeParams& params,
                                  const SolidGrid& solid, std::vector<Space> space,
                                  const DistanceGrid& distance, CellLabels cells,
                                  const std::vector<std::string>& names, Context& ctx) {
  Decomposition out;
  const double h = solid.frame.voxel;
  out.frame = solid.frame;
  out.sealedVoxels = solid.sealedVoxels;
  const int outsideBefore = cells.outsideCell;
  const std::vector<float> peaksBefore = cells.peak;
  PortalSet portals = fitPortals(std::move(cells), distance, params.portals, ctx);
  // Every face between two cells on a portal of theirs, or the two merged (leaks.h).
  const ClosedLeaks closed =
      closeLeaks(portals, distance, int(peaksBefore.size()), outsideBefore, params.leaks, ctx);
  const MergedPortals merged = mergePortalPieces(portals, solid.frame, params.portalMerge, ctx);
  snapPortalsToWalls(surfaces, solid.frame, params.portals.searchRange, portals, ctx);
  std::vector<float> peaks(size_t(closed.cellCount), 0.0f);
  for (size_t c = 0; c < peaksBefore.size(); ++c)
    if (closed.cellOf[c] >= 0)
      peaks[size_t(closed.cellOf[c])] = std::max(peaks[size_t(closed.cellOf[c])], peaksBefore[c]);
  std::vector<std::string> keptNames;
  for (int32_t c : closed.keptCell) keptNames.push_back(names[size_t(c)]);
  out.outsideCell = closed.outsideCell;
  out.enclosed = closed.cellCount - (out.outsideCell >= 0 ? 1 : 0) > 0;
  out.leakMerges = closed.mergedPairs;
  out.leakPlacements = closed.placements;
  out.mergedPortalPieces = merged.merged;
  out.voxelCell = std::move(portals.cell);
  out.leakingFaces = portals.leakingFaces;
  std::vector<PortalQuad> quads;
  for (FittedPortal& fp : portals.portals) {
    fp.quad.name = "portal:" + keptNames[size_t(fp.quad.cellA)] + ":" + keptNames[size_t(fp.quad.cellB)];
    quads.push_back(fp.quad);
  }
  out.portals = std::move(portals.portals);
  if (out.leakMerges > 0)
    ctx.warn("decompose: " + params.sourceName + ": " + std::to_string(out.leakMerges) +
             " pairs of cells merged: they met outside any portal of theirs");
  if (out.leakingFaces > 0)
    ctx.warn("decompose: " + params.sourceName + ": " + std::to_string(out.leakingFaces) +
             " voxel faces join two cells outside any portal");
  out.space = std::move(space);

  Assignment assigned =
      assignTriangles(scene, out.frame, out.voxelCell, quads, out.outsideCell, params.assign, ctx);
  out.inputTriangles = scene.triangles.size();
  out.scene = std::move(assigned.scene);
  out.splitTriangles = assigned.splitTriangles;
  out.fallbackTriangles = assigned.fallbackTriangles;
  out.thinWallArea = assigned.thinWallArea;

  // The graph, and per-cell statistics from the final labels.
  int cellCount = int(peaks.size());
  out.graph.cells.resize(size_t(cellCount));
  out.cellStats.resize(size_t(cellCount));
  for (int c = 0; c < cellCount; ++c) {
    out.graph.cells[size_t(c)].name = keptNames[size_t(c)];
    out.cellStats[size_t(c)].peak = peaks[size_t(c)];
  }
  for (size_t t = 0; t < assigned.cellOfTriangle.size(); ++t) {
    const int c = assigned.cellOfTriangle[t];
    if (c >= 0 && c < cellCount) out.graph.cells[size_t(c)].triangles.push_back(uint32_t(t));
  }
  measureCells(out, cellCount, h);
  out.graph.portals = std::move(quads);
  if (params.dropUnfacedClosedCells) out.droppedUnfaced = dropUnfacedClosedCells(out);
  cellCount = int(out.graph.cells.size());

  // Closed rooms: no portal (after the leak pass no voxel face touches another cell either).
  out.closedRoom.assign(size_t(cellCount), 0);
  for (int c = 0; c < cellCount; ++c)
    out.closedRoom[size_t(c)] = c != out.outsideCell && out.graph.portalsOf(c).empty();
  markParts(out, cellCount);
  for (const std::string& w : validateCells(out.scene, out.graph).warnings) {
    // A closed room is said once below, as what it is.
    if (w == "the cell graph is not connected") continue;
    const std::string noPortal = ": has no portal";
    if (w.size() > noPortal.size() && w.compare(w.size() - noPortal.size(), noPortal.size(), noPortal) == 0)
      continue;
    ctx.warn("decompose: " + params.sourceName + ": " + w);
  }
  for (int c = 0; c < cellCount; ++c)
    if (out.closedRoom[size_t(c)])
      ctx.warn("decompose: " + params.sourceName + ": cell " + out.graph.cells[size_t(c)].name +
               " is a closed room: no portal, it touches no other cell");
  if (!out.connectedOpen)
    ctx.warn("decompose: " + params.sourceName +
             ": the rooms fall in separate groups that no portal joins "
             "(walls seal them from each other)");
  if (out.thinWallArea > 0.1)
    ctx.warn("decompose: " + params.sourceName + ": " + std::to_string(out.thinWallArea) +
             " m2 of wall between two cells is thinner than one voxel (" + metres(h) +
             "); light may leak through it in a bake");
  if (h > 0.125)
    ctx.warn("decompose: " + params.sourceName + ": " + metres(h) + " voxels: doors narrower than " +
             metres(8 * h) + " may not become portals (give a smaller voxel size)");
  return out;
}

}  // namespace cpgi::decomp
