#include "decomposition/thin_wall_portals.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace cpgi::decomp {
namespace {

// Faces facing both ways in one plane are one zero-thickness wall; planes within this of each other
// are one (a plan's coordinates written as floats and read back).
constexpr double kPlaneTolerance = 5e-4;  // metres

// The plane (its coordinate along `axis`) of the zero-thickness wall around the portal nearest its middle,
// if any.
std::optional<double> thinWallPlane(const Scene& scene, const PortalQuad& q, int axis, double reach,
                                    double grow) {
  glm::dvec3 lo(q.corners[0]), hi(q.corners[0]);
  for (const glm::vec3& c : q.corners) lo = glm::min(lo, glm::dvec3(c)), hi = glm::max(hi, glm::dvec3(c));
  const double plane = 0.5 * (lo[axis] + hi[axis]);
  if (hi[axis] - lo[axis] > reach) return std::nullopt;  // tilted further than any wall could say
  // Per plane (in steps of the tolerance): which ways its faces look, bit 0 +axis, bit 1 -axis.
  std::map<long long, int> facing;
  for (const Triangle& t : scene.triangles) {
    const glm::vec3 n = t.geometricNormal();
    if (std::abs(n[axis]) < 0.999f) continue;
    const double offset = double(t.p[0][axis]) - plane;
    if (std::abs(offset) > reach) continue;
    bool overlaps = true;
    for (int k = 0; k < 3 && overlaps; ++k) {
      if (k == axis) continue;
      const double tlo = std::min({t.p[0][k], t.p[1][k], t.p[2][k]}),
                   thi = std::max({t.p[0][k], t.p[1][k], t.p[2][k]});
      overlaps = thi >= lo[k] - grow && tlo <= hi[k] + grow;
    }
    if (overlaps) facing[std::llround(offset / kPlaneTolerance)] |= n[axis] > 0.0f ? 1 : 2;
  }
  std::optional<double> best;
  for (const auto& [step, ways] : facing) {
    // The two faces of a wall may round to neighbouring steps.
    int both = ways;
    if (const auto next = facing.find(step + 1); next != facing.end()) both |= next->second;
    if (both != 3) continue;
    const double offset = double(step) * kPlaneTolerance;
    if (!best || std::abs(offset) < std::abs(*best)) best = offset;
  }
  if (!best) return std::nullopt;
  return plane + *best;
}

}  // namespace

ThinWallSnap snapPortalsToThinWalls(const Scene& scene, const GridFrame& f, PortalSet& set, Context& ctx) {
  auto timer = ctx.time("thin_wall_portals");
  ThinWallSnap out;
  const double h = f.voxel;
  for (FittedPortal& fp : set.portals) {
    PortalQuad& q = fp.quad;
    const glm::vec3 a = glm::abs(q.normal);
    const int axis = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    if (a[axis] < 0.999f) continue;
    const std::optional<double> wall = thinWallPlane(scene, q, axis, 1.5 * h, h);
    if (!wall) continue;
    double shift = 0.0;
    for (const glm::vec3& c : q.corners) shift = std::max(shift, std::abs(double(c[axis]) - *wall));
    if (shift < 1e-5) continue;
    for (glm::vec3& c : q.corners) c[axis] = float(*wall);
    const glm::vec3 normal = q.normal;
    computePortalFrame(q);
    q.normal = glm::vec3(0.0f);
    q.normal[axis] = normal[axis] > 0.0f ? 1.0f : -1.0f;
    // The voxels between the old plane and the new, and the wall's layer, to the side they are on.
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
  ctx.progress("thin_wall_portals", 1.0);
  return out;
}

}  // namespace cpgi::decomp
