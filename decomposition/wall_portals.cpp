#include "decomposition/wall_portals.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

namespace cpgi::decomp {
namespace {

// Faces within this of each other along the axis are in one plane (a plan's coordinates written as
// floats and read back).
constexpr double kPlaneTolerance = 5e-4;  // metres

// The mid-plane (its coordinate along `axis`) of the wall around portal q, if the scene's faces show one.
std::optional<double> wallMidPlane(const Scene& scene, const PortalQuad& q, int axis, double maxThickness,
                                   double slack, double grow) {
  glm::dvec3 lo(q.corners[0]), hi(q.corners[0]);
  for (const glm::vec3& c : q.corners) lo = glm::min(lo, glm::dvec3(c)), hi = glm::max(hi, glm::dvec3(c));
  const double plane = 0.5 * (lo[axis] + hi[axis]), tilt = 0.5 * (hi[axis] - lo[axis]);
  // The offsets from the portal's plane of the parallel faces around it, by the way they look along axis.
  std::set<double> back, front;
  for (const Triangle& t : scene.triangles) {
    const glm::vec3 n = t.geometricNormal();
    if (std::abs(n[axis]) < 0.999f) continue;
    const double offset = double(t.p[0][axis]) - plane;
    if (std::abs(offset) > maxThickness + tilt + slack) continue;
    bool overlaps = true;
    for (int k = 0; k < 3 && overlaps; ++k) {
      if (k == axis) continue;
      const double tlo = std::min({t.p[0][k], t.p[1][k], t.p[2][k]}),
                   thi = std::max({t.p[0][k], t.p[1][k], t.p[2][k]});
      overlaps = thi >= lo[k] - grow && tlo <= hi[k] + grow;
    }
    if (overlaps) (n[axis] > 0.0f ? front : back).insert(offset);
  }
  // Each back face with the nearest front face at or beyond it: a wall, when thin enough and around the
  // portal; the one whose middle is nearest the portal.
  std::optional<double> best;
  for (double b : back) {
    const auto f = front.lower_bound(b - kPlaneTolerance);
    if (f == front.end() || *f - b > maxThickness || b > tilt + slack || *f < -tilt - slack) continue;
    const double mid = 0.5 * (b + *f);
    if (!best || std::abs(mid) < std::abs(*best)) best = mid;
  }
  if (!best) return std::nullopt;
  return plane + *best;
}

}  // namespace

WallSnap snapPortalsToWalls(const Scene& scene, const GridFrame& f, double maxThickness, PortalSet& set,
                            Context& ctx) {
  auto timer = ctx.time("wall_portals");
  WallSnap out;
  const double h = f.voxel;
  for (FittedPortal& fp : set.portals) {
    PortalQuad& q = fp.quad;
    const glm::vec3 a = glm::abs(q.normal);
    const int axis = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    if (a[axis] < 0.99f) continue;  // an opening in a wall along the grid, fitted up to 8° off it
    const std::optional<double> wall = wallMidPlane(scene, q, axis, maxThickness, 1.5 * h, h);
    if (!wall) continue;
    double shift = 0.0;
    for (const glm::vec3& c : q.corners) shift = std::max(shift, std::abs(double(c[axis]) - *wall));
    if (shift < 1e-5) continue;
    for (glm::vec3& c : q.corners) c[axis] = float(*wall);
    const glm::vec3 normal = q.normal;
    computePortalFrame(q);
    q.normal = glm::vec3(0.0f);
    q.normal[axis] = normal[axis] > 0.0f ? 1.0f : -1.0f;
    // The voxels between the old plane and the new, and the layer around it, to the side they are on.
    FittedPortal slab = fp;
    slab.depth = float(shift + h);
    relabelSlab(f, slab, set.cell);
    fp.depth = std::max(fp.depth, slab.depth);
    ++out.moved;
    out.largestShift = std::max(out.largestShift, shift);
  }
  if (out.moved > 0) {
    std::vector<PortalQuad> quads;
    for (const FittedPortal& fp : set.portals) quads.push_back(fp.quad);
    set.leakingFaces = countLeakingFaces(f, set.cell, quads);
  }
  ctx.progress("wall_portals", 1.0);
  return out;
}

}  // namespace cpgi::decomp
