#include "decomposition/voxelize.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/Morphology.h>

#include "core/error.h"
#include "core/memory_limit.h"

namespace cpgi::decomp {
namespace {

// The scene's triangles clipped to a box (grown a little past the grid, so the band at the grid's edge is
// whole): a far terrain or far scenery costs the narrow band nothing. Each piece keeps its source triangle.
struct ClippedTriangles {
  std::vector<std::array<glm::dvec3, 3>> p;
  std::vector<int32_t> source;
  double area = 0.0;  ///< m², of the pieces
};

ClippedTriangles clipToBox(const Scene& scene, const glm::dvec3& lo, const glm::dvec3& hi) {
  ClippedTriangles out;
  std::vector<glm::dvec3> poly, next;
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    const Triangle& tri = scene.triangles[t];
    poly.assign({glm::dvec3(tri.p[0]), glm::dvec3(tri.p[1]), glm::dvec3(tri.p[2])});
    // Sutherland–Hodgman against the six planes; a triangle inside keeps its three corners exactly.
    for (int axis = 0; axis < 3 && !poly.empty(); ++axis)
      for (int side = 0; side < 2 && !poly.empty(); ++side) {
        const double bound = side == 0 ? lo[axis] : hi[axis];
        auto inside = [&](const glm::dvec3& q) { return side == 0 ? q[axis] >= bound : q[axis] <= bound; };
        next.clear();
        for (size_t i = 0; i < poly.size(); ++i) {
          const glm::dvec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
          if (inside(a)) next.push_back(a);
          if (inside(a) != inside(b)) next.push_back(a + (b - a) * ((bound - a[axis]) / (b[axis] - a[axis])));
        }
        poly.swap(next);
      }
    for (size_t i = 1; i + 1 < poly.size(); ++i) {
      out.p.push_back({poly[0], poly[i], poly[i + 1]});
      out.source.push_back(int32_t(t));
      out.area += 0.5 * glm::length(glm::cross(poly[i] - poly[0], poly[i + 1] - poly[0]));
    }
  }
  return out;
}

// meshToVolume's MeshDataAdapter over the clipped triangles, in the grid's index space.
class TriangleAdapter {
 public:
  TriangleAdapter(const ClippedTriangles& tris, const GridFrame& frame) : tris_(tris), frame_(frame) {}
  size_t polygonCount() const { return tris_.p.size(); }
  size_t pointCount() const { return tris_.p.size() * 3; }
  size_t vertexCount(size_t) const { return 3; }
  void getIndexSpacePoint(size_t n, size_t v, openvdb::Vec3d& pos) const {
    const glm::dvec3 q = (tris_.p[n][v] - frame_.origin) / frame_.voxel;
    pos = openvdb::Vec3d(q.x, q.y, q.z);
  }

 private:
  const ClippedTriangles& tris_;
  const GridFrame& frame_;
};

// The voxels whose centre lies within half a voxel of a triangle, as a sparse mask over `f`'s index space
// (OpenVDB's unsigned distance in a 1-voxel band); `nearest` (optional) gets the polygon index grid.
openvdb::MaskGrid solidMaskOf(const ClippedTriangles& tris, const GridFrame& f, openvdb::Int32Grid* nearest) {
  // Index space is our own (see TriangleAdapter); the transform only carries the voxel size, which
  // meshToVolume uses to report distances in metres.
  const auto xform = openvdb::math::Transform::createLinearTransform(f.voxel);
  openvdb::FloatGrid::Ptr udf = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      TriangleAdapter(tris, f), *xform, 1.0f, 1.0f,
      openvdb::tools::UNSIGNED_DISTANCE_FIELD | openvdb::tools::DISABLE_RENORMALIZATION, nearest);
  // Solid where the centre is within half a voxel: then two face neighbours on opposite sides of any
  // plane differ by at most one voxel in distance and cannot both be outside the band.
  const float halfVoxel = float(0.5 * f.voxel) * (1.0f + 1e-4f);
  openvdb::MaskGrid mask;
  auto acc = mask.getAccessor();
  for (auto it = udf->cbeginValueOn(); it; ++it)
    if (*it <= halfVoxel) acc.setValueOn(it.getCoord());
  return mask;
}

// The grid over `box` padded by `pad` voxels of `h` on every side.
GridFrame frameOver(const glm::dvec3& lo, const glm::dvec3& hi, double h, int pad) {
  GridFrame f;
  const glm::dvec3 span = (hi - lo) / h;
  f.voxel = h;
  f.origin = lo - pad * h;
  f.dims = glm::ivec3(int(std::ceil(span.x)) + 2 * pad + 1, int(std::ceil(span.y)) + 2 * pad + 1,
                      int(std::ceil(span.z)) + 2 * pad + 1);
  return f;
}

// Per column (x, z; y is up) of `f`: the lowest and highest solid voxel and how many are solid.
struct Column {
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min(), solid = 0;
  /// At least `gapVoxels` empty voxels between its lowest and highest solid voxel: a floor under a roof.
  bool covered(int gapVoxels) const { return solid > 0 && highest - lowest + 1 - solid >= gapVoxels; }
};

std::vector<Column> solidColumns(const openvdb::MaskGrid& solid, const GridFrame& f) {
  std::vector<Column> columns(size_t(f.dims.x) * size_t(f.dims.z));
  for (auto it = solid.cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    if (!f.contains({c.x(), c.y(), c.z()})) continue;
    Column& col = columns[size_t(c.z()) * size_t(f.dims.x) + size_t(c.x())];
    col.lowest = std::min(col.lowest, c.y()), col.highest = std::max(col.highest, c.y());
    ++col.solid;
  }
  return columns;
}

// The index range [lo, hi] of the grid's covered columns. Empty (lo > hi) when none is.
struct ColumnRange {
  glm::ivec2 lo{std::numeric_limits<int>::max()}, hi{std::numeric_limits<int>::min()};
  bool empty() const { return lo.x > hi.x; }
  void extend(glm::ivec2 c) { lo = glm::min(lo, c), hi = glm::max(hi, c); }
};

ColumnRange coveredColumns(const openvdb::MaskGrid& solid, const GridFrame& f, int gapVoxels) {
  const std::vector<Column> columns = solidColumns(solid, f);
  ColumnRange out;
  for (int z = 0; z < f.dims.z; ++z)
    for (int x = 0; x < f.dims.x; ++x)
      if (columns[size_t(z) * size_t(f.dims.x) + size_t(x)].covered(gapVoxels)) out.extend({x, z});
  return out;
}

// The covered columns' parts: columns within `reach` columns of each other (Chebyshev) are one part.
// Per column of the parts' grown reach its part, -1 elsewhere; `parts` gets the number of parts.
std::vector<int> coveredParts(const std::vector<Column>& columns, glm::ivec2 dims, int gapVoxels, int reach,
                              int& parts) {
  const size_t n = columns.size();
  auto at = [&](int x, int z) { return size_t(z) * size_t(dims.x) + size_t(x); };
  // Grown by `reach`, then 8-connected: two columns `reach` apart meet in the grown mask.
  std::vector<char> grown(n, 0);
  for (int z = 0; z < dims.y; ++z)
    for (int x = 0; x < dims.x; ++x)
      if (columns[at(x, z)].covered(gapVoxels))
        for (int dz = std::max(0, z - reach); dz <= std::min(dims.y - 1, z + reach); ++dz)
          std::fill(grown.begin() + ptrdiff_t(at(std::max(0, x - reach), dz)),
                    grown.begin() + ptrdiff_t(at(std::min(dims.x - 1, x + reach), dz)) + 1, char(1));
  std::vector<int> part(n, -1);
  std::vector<size_t> queue;
  parts = 0;
  for (size_t seed = 0; seed < n; ++seed) {
    if (!grown[seed] || part[seed] >= 0) continue;
    const int label = parts++;
    part[seed] = label, queue.assign(1, seed);
    while (!queue.empty()) {
      const size_t i = queue.back();
      queue.pop_back();
      const int x = int(i % size_t(dims.x)), z = int(i / size_t(dims.x));
      for (int dz = -1; dz <= 1; ++dz)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = x + dx, qz = z + dz;
          if (qx < 0 || qz < 0 || qx >= dims.x || qz >= dims.y) continue;
          const size_t q = at(qx, qz);
          if (grown[q] && part[q] < 0) part[q] = label, queue.push_back(q);
        }
    }
  }
  return part;
}

// The part of the grid `f` to keep: across the horizontal, the covered columns grown by `marginVoxels`
// (clamped to the grid), the whole height; `offset` gets the kept part's first voxel in `f`.
GridFrame cropToCovered(const GridFrame& f, const ColumnRange& covered, double marginVoxels,
                        glm::ivec3& offset) {
  offset = glm::ivec3(0);
  if (covered.empty() || !std::isfinite(marginVoxels)) return f;
  const int margin = int(std::clamp(std::ceil(marginVoxels), 0.0, double(std::max(f.dims.x, f.dims.z))));
  const glm::ivec2 lo = glm::max(covered.lo - margin, glm::ivec2(0));
  const glm::ivec2 hi = glm::min(covered.hi + margin, glm::ivec2(f.dims.x, f.dims.z) - 1);
  offset = glm::ivec3(lo.x, 0, lo.y);
  GridFrame kept = f;
  kept.origin = f.origin + f.voxel * glm::dvec3(offset);
  kept.dims = glm::ivec3(hi.x - lo.x + 1, f.dims.y, hi.y - lo.y + 1);
  return kept;
}

}  // namespace

double decompositionBytes(double voxels, double voxel, double surfaceArea) {
  const double band = surfaceArea / (voxel * voxel) * kBandBytesPerSurfaceVoxel;
  return std::max(voxels * kDecompositionBytesPerVoxel, voxels * kVoxelizeBytesPerVoxel + band);
}

RoomExtent findRoomExtent(const Scene& scene, const RoomExtentParams& params, Context& ctx) {
  auto timer = ctx.time("voxelize.extent");
  openvdb::initialize();
  RoomExtent out;
  const Bounds b = scene.bounds();
  out.box = b;
  if (b.empty() || !(params.voxel > 0.0) || !std::isfinite(params.margin)) return out;
  const GridFrame f = frameOver(glm::dvec3(b.lo), glm::dvec3(b.hi), params.voxel, 2);
  // The coarse pass sees the whole scene; its columns are few (the voxel is the bounds' budget's).
  if (double(f.dims.x) * double(f.dims.z) > 1e8) return out;
  const ClippedTriangles all = clipToBox(scene, glm::dvec3(-INFINITY), glm::dvec3(INFINITY));
  const std::vector<Column> columns = solidColumns(solidMaskOf(all, f, nullptr), f);
  const int gap = int(std::ceil(params.coverHeight / params.voxel));
  const int reach = int(std::ceil(params.margin / params.voxel));
  const std::vector<int> part = coveredParts(columns, {f.dims.x, f.dims.z}, gap, reach, out.parts);
  if (out.parts == 0) return out;
  // Each part weighed by the triangles whose centre stands over it: a level's arena or a house holds
  // thousands, far scenery a few large ones, however much ground those cover.
  std::vector<size_t> triangles(size_t(out.parts), 0);
  for (const Triangle& t : scene.triangles) {
    const glm::ivec3 v = f.voxelOf(t.centroid());
    if (v.x < 0 || v.z < 0 || v.x >= f.dims.x || v.z >= f.dims.z) continue;
    const int p = part[size_t(v.z) * size_t(f.dims.x) + size_t(v.x)];
    if (p >= 0) ++triangles[size_t(p)];
  }
  const size_t most = *std::max_element(triangles.begin(), triangles.end());
  auto keep = [&](int p) {
    return p >= 0 && double(triangles[size_t(p)]) >= params.minPartShare * double(most);
  };
  ColumnRange kept;
  for (size_t i = 0; i < part.size(); ++i)
    if (keep(part[i]) && columns[i].covered(gap))
      kept.extend({int(i % size_t(f.dims.x)), int(i / size_t(f.dims.x))});
  for (int p = 0; p < out.parts; ++p) out.keptParts += keep(p);
  // Across: the kept parts' columns and the margin round them; up: the triangles whose centre stands over
  // them (not every solid voxel over them: a far sky's giant faces pass over a level's columns too).
  const glm::ivec2 lo = glm::max(kept.lo - reach, glm::ivec2(0));
  const glm::ivec2 hi = glm::min(kept.hi + reach, glm::ivec2(f.dims.x, f.dims.z) - 1);
  double bottom = std::numeric_limits<double>::max(), top = -std::numeric_limits<double>::max();
  for (const Triangle& t : scene.triangles) {
    const glm::ivec3 v = f.voxelOf(t.centroid());
    if (v.x < lo.x || v.z < lo.y || v.x > hi.x || v.z > hi.y) continue;
    for (const glm::vec3& q : t.p) bottom = std::min(bottom, double(q.y)), top = std::max(top, double(q.y));
  }
  if (bottom > top) return out;
  glm::dvec3 boxLo = f.origin + params.voxel * (glm::dvec3(lo.x, 0, lo.y) - 0.5);
  glm::dvec3 boxHi = f.origin + params.voxel * (glm::dvec3(hi.x, 0, hi.y) + 0.5);
  boxLo.y = bottom, boxHi.y = top;
  Bounds box;
  box.lo = glm::max(b.lo, glm::vec3(boxLo));
  box.hi = glm::min(b.hi, glm::vec3(boxHi));
  // Within a coarse voxel of the bounds on every side: the bounds themselves, so a compact building's grid
  // is exactly what it was.
  const glm::vec3 slack(float(params.voxel));
  if (glm::all(glm::lessThanEqual(box.lo, b.lo + slack)) &&
      glm::all(glm::greaterThanEqual(box.hi, b.hi - slack)))
    return out;
  out.box = box;
  out.trimmed = true;
  for (const Triangle& t : scene.triangles) {
    Bounds tb;
    for (const glm::vec3& q : t.p) tb.extend(q);
    out.farTriangles += glm::any(glm::lessThan(tb.hi, box.lo)) || glm::any(glm::greaterThan(tb.lo, box.hi));
  }
  return out;
}

SolidGrid voxelize(const Scene& scene, const VoxelizeParams& params, Context& ctx) {
  auto timer = ctx.time("voxelize");
  openvdb::initialize();
  SolidGrid out;
  const Bounds bounds = scene.bounds();
  const Bounds b = params.extent.empty() ? bounds : params.extent;
  const double h = params.voxelSize;
  // A part of the scene starts on the whole scene's lattice: its voxels are those the whole grid has.
  const glm::dvec3 lo =
      glm::dvec3(bounds.lo) + h * glm::floor((glm::dvec3(b.lo) - glm::dvec3(bounds.lo)) / h);
  // In doubles until checked: a tiny voxel makes every count here overflow an int (1e-6 m said "0 voxels").
  const double seal = params.sealRadius > 0.0 ? std::max(1.0, std::round(params.sealRadius / h)) : 0.0;
  const double padding = 2.0 + seal;
  const glm::dvec3 span = (glm::dvec3(b.hi) - lo) / h;
  const double total = (std::ceil(span.x) + 2 * padding + 1) * (std::ceil(span.y) + 2 * padding + 1) *
                       (std::ceil(span.z) + 2 * padding + 1);
  if (!(total <= double(params.maxVoxels))) {
    // The smallest voxel whose grid fits, for the bounds alone (the padding adds a little).
    const glm::dvec3 size = glm::dvec3(b.hi - b.lo);
    const double fits = std::cbrt(std::max(size.x, 1e-3) * std::max(size.y, 1e-3) * std::max(size.z, 1e-3) /
                                  double(params.maxVoxels));
    std::ostringstream s;
    s << h << " m gives " << total << " voxels, more than the limit of " << params.maxVoxels
      << "; the scene's bounds need a voxel of at least about " << std::setprecision(2) << fits << " m";
    throw InputError("voxel size", s.str());
  }
  out.sealVoxels = int(seal);
  const int pad = 2 + out.sealVoxels;
  GridFrame& f = out.frame;
  f = frameOver(lo, glm::dvec3(b.hi), h, pad);
  // What lies past the grid (and the band's two voxels round it) is left out before OpenVDB sees it.
  const ClippedTriangles tris =
      clipToBox(scene, f.origin - 3.0 * h, f.origin + h * (glm::dvec3(f.dims) + 2.0));
  // Before OpenVDB's band and the dense grids: a grid the machine cannot hold is one line now, not
  // std::bad_alloc or the OOM killer minutes into the watershed.
  std::ostringstream grid;
  grid << "the decomposition's grid of " << f.dims.x << "x" << f.dims.y << "x" << f.dims.z << " voxels of "
       << h << " m";
  requireMemory(decompositionBytes(total, h, tris.area), params.memoryLimit, "voxel size", grid.str(),
                "give a larger `voxel size` or raise `maximum memory`");

  openvdb::Int32Grid indexGrid(-1);
  openvdb::MaskGrid solidMask = solidMaskOf(tris, f, &indexGrid);
  const double udfSeconds = timer.elapsed();
  ctx.addTiming("voxelize.udf", udfSeconds);

  if (out.sealVoxels > 0) {
    const openvdb::Index64 before = solidMask.activeVoxelCount();
    // Closing = dilation then erosion; face neighbours because OpenVDB erodes only by those.
    openvdb::tools::dilateActiveValues(solidMask.tree(), out.sealVoxels, openvdb::tools::NN_FACE,
                                       openvdb::tools::IGNORE_TILES);
    openvdb::tools::erodeActiveValues(solidMask.tree(), out.sealVoxels, openvdb::tools::NN_FACE,
                                      openvdb::tools::IGNORE_TILES);
    out.sealedVoxels = size_t(solidMask.activeVoxelCount() - std::min(before, solidMask.activeVoxelCount()));
  }

  // Open ground far from the building: cut off before any dense grid is made.
  glm::ivec3 offset;
  f = cropToCovered(f, coveredColumns(solidMask, f, int(std::ceil(params.coverHeight / h))),
                    params.outsideMargin / h, offset);
  ctx.addTiming("voxelize.mask_seal", timer.elapsed() - udfSeconds);
  out.solid.assign(f.count(), 0);
  out.nearestTriangle.assign(f.count(), -1);
  for (auto it = solidMask.cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const glm::ivec3 v = glm::ivec3(c.x(), c.y(), c.z()) - offset;
    if (f.contains(v)) out.solid[f.index(v)] = 1;
  }
  for (auto it = indexGrid.cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const glm::ivec3 v = glm::ivec3(c.x(), c.y(), c.z()) - offset;
    if (f.contains(v)) out.nearestTriangle[f.index(v)] = tris.source[size_t(*it)];
  }
  ctx.progress("voxelize", 1.0);
  return out;
}

}  // namespace cpgi::decomp
