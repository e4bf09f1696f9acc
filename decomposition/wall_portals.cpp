#include "decomposition/wall_portals.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <vector>

namespace cpgi::decomp {
namespace {

// Faces within this of each other along the axis are in one plane (a plan's coordinates written as
// floats and read back).
constexpr double kPlaneTolerance = 5e-4;  // metres

struct WallPlane {
  double at = 0.0;             ///< the mid-plane's coordinate along the axis
  bool zeroThickness = false;  ///< the wall's two faces lie in it
};

// The mid-plane of the wall around portal q, if the scene's faces show one.
std::optional<WallPlane> wallMidPlane(const Scene& scene, const PortalQuad& q, int axis, double maxThickness,
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
  std::optional<WallPlane> best;
  for (double b : back) {
    const auto f = front.lower_bound(b - kPlaneTolerance);
    if (f == front.end() || *f - b > maxThickness || b > tilt + slack || *f < -tilt - slack) continue;
    const double mid = 0.5 * (b + *f);
    if (!best || std::abs(mid) < std::abs(best->at - plane))
      best = WallPlane{plane + mid, *f - b < 2.0 * kPlaneTolerance};
  }
  return best;
}

// Shrinks a portal lying in a zero-thickness wall's plane off the wall's faces: the quad's margin (and a
// quad fitted to voxels that leaked along the wall, plan 9's R5:R4 over 9.2 m² of wall round a 3.5 m² door)
// would otherwise lie on the wall's faces, and light would pass through the wall there. The edges move
// in, 2 cm at a time, while most of the row of points along one of them lies on the wall's faces.
void clipToOpening(const Scene& scene, int axis, double wall, PortalQuad& q) {
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  std::vector<const Triangle*> faces;
  for (const Triangle& t : scene.triangles)
    if (std::abs(t.geometricNormal()[axis]) > 0.999f &&
        std::abs(double(t.p[0][axis]) - wall) < kPlaneTolerance)
      faces.push_back(&t);
  auto onWall = [&](const glm::vec3& p) {
    for (const Triangle* t : faces) {
      const glm::vec2 a(t->p[0][a1], t->p[0][a2]), b(t->p[1][a1], t->p[1][a2]), c(t->p[2][a1], t->p[2][a2]);
      const glm::vec2 x(p[a1], p[a2]);
      const auto side = [](glm::vec2 o, glm::vec2 d, glm::vec2 y) {
        return (d.x - o.x) * (y.y - o.y) - (d.y - o.y) * (y.x - o.x);
      };
      const float s1 = side(a, b, x), s2 = side(b, c, x), s3 = side(c, a, x);
      if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) return true;
    }
    return false;
  };
  const glm::vec3 o = q.corners[0], eu = q.corners[1] - o, ev = q.corners[3] - o;
  const int nu = std::max(2, int(std::ceil(glm::length(eu) / 0.02f))),
            nv = std::max(2, int(std::ceil(glm::length(ev) / 0.02f)));
  std::vector<char> wallAt(size_t(nu) * size_t(nv));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      wallAt[size_t(j) * size_t(nu) + size_t(i)] =
          onWall(o + (float(i) + 0.5f) / float(nu) * eu + (float(j) + 0.5f) / float(nv) * ev);
  int i0 = 0, i1 = nu, j0 = 0, j1 = nv;  // the kept points: [i0, i1) × [j0, j1)
  auto wallShare = [&](int fi, int li, int fj, int lj) {
    int wallCount = 0, all = 0;
    for (int j = fj; j < lj; ++j)
      for (int i = fi; i < li; ++i) wallCount += wallAt[size_t(j) * size_t(nu) + size_t(i)], ++all;
    return all > 0 ? double(wallCount) / double(all) : 0.0;
  };
  // The edge whose row is most on the wall first: a quad over a wall beside a door is most of it wall,
  // every row across the wall too, and only its far edge is all wall.
  while (i0 < i1 && j0 < j1) {
    const double share[4] = {wallShare(i0, i0 + 1, j0, j1), wallShare(i1 - 1, i1, j0, j1),
                             wallShare(i0, i1, j0, j0 + 1), wallShare(i0, i1, j1 - 1, j1)};
    const int edge = int(std::max_element(share, share + 4) - share);
    if (share[edge] <= 0.5) break;
    if (edge == 0) ++i0;
    if (edge == 1) --i1;
    if (edge == 2) ++j0;
    if (edge == 3) --j1;
  }
  if (i0 >= i1 || j0 >= j1) return;  // all wall: leave the quad as fitted
  const glm::vec3 normal = q.normal;
  const glm::vec3 c0 = o + float(i0) / float(nu) * eu + float(j0) / float(nv) * ev;
  const glm::vec3 du = float(i1 - i0) / float(nu) * eu, dv = float(j1 - j0) / float(nv) * ev;
  q.corners = {c0, c0 + du, c0 + du + dv, c0 + dv};
  computePortalFrame(q);
  q.normal = normal;
}

// A quad fitted askew and pressed onto its wall's plane is no longer a rectangle (plan 20's R1:R4, fitted
// 2.3° off its wall: corners 0.1° off square once flat), and a cell's atlas charts a quad that is not a
// rectangle as two loose triangles. The rectangle in the plane round it instead: along its first edge as
// pressed, across that in the plane, spanning every corner; the corners keep their winding.
void squareInPlane(PortalQuad& q, int axis) {
  glm::dvec3 u = glm::dvec3(q.corners[1]) - glm::dvec3(q.corners[0]),
             v = glm::dvec3(q.corners[3]) - glm::dvec3(q.corners[0]);
  u[axis] = 0.0, v[axis] = 0.0;
  if (!(glm::length(u) > 0.0 && glm::length(v) > 0.0)) return;
  u = glm::normalize(u);
  if (std::abs(glm::dot(u, glm::normalize(v))) < 1e-6) return;  // square already
  glm::dvec3 n(0.0);
  n[axis] = 1.0;
  const glm::dvec3 across = glm::cross(n, u);
  v = glm::dot(across, v) > 0.0 ? across : -across;
  glm::dvec3 centre(0.0);
  for (const glm::vec3& c : q.corners) centre += 0.25 * glm::dvec3(c);
  double hu = 0.0, hv = 0.0;
  for (const glm::vec3& c : q.corners) {
    hu = std::max(hu, std::abs(glm::dot(glm::dvec3(c) - centre, u)));
    hv = std::max(hv, std::abs(glm::dot(glm::dvec3(c) - centre, v)));
  }
  const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  for (int k = 0; k < 4; ++k) {
    q.corners[size_t(k)] = glm::vec3(centre + su[k] * hu * u + sv[k] * hv * v);
    q.corners[size_t(k)][axis] = float(centre[axis]);
  }
}

}  // namespace

WallSnap snapPortalsToWalls(const Scene& scene, const GridFrame& f, double maxThickness, PortalSet& set,
                            Context& ctx) {
  auto timer = ctx.time("wall_portals");
  WallSnap out;
  const double h = f.voxel;
  // The moves relabel voxels by side; where a wall's faces do not close the space round a portal (a game
  // level's walls meeting at angles, OpenArena's oa_dm1), that can open voxel faces between cells that no
  // portal covers. The portals as fitted are kept then.
  const PortalSet fitted = set;
  for (FittedPortal& fp : set.portals) {
    PortalQuad& q = fp.quad;
    const glm::vec3 a = glm::abs(q.normal);
    const int axis = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    if (a[axis] < 0.99f) continue;  // an opening in a wall along the grid, fitted up to 8° off it
    const std::optional<WallPlane> wall = wallMidPlane(scene, q, axis, maxThickness, 1.5 * h, h);
    if (!wall) continue;
    double shift = 0.0;
    for (const glm::vec3& c : q.corners) shift = std::max(shift, std::abs(double(c[axis]) - wall->at));
    if (shift < 1e-5 && !wall->zeroThickness) continue;
    for (glm::vec3& c : q.corners) c[axis] = float(wall->at);
    squareInPlane(q, axis);
    const glm::vec3 normal = q.normal;
    computePortalFrame(q);
    q.normal = glm::vec3(0.0f);
    q.normal[axis] = normal[axis] > 0.0f ? 1.0f : -1.0f;
    if (wall->zeroThickness) clipToOpening(scene, axis, wall->at, q);
    // The voxels between the old plane and the new, and the layer around it, to the side they are on.
    FittedPortal slab = fp;
    slab.depth = float(shift + h);
    relabelSlab(f, slab, set.cell);
    fp.depth = std::max(fp.depth, slab.depth);
    ++out.moved;
    out.largestShift = std::max(out.largestShift, shift);
  }
  if (out.moved > 0) set.leakingFaces = countLeakingFaces(f, set.cell, quadsOf(set.portals));
  if (set.leakingFaces > fitted.leakingFaces) {
    set = fitted;
    out = WallSnap{};
  }
  ctx.progress("wall_portals", 1.0);
  return out;
}

}  // namespace cpgi::decomp
