#include "decomposition/volume_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "core/error.h"
#include "decomposition/voxelize.h"

namespace cpgi::decomp {
namespace {

bool isEmpty(Space s) {
  return s == Space::Inside || s == Space::Outside;
}

// Breadth-first from every voxel already in `queue`, into the empty unlabelled voxels `may` allows,
// each taking the label of the voxel it was reached from; `steps` (when given) gets the number of steps.
template <class May>
void grow(const GridFrame& f, std::vector<size_t>& queue, std::vector<int32_t>& label, May&& may,
          std::vector<uint32_t>* steps = nullptr) {
  for (size_t head = 0; head < queue.size(); ++head) {
    const size_t i = queue[head];
    const glm::ivec3 c = f.coord(i);
    for (const auto& d : kFaceNeighbours) {
      const glm::ivec3 nb(c.x + d[0], c.y + d[1], c.z + d[2]);
      if (!f.contains(nb)) continue;
      const size_t j = f.index(nb);
      if (label[j] >= 0 || !may(j)) continue;
      label[j] = label[i];
      if (steps) (*steps)[j] = (*steps)[i] + 1;
      queue.push_back(j);
    }
  }
}

std::vector<size_t> labelled(const std::vector<int32_t>& label) {
  std::vector<size_t> out;
  for (size_t i = 0; i < label.size(); ++i)
    if (label[i] >= 0) out.push_back(i);
  return out;
}

// Empty voxels that no volume holds, further than `reachSteps` from every volume, connected to the
// grid's border: the space around the building and whatever of it comes in through its openings.
void labelOutside(const GridFrame& f, const std::vector<Space>& space, const std::vector<uint32_t>& steps,
                  uint32_t reachSteps, int32_t outside, std::vector<int32_t>& label) {
  std::vector<int32_t> scratch = label;
  auto open = [&](size_t i) { return isEmpty(space[i]) && label[i] < 0 && steps[i] > reachSteps; };
  std::vector<size_t> queue;
  for (size_t i = 0; i < label.size(); ++i) {
    const glm::ivec3 c = f.coord(i);
    const bool border =
        c.x == 0 || c.y == 0 || c.z == 0 || c.x == f.dims.x - 1 || c.y == f.dims.y - 1 || c.z == f.dims.z - 1;
    if (border && open(i)) scratch[i] = outside, queue.push_back(i);
  }
  grow(f, queue, scratch, open);
  label = std::move(scratch);
}

bool touches(const GridFrame& f, const std::vector<int32_t>& label, int32_t a) {
  for (size_t i = 0; i < label.size(); ++i) {
    if (label[i] != a) continue;
    const glm::ivec3 c = f.coord(i);
    for (const auto& d : kFaceNeighbours) {
      const glm::ivec3 nb(c.x + d[0], c.y + d[1], c.z + d[2]);
      if (f.contains(nb) && label[f.index(nb)] >= 0 && label[f.index(nb)] != a) return true;
    }
  }
  return false;
}

// The mesh's pieces connected by shared corners (to 0.1 mm): a room given as several boxes that overlap is
// filled box by box, since the parity of crossings of the union would leave the overlap out.
std::vector<std::vector<Triangle>> connectedPieces(const std::vector<Triangle>& mesh) {
  std::vector<size_t> parent(mesh.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto root = [&](size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::array<int64_t, 3>, size_t> firstAt;
  for (size_t t = 0; t < mesh.size(); ++t)
    for (const glm::vec3& p : mesh[t].p) {
      const std::array<int64_t, 3> k{std::llround(p.x * 1e4), std::llround(p.y * 1e4),
                                     std::llround(p.z * 1e4)};
      const auto [it, fresh] = firstAt.emplace(k, t);
      if (!fresh) parent[root(t)] = root(it->second);
    }
  std::map<size_t, std::vector<Triangle>> pieces;
  for (size_t t = 0; t < mesh.size(); ++t) pieces[root(t)].push_back(mesh[t]);
  std::vector<std::vector<Triangle>> out;
  for (auto& [r, piece] : pieces) out.push_back(std::move(piece));
  return out;
}

void fillClosedMesh(const std::vector<Triangle>& mesh, const GridFrame& f, const std::vector<Space>& space,
                    int32_t label, std::vector<int32_t>& out) {
  Bounds b;
  for (const Triangle& t : mesh)
    for (const glm::vec3& q : t.p) b.extend(q);
  if (b.empty()) return;
  const glm::ivec3 lo = glm::max(f.voxelOf(b.lo), glm::ivec3(0)), hi = glm::min(f.voxelOf(b.hi), f.dims - 1);
  // Crossings with the side they cross from: a row through an edge shared by two triangles of one face
  // (a quad's diagonal) meets both, which would flip the parity; one crossing per face and side is kept.
  std::vector<std::pair<double, int>> xs;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y) {
      const glm::vec3 row = f.centre(glm::ivec3(0, y, z));
      xs.clear();
      for (const Triangle& t : mesh) {
        // Where the line (·, row.y, row.z) meets the triangle, by 2D barycentrics in the y-z plane.
        const glm::dvec2 a(t.p[0].y, t.p[0].z), bb(t.p[1].y, t.p[1].z), c(t.p[2].y, t.p[2].z),
            p(row.y, row.z);
        const double det = (bb.x - a.x) * (c.y - a.y) - (c.x - a.x) * (bb.y - a.y);
        if (std::abs(det) < 1e-12) continue;
        const double u = ((p.x - a.x) * (c.y - a.y) - (c.x - a.x) * (p.y - a.y)) / det;
        const double v = ((bb.x - a.x) * (p.y - a.y) - (p.x - a.x) * (bb.y - a.y)) / det;
        if (u < 0 || v < 0 || u + v > 1) continue;
        xs.emplace_back(t.p[0].x + u * (t.p[1].x - t.p[0].x) + v * (t.p[2].x - t.p[0].x), det > 0 ? 1 : -1);
      }
      std::sort(xs.begin(), xs.end());
      xs.erase(std::unique(xs.begin(), xs.end(),
                           [](const auto& l, const auto& r) {
                             return l.second == r.second && std::abs(l.first - r.first) < 1e-6;
                           }),
               xs.end());
      for (size_t k = 0; k + 1 < xs.size(); k += 2)
        for (int x = lo.x; x <= hi.x; ++x) {
          const double cx = f.origin.x + f.voxel * x;
          const size_t i = f.index(x, y, z);
          // Outside voxels too: the rooms of a building whose doors stand open are reachable from the bounds.
          if (cx >= xs[k].first && cx <= xs[k + 1].first && isEmpty(space[i]) && out[i] < 0) out[i] = label;
        }
    }
}

}  // namespace

void labelVolumeVoxels(const std::vector<Triangle>& mesh, const GridFrame& f, const std::vector<Space>& space,
                       int32_t label, std::vector<int32_t>& out) {
  for (const std::vector<Triangle>& piece : connectedPieces(mesh))
    fillClosedMesh(piece, f, space, label, out);
}

Decomposition decomposeFromVolumes(const Scene& scene, const CellGraph& volumes,
                                   const DecomposeParams& params, const VolumeCellsParams& volumeParams,
                                   Context& ctx) {
  checkDecomposeInput(scene, params);
  if (!(volumeParams.reach >= 0.0 && volumeParams.reach <= 10.0))
    throw InputError("volume reach", "must be in [0, 10] metres");
  const Scene withUnseen = withUnseenSurfaces(scene);
  const Scene& surfaces = hasUnseenSurfaces(scene) ? withUnseen : scene;
  EmptySpace empty = voxelizeEmptySpace(surfaces, params, ctx);
  const double h = empty.voxelSize;
  const SolidGrid& solid = empty.solid;
  SpaceGrid& space = empty.space;
  const DistanceGrid& distance = empty.distance;

  std::optional<Context::ScopedTimer> timer;
  timer.emplace(ctx, "volumes");
  const GridFrame& f = solid.frame;
  const int32_t rooms = int32_t(volumes.cells.size());
  std::vector<int32_t> label(f.count(), -1);
  std::vector<std::string> names;
  std::vector<size_t> held(size_t(rooms), 0);
  for (int32_t c = 0; c < rooms; ++c) {
    names.push_back(volumes.cells[size_t(c)].name);
    labelVolumeVoxels(volumes.cells[size_t(c)].volume, f, space.space, c, label);
  }
  for (int32_t l : label)
    if (l >= 0) ++held[size_t(l)];
  std::ostringstream voxelText;
  voxelText << h << " m voxels";
  if (std::all_of(held.begin(), held.end(), [](size_t n) { return n == 0; }))
    throw InputError(params.sourceName, "no cellvolume: mesh holds empty space at " + voxelText.str() +
                                            " (are the volumes closed meshes around the rooms?)");
  for (int32_t c = 0; c < rooms; ++c)
    if (held[size_t(c)] == 0 && !volumes.cells[size_t(c)].volume.empty())
      ctx.warn("cellvolume:" + names[size_t(c)] + ": holds no empty voxel at " + voxelText.str());

  // Steps from the nearest volume through the empty space no volume holds.
  std::vector<uint32_t> steps(f.count(), std::numeric_limits<uint32_t>::max());
  {
    std::vector<int32_t> reached = label;
    std::vector<size_t> queue = labelled(label);
    for (size_t i : queue) steps[i] = 0;
    grow(
        f, queue, reached, [&](size_t j) { return isEmpty(space.space[j]); }, &steps);
  }
  const uint32_t reachSteps = uint32_t(std::max(1.0, std::ceil(volumeParams.reach / h)));
  const int named = volumes.findCell("outside");
  const int32_t outside = named >= 0 ? int32_t(named) : rooms;
  labelOutside(f, space.space, steps, reachSteps, outside, label);
  // The rest (doorways, a slab's depth under a stair's hole, closets no volume gives) goes to whichever
  // volume or the outside reaches it first, all growing at once: two volumes meet mid-way.
  {
    std::vector<size_t> queue = labelled(label);
    grow(f, queue, label, [&](size_t j) { return isEmpty(space.space[j]); });
  }
  int outsideCell = outside;
  if (named < 0) {
    if (touches(f, label, outside)) {
      names.push_back("outside");
    } else {  // a closed building: the space around it is no cell
      std::replace(label.begin(), label.end(), outside, int32_t(-1));
      outsideCell = -1;
    }
  }

  CellLabels cells;
  cells.frame = f;
  cells.peak.assign(names.size(), 0.0f);
  cells.volume.assign(names.size(), 0);
  cells.outsideCell = outsideCell;
  for (size_t i = 0; i < label.size(); ++i)
    if (label[i] >= 0) {
      cells.peak[size_t(label[i])] = std::max(cells.peak[size_t(label[i])], float(distance.metres(i)));
      ++cells.volume[size_t(label[i])];
    }
  cells.cell = std::move(label);
  timer.reset();
  // The rooms are the user's: a pair the leak pass cannot part keeps its leaking faces, never merges.
  DecomposeParams roomsKept = params;
  roomsKept.leaks.merge = false;
  roomsKept.dropUnfacedClosedCells = false;
  Decomposition out = finishDecomposition(scene, surfaces, roomsKept, solid, std::move(space.space), distance,
                                          std::move(cells), names, ctx);
  out.voxelChoice = empty.voxelChoice + "; cells from " + std::to_string(rooms) + " cellvolume: meshes";
  return out;
}

int nameCellsByVolumes(Decomposition& d, const CellGraph& rooms, double leastShare) {
  const size_t cellCount = d.graph.cells.size();
  std::vector<int32_t> room(d.voxelCell.size(), -1);
  for (size_t r = 0; r < rooms.cells.size(); ++r)
    if (!rooms.cells[r].volume.empty() && rooms.cells[r].name != "outside")
      labelVolumeVoxels(rooms.cells[r].volume, d.frame, d.space, int32_t(r), room);
  // Per cell, its voxels under each room volume.
  std::vector<std::map<int32_t, size_t>> under(cellCount);
  std::vector<size_t> voxels(cellCount, 0);
  for (size_t i = 0; i < d.voxelCell.size(); ++i) {
    const int32_t c = d.voxelCell[i];
    if (c < 0 || size_t(c) >= cellCount || c == d.outsideCell) continue;
    ++voxels[size_t(c)];
    if (room[i] >= 0) ++under[size_t(c)][room[i]];
  }
  std::set<std::string> taken;
  for (const Cell& c : d.graph.cells) taken.insert(c.name);
  int renamed = 0;
  for (size_t c = 0; c < cellCount; ++c) {
    if (int(c) == d.outsideCell || under[c].empty()) continue;
    const auto best = std::max_element(under[c].begin(), under[c].end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    if (double(best->second) < leastShare * double(voxels[c])) continue;
    const std::string& name = rooms.cells[size_t(best->first)].name;
    std::string unique = name;
    for (int k = 2; taken.count(unique); ++k) unique = name + "-" + std::to_string(k);
    taken.insert(unique);
    d.graph.cells[c].name = unique;
    ++renamed;
  }
  for (PortalQuad& q : d.graph.portals)
    q.name = "portal:" + d.graph.cells[size_t(q.cellA)].name + ":" + d.graph.cells[size_t(q.cellB)].name;
  return renamed;
}

}  // namespace cpgi::decomp
