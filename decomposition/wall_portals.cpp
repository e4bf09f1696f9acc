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

// Within this of each other, two coordinates are one (a rectangle's corners, a triangle edge along an axis).
constexpr double kSameCoordinate = 1e-4;  // metres

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

// Where the opening's side beyond one edge of the portal lies: the edge at coordinate `at` along in-plane
// axis `across`, `low` when the opening lies above it (the sill, the left jamb).
struct EdgeSide {
  int across = 0;
  bool low = true;
};

// The face of a thick wall's opening that bounds that edge: a reveal (a sill facing up, a jamb facing the
// opening, a lintel facing down) through the wall's mid-plane, along the edge for at least half its length.
std::optional<double> revealAt(const Triangle& t, int axis, double wall, EdgeSide side, double alongLo,
                               double alongHi, int along) {
  const glm::vec3 n = t.geometricNormal();
  if (std::abs(n[side.across]) < 0.999f || (n[side.across] > 0.0f) != side.low) return std::nullopt;
  const auto extent = [&](int k) {
    return std::pair{std::min({t.p[0][k], t.p[1][k], t.p[2][k]}),
                     std::max({t.p[0][k], t.p[1][k], t.p[2][k]})};
  };
  const auto [axisLo, axisHi] = extent(axis);
  if (axisLo > wall + kSameCoordinate || axisHi < wall - kSameCoordinate) return std::nullopt;
  const auto [lo, hi] = extent(along);
  if (std::min(double(hi), alongHi) - std::max(double(lo), alongLo) < 0.5 * (alongHi - alongLo))
    return std::nullopt;
  return double(t.p[0][side.across]);
}

// The edge of a zero-thickness wall's face that bounds that edge: a side of a face in the wall's plane,
// along the portal's edge for at least half its length, with the face beyond it (below a sill).
std::optional<double> wallEdgeAt(const Triangle& t, int axis, double wall, EdgeSide side, double alongLo,
                                 double alongHi, int along) {
  if (std::abs(t.geometricNormal()[axis]) < 0.999f || std::abs(double(t.p[0][axis]) - wall) > kPlaneTolerance)
    return std::nullopt;
  std::optional<double> out;
  for (int e = 0; e < 3; ++e) {
    const glm::vec3 &p = t.p[size_t(e)], &q = t.p[size_t((e + 1) % 3)], &r = t.p[size_t((e + 2) % 3)];
    if (std::abs(double(p[side.across]) - double(q[side.across])) > kSameCoordinate) continue;
    const double at = double(p[side.across]);
    if ((double(r[side.across]) < at) != side.low) continue;  // the face on the opening's side of it
    const double lo = std::min(p[along], q[along]), hi = std::max(p[along], q[along]);
    if (std::min(hi, alongHi) - std::max(lo, alongLo) >= 0.5 * (alongHi - alongLo)) out = at;
  }
  return out;
}

// Moves each edge of a portal lying in its wall's plane as a rectangle along the wall's in-plane axes onto
// the nearest edge of the opening within `reach`: the voxels put the portal's edges on their lattice, up to
// half a voxel off the opening's. A sill 2 cm under a window's portal lets the light that a cell sends
// through the gap out of the cell, which the rooms behind (plan 22's R8, −5.6 % with the automatic cells
// against −0.9 % with the plan's own) never get; the gap between a jamb and the portal likewise. Returns
// whether an edge moved.
bool fitToOpening(const Scene& scene, int axis, const WallPlane& wall, double reach, PortalQuad& q) {
  const int inPlane[2] = {(axis + 1) % 3, (axis + 2) % 3};
  glm::dvec3 lo(q.corners[0]), hi(q.corners[0]);
  for (const glm::vec3& c : q.corners) lo = glm::min(lo, glm::dvec3(c)), hi = glm::max(hi, glm::dvec3(c));
  // A rectangle turned in the wall's plane (fitted a few degrees askew and squared there) becomes the one
  // along the axes whose four edges are all the opening's; otherwise it is left.
  bool alongAxes = true;
  for (const glm::vec3& c : q.corners)
    for (int k : inPlane)
      alongAxes =
          alongAxes && (std::abs(c[k] - lo[k]) < kSameCoordinate || std::abs(c[k] - hi[k]) < kSameCoordinate);
  double to[2][2], distance[2][2];  // [in-plane axis][low, high edge]
  for (int m = 0; m < 2; ++m) {
    to[m][0] = lo[inPlane[m]], to[m][1] = hi[inPlane[m]];
    distance[m][0] = distance[m][1] = reach;
  }
  bool found[2][2] = {{false, false}, {false, false}};
  for (const Triangle& t : scene.triangles)
    for (int m = 0; m < 2; ++m)
      for (int s = 0; s < 2; ++s) {
        const int across = inPlane[m], along = inPlane[1 - m];
        const EdgeSide side{across, s == 0};
        const std::optional<double> at = wall.zeroThickness
                                             ? wallEdgeAt(t, axis, wall.at, side, lo[along], hi[along], along)
                                             : revealAt(t, axis, wall.at, side, lo[along], hi[along], along);
        const double edge = s == 0 ? lo[across] : hi[across];
        if (at && std::abs(*at - edge) <= distance[m][s])
          distance[m][s] = std::abs(*at - edge), to[m][s] = *at, found[m][s] = true;
      }
  const bool allFound = found[0][0] && found[0][1] && found[1][0] && found[1][1];
  if (!alongAxes && !allFound) return false;
  bool moved = !alongAxes;
  for (int m = 0; m < 2; ++m) {
    if (to[m][1] - to[m][0] < reach) return false;  // the opening would close up: not this opening's edges
    moved = moved || to[m][0] != lo[inPlane[m]] || to[m][1] != hi[inPlane[m]];
  }
  if (!moved) return false;
  // The corners keep their winding: each takes the low or the high side it was nearer along each axis,
  // which for a turned rectangle is read about its centre.
  const glm::dvec3 centre = 0.5 * (lo + hi);
  for (glm::vec3& c : q.corners)
    for (int m = 0; m < 2; ++m) {
      const int k = inPlane[m];
      c[k] = float(double(c[k]) < centre[k] ? to[m][0] : to[m][1]);
    }
  const glm::vec3 normal = q.normal;
  computePortalFrame(q);
  q.normal = normal;
  return true;
}

// Fits each portal lying in its wall's plane to the opening's edges (fitToOpening), and puts back the
// portals of any pair of cells that the fit would leave a voxel face between uncovered. Returns how many
// portals kept a fitted edge.
int fitPortalsToOpenings(const Scene& scene, const GridFrame& f, double maxThickness, PortalSet& set) {
  const double h = f.voxel;
  const std::vector<PortalQuad> before = quadsOf(set.portals);
  std::vector<char> fitted(set.portals.size(), 0);
  for (size_t k = 0; k < set.portals.size(); ++k) {
    PortalQuad& q = set.portals[k].quad;
    const glm::vec3 a = glm::abs(q.normal);
    const int axis = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    if (a[axis] < 0.99999f) continue;
    const std::optional<WallPlane> wall = wallMidPlane(scene, q, axis, maxThickness, 1.5 * h, h);
    if (!wall || std::abs(double(q.corners[0][axis]) - wall->at) > kSameCoordinate) continue;
    fitted[k] = fitToOpening(scene, axis, *wall, h, q);
  }
  if (std::none_of(fitted.begin(), fitted.end(), [](char c) { return c != 0; })) return 0;
  const auto leaksBefore = leakingFacesByPair(f, set.cell, before);
  const auto leaksAfter = leakingFacesByPair(f, set.cell, quadsOf(set.portals));
  const auto count = [](const auto& byPair, std::pair<int, int> pair) {
    const auto it = byPair.find(pair);
    return it == byPair.end() ? size_t(0) : it->second;
  };
  int kept = 0;
  for (size_t k = 0; k < set.portals.size(); ++k) {
    const PortalQuad& q = set.portals[k].quad;
    const std::pair pair{std::min(q.cellA, q.cellB), std::max(q.cellA, q.cellB)};
    if (count(leaksAfter, pair) > count(leaksBefore, pair)) {
      set.portals[k].quad = before[k];
    } else {
      kept += fitted[k];
    }
  }
  set.leakingFaces = countLeakingFaces(f, set.cell, quadsOf(set.portals));
  return kept;
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
  out.fittedToOpening = fitPortalsToOpenings(scene, f, maxThickness, set);
  ctx.progress("wall_portals", 1.0);
  return out;
}

}  // namespace cpgi::decomp
