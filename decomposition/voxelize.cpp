#include "decomposition/voxelize.h"

#include <algorithm>
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

// meshToVolume's MeshDataAdapter over the scene's triangles, in the grid's index space.
class TriangleAdapter {
 public:
  TriangleAdapter(const Scene& scene, const GridFrame& frame) : scene_(scene), frame_(frame) {}
  size_t polygonCount() const { return scene_.triangles.size(); }
  size_t pointCount() const { return scene_.triangles.size() * 3; }
  size_t vertexCount(size_t) const { return 3; }
  void getIndexSpacePoint(size_t n, size_t v, openvdb::Vec3d& pos) const {
    const glm::dvec3 q = (glm::dvec3(scene_.triangles[n].p[v]) - frame_.origin) / frame_.voxel;
    pos = openvdb::Vec3d(q.x, q.y, q.z);
  }

 private:
  const Scene& scene_;
  const GridFrame& frame_;
};

// The index range [lo, hi] of the grid's columns (x, z) that are covered: at least `gapVoxels` empty
// voxels between the lowest and the highest solid voxel of the column. Empty (lo > hi) when none is.
struct ColumnRange {
  glm::ivec2 lo{std::numeric_limits<int>::max()}, hi{std::numeric_limits<int>::min()};
  bool empty() const { return lo.x > hi.x; }
};

ColumnRange coveredColumns(const openvdb::MaskGrid& solid, const GridFrame& f, int gapVoxels) {
  struct Column {
    int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min(), solid = 0;
  };
  std::vector<Column> columns(size_t(f.dims.x) * size_t(f.dims.z));
  for (auto it = solid.cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    if (!f.contains({c.x(), c.y(), c.z()})) continue;
    Column& col = columns[size_t(c.z()) * size_t(f.dims.x) + size_t(c.x())];
    col.lowest = std::min(col.lowest, c.y()), col.highest = std::max(col.highest, c.y());
    ++col.solid;
  }
  ColumnRange out;
  for (int z = 0; z < f.dims.z; ++z)
    for (int x = 0; x < f.dims.x; ++x) {
      const Column& col = columns[size_t(z) * size_t(f.dims.x) + size_t(x)];
      if (col.solid == 0 || col.highest - col.lowest + 1 - col.solid < gapVoxels) continue;
      out.lo = glm::min(out.lo, glm::ivec2(x, z)), out.hi = glm::max(out.hi, glm::ivec2(x, z));
    }
  return out;
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

SolidGrid voxelize(const Scene& scene, const VoxelizeParams& params, Context& ctx) {
  auto timer = ctx.time("voxelize");
  openvdb::initialize();
  SolidGrid out;
  const Bounds b = scene.bounds();
  const double h = params.voxelSize;
  // In doubles until checked: a tiny voxel makes every count here overflow an int (1e-6 m said "0 voxels").
  const double seal = params.sealRadius > 0.0 ? std::max(1.0, std::round(params.sealRadius / h)) : 0.0;
  const double padding = 2.0 + seal;
  const glm::dvec3 span = glm::dvec3(b.hi - b.lo) / h;
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
  // Before OpenVDB's band and the dense grids: a grid the machine cannot hold is one line now, not
  // std::bad_alloc or the OOM killer minutes into the watershed.
  double area = 0.0;
  for (const Triangle& t : scene.triangles) area += double(t.area());
  std::ostringstream grid;
  grid << "the decomposition's grid of " << std::ceil(span.x) + 2 * padding + 1 << "x"
       << std::ceil(span.y) + 2 * padding + 1 << "x" << std::ceil(span.z) + 2 * padding + 1 << " voxels of "
       << h << " m";
  requireMemory(decompositionBytes(total, h, area), params.memoryLimit, "voxel size", grid.str(),
                "give a larger `voxel size` or raise `maximum memory`");
  out.sealVoxels = int(seal);
  const int pad = 2 + out.sealVoxels;
  GridFrame& f = out.frame;
  f.voxel = h;
  f.origin = glm::dvec3(b.lo) - pad * h;
  f.dims = glm::ivec3(int(std::ceil(span.x)) + 2 * pad + 1, int(std::ceil(span.y)) + 2 * pad + 1,
                      int(std::ceil(span.z)) + 2 * pad + 1);

  // Index space is our own (see TriangleAdapter); the transform only carries the voxel size, which
  // meshToVolume uses to report distances in metres.
  const auto xform = openvdb::math::Transform::createLinearTransform(h);
  openvdb::Int32Grid indexGrid(-1);
  openvdb::FloatGrid::Ptr udf = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      TriangleAdapter(scene, f), *xform, 1.0f, 1.0f, openvdb::tools::UNSIGNED_DISTANCE_FIELD | openvdb::tools::DISABLE_RENORMALIZATION, &indexGrid);

  // Solid where the centre is within half a voxel: then two face neighbours on opposite sides of any
  // plane differ by at most one voxel in distance and cannot both be outside the band.
  const double udfSeconds = timer.elapsed();
  ctx.addTiming("voxelize.udf", udfSeconds);
  const float halfVoxel = float(0.5 * h) * (1.0f + 1e-4f);
  openvdb::MaskGrid solidMask;
  auto maskAcc = solidMask.getAccessor();
  for (auto it = udf->cbeginValueOn(); it; ++it)
    if (*it <= halfVoxel) maskAcc.setValueOn(it.getCoord());

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
    if (f.contains(v)) out.nearestTriangle[f.index(v)] = *it;
  }
  ctx.progress("voxelize", 1.0);
  return out;
}

}  // namespace cpgi::decomp
