#include "decomposition/portals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/linear_least_squares_fitting_3.h>
#include <CGAL/min_quadrilateral_2.h>

#include "decomposition/sections.h"

namespace cpgi::decomp {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// A voxel face between cells a < b: the face between voxel `lower` and its +axis neighbour.
struct Face {
  int a, b;
  size_t lower;
  int axis;
  int sign;      // +1 when the +axis side is cell b
  float saddle;  // min of the two voxels' distances, metres
};

uint64_t halfKey(const glm::ivec3& h) {
  return (uint64_t(uint32_t(h.x)) << 42) | (uint64_t(uint32_t(h.y)) << 21) | uint64_t(uint32_t(h.z));
}

int findRoot(std::vector<int>& parent, int x) {
  while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
  return x;
}

// The direction from cell a into cell b across an opening: its faces' mean direction, or where they cancel
// (an interface wrapped round a column of one cell, faces looking both ways in equal numbers), the axis
// most of its faces lie across, signed by the first of those. Normalising the zero mean gave NaN, which
// CGAL's exact rectangle fit turned into a crash (SIGFPE in GMP) on OpenArena's aggressor.
glm::vec3 openingDirection(const std::vector<const Face*>& faces, const glm::vec3& meanDir) {
  if (glm::length(meanDir) > 0.5f) return glm::normalize(meanDir);
  int count[3] = {0, 0, 0};
  for (const Face* face : faces) ++count[face->axis];
  const int axis = count[0] >= count[1] ? (count[0] >= count[2] ? 0 : 2) : (count[1] >= count[2] ? 1 : 2);
  glm::vec3 n(0.0f);
  for (const Face* face : faces)
    if (face->axis == axis) {
      n[axis] = float(face->sign);
      break;
    }
  return n;
}

// Fits one quad to the faces of one opening.
FittedPortal fitOpening(const GridFrame& f, const std::vector<const Face*>& faces, double margin) {
  const float h = float(f.voxel);
  std::vector<Kernel::Point_3> mids;
  std::vector<glm::vec3> corners;
  glm::vec3 meanDir(0.0f);
  FittedPortal out;
  for (const Face* face : faces) {
    glm::vec3 axis(0.0f);
    axis[face->axis] = 1.0f;
    const glm::vec3 m = f.centre(face->lower) + 0.5f * h * axis;
    mids.emplace_back(m.x, m.y, m.z);
    meanDir += float(face->sign) * axis;
    glm::vec3 e1(0.0f), e2(0.0f);
    e1[(face->axis + 1) % 3] = 0.5f * h;
    e2[(face->axis + 2) % 3] = 0.5f * h;
    for (float s1 : {-1.0f, 1.0f})
      for (float s2 : {-1.0f, 1.0f}) corners.push_back(m + s1 * e1 + s2 * e2);
    out.halfWidth = std::max(out.halfWidth, face->saddle);
  }
  out.faces = uint32_t(faces.size());

  Kernel::Plane_3 plane;
  Kernel::Point_3 centroid;
  glm::vec3 n = openingDirection(faces, meanDir);
  if (mids.size() >= 3) {
    CGAL::linear_least_squares_fitting_3(mids.begin(), mids.end(), plane, centroid, CGAL::Dimension_tag<0>());
    const auto pn = plane.orthogonal_vector();
    glm::vec3 fitted(float(pn.x()), float(pn.y()), float(pn.z()));
    fitted = glm::normalize(fitted);
    if (glm::dot(fitted, n) < 0.0f) fitted = -fitted;
    // A fit that disagrees with the faces' own orientation means the faces are (nearly) collinear — a
    // one-voxel crack — and the plane is not determined by them; the faces' mean direction is.
    if (glm::dot(fitted, n) > 0.5f) n = fitted;
  } else {
    glm::vec3 c(0.0f);
    for (const auto& p : mids) c += glm::vec3(float(p.x()), float(p.y()), float(p.z()));
    c /= float(mids.size());
    centroid = Kernel::Point_3(c.x, c.y, c.z);
  }
  const glm::vec3 c(float(centroid.x()), float(centroid.y()), float(centroid.z()));
  // In-plane basis (u, v, n) right-handed, u from the world axis least aligned with n.
  glm::vec3 ref(0.0f);
  ref[std::abs(n.x) < std::abs(n.y) ? (std::abs(n.x) < std::abs(n.z) ? 0 : 2)
                                    : (std::abs(n.y) < std::abs(n.z) ? 1 : 2)] = 1.0f;
  const glm::vec3 u = glm::normalize(glm::cross(ref, n));
  const glm::vec3 v = glm::cross(n, u);

  std::vector<Kernel::Point_2> projected, hull, rect;
  projected.reserve(corners.size());
  for (const glm::vec3& p : corners) {
    const glm::vec2 q(glm::dot(p - c, u), glm::dot(p - c, v));
    // GMP, under CGAL's exact predicates, raises SIGFPE on a NaN: say which step went wrong instead.
    if (!std::isfinite(q.x) || !std::isfinite(q.y))
      throw std::logic_error("fitOpening: a non-finite opening point");
    projected.emplace_back(q.x, q.y);
  }
  CGAL::convex_hull_2(projected.begin(), projected.end(), std::back_inserter(hull));
  CGAL::min_rectangle_2(hull.begin(), hull.end(), std::back_inserter(rect));

  // Rectangle centre and half-axes in the plane, then grown by the margin.
  glm::vec2 r[4];
  for (int i = 0; i < 4; ++i) r[i] = glm::vec2(float(rect[size_t(i)].x()), float(rect[size_t(i)].y()));
  const glm::vec2 rc = 0.25f * (r[0] + r[1] + r[2] + r[3]);
  glm::vec2 a1 = r[1] - r[0], a2 = r[3] - r[0];
  const float l1 = glm::length(a1), l2 = glm::length(a2);
  a1 = l1 > 0.0f ? a1 / l1 : glm::vec2(1, 0);
  a2 = l2 > 0.0f ? a2 / l2 : glm::vec2(-a1.y, a1.x);
  const float grow = float(margin) * h;
  const float half1 = 0.5f * l1 + grow, half2 = 0.5f * l2 + grow;
  const glm::vec3 centre = c + rc.x * u + rc.y * v;
  const glm::vec3 w1 = a1.x * u + a1.y * v, w2 = a2.x * u + a2.y * v;
  const glm::vec3 e1 = half1 * w1;
  glm::vec3 e2 = half2 * w2;
  if (glm::dot(glm::cross(e1, e2), n) < 0.0f) e2 = -e2;  // corners counter-clockwise about n
  out.quad.corners = {centre - e1 - e2, centre + e1 - e2, centre + e1 + e2, centre - e1 + e2};
  computePortalFrame(out.quad);
  out.quad.normal = n;  // the fitted plane's normal (computePortalFrame's agrees up to rounding)
  out.quad.cellA = faces.front()->a;
  out.quad.cellB = faces.front()->b;
  float depth = 0.0f;
  for (const auto& p : mids)
    depth =
        std::max(depth, std::abs(glm::dot(glm::vec3(float(p.x()), float(p.y()), float(p.z())) - centre, n)));
  out.depth = depth + h;
  return out;
}

// Moves the portal along its normal to the middle of the narrowest stretch of the opening. The watershed
// interface lies anywhere along a door's depth (its width is the same all through the wall); the cross-
// section of empty voxels within the quad's footprint, slice by slice along the normal, is smallest
// across the whole depth of the wall, and the middle of that run is the wall's mid-plane.
void centreInConstriction(FittedPortal& fp, const GridFrame& f, const std::vector<int32_t>& cell,
                          float searchRange) {
  PortalQuad& q = fp.quad;
  const float h = float(f.voxel);
  const glm::vec3 c = q.centre();
  const glm::vec3 eu = q.corners[1] - q.corners[0], ev = q.corners[3] - q.corners[0];
  const float hu = 0.5f * glm::length(eu), hv = 0.5f * glm::length(ev);
  if (hu <= 0.0f || hv <= 0.0f) return;
  const glm::vec3 du = eu / (2.0f * hu), dv = ev / (2.0f * hv);
  const int bins = 2 * int(std::ceil(searchRange / h)) + 1, mid = bins / 2;
  // Slices measured from the voxel centre nearest the quad's centre, so that for axis-aligned portals
  // every voxel layer falls in the middle of one slice.
  const glm::vec3 ref = f.centre(f.voxelOf(c));
  std::vector<size_t> count(size_t(bins), 0);
  Bounds box;
  for (const glm::vec3& k : q.corners)
    box.extend(k - searchRange * q.normal), box.extend(k + searchRange * q.normal);
  const glm::ivec3 lo = glm::max(f.voxelOf(box.lo), glm::ivec3(0)),
                   hi = glm::min(f.voxelOf(box.hi), f.dims - 1);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const size_t i = f.index(x, y, z);
        if (cell[i] != q.cellA && cell[i] != q.cellB) continue;
        const glm::vec3 p = f.centre(i) - c;
        if (std::abs(glm::dot(p, du)) > hu || std::abs(glm::dot(p, dv)) > hv) continue;
        const int b = mid + int(std::floor(glm::dot(f.centre(i) - ref, q.normal) / h + 0.5f));
        if (b >= 0 && b < bins) ++count[size_t(b)];
      }
  // The run of near-minimal slices nearest the fitted plane.
  const size_t least = *std::min_element(count.begin(), count.end());
  const size_t limit = least + std::max<size_t>(1, least / 50);
  int best = -1;
  for (int b = 0; b < bins; ++b)
    if (count[size_t(b)] <= limit && (best < 0 || std::abs(b - mid) < std::abs(best - mid))) best = b;
  if (best < 0) return;
  int first = best, last = best;
  while (first > 0 && count[size_t(first - 1)] <= limit) --first;
  while (last + 1 < bins && count[size_t(last + 1)] <= limit) ++last;
  // A run reaching the end of the search is not a constriction we can centre on.
  if (first == 0 || last == bins - 1) return;
  const float shift = glm::dot(ref - c, q.normal) + 0.5f * float(first + last - 2 * mid) * h;
  for (glm::vec3& k : q.corners) k += shift * q.normal;
  fp.depth += std::abs(shift);
}

}  // namespace

void relabelSlab(const GridFrame& f, const FittedPortal& fp, std::vector<int32_t>& cell) {
  const PortalQuad& q = fp.quad;
  Bounds box;
  for (const glm::vec3& c : q.corners)
    box.extend(c - fp.depth * q.normal), box.extend(c + fp.depth * q.normal);
  const glm::ivec3 lo = glm::max(f.voxelOf(box.lo), glm::ivec3(0));
  const glm::ivec3 hi = glm::min(f.voxelOf(box.hi), f.dims - 1);
  const glm::vec3 c = q.centre();
  const glm::vec3 eu = q.corners[1] - q.corners[0], ev = q.corners[3] - q.corners[0];
  const float hu = 0.5f * glm::length(eu), hv = 0.5f * glm::length(ev);
  if (hu <= 0.0f || hv <= 0.0f) return;
  const glm::vec3 du = eu / (2.0f * hu), dv = ev / (2.0f * hv);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const size_t i = f.index(x, y, z);
        const int l = cell[i];
        if (l != q.cellA && l != q.cellB) continue;
        const glm::vec3 p = f.centre(i) - c;
        const float s = glm::dot(p, q.normal);
        if (std::abs(s) > fp.depth || std::abs(glm::dot(p, du)) > hu || std::abs(glm::dot(p, dv)) > hv)
          continue;
        cell[i] = s < 0.0f ? q.cellA : q.cellB;
      }
}

bool segmentCrossesPortal(const PortalQuad& portal, const glm::vec3& a, const glm::vec3& b, float tolerance) {
  const glm::vec3 c = portal.centre();
  const float sa = glm::dot(a - c, portal.normal), sb = glm::dot(b - c, portal.normal);
  if ((sa > 0.0f && sb > 0.0f) || (sa < 0.0f && sb < 0.0f) || sa == sb) return false;
  const glm::vec3 x = a + (sa / (sa - sb)) * (b - a);
  const glm::vec3 o = portal.corners[0];
  const glm::vec3 eu = portal.corners[1] - o, ev = portal.corners[3] - o;
  const float lu = glm::length(eu), lv = glm::length(ev);
  if (lu <= 0.0f || lv <= 0.0f) return false;
  const float pu = glm::dot(x - o, eu / lu), pv = glm::dot(x - o, ev / lv);
  return pu >= -tolerance && pu <= lu + tolerance && pv >= -tolerance && pv <= lv + tolerance;
}

namespace {

using PortalsByPair = std::map<std::pair<int, int>, std::vector<const PortalQuad*>>;

void addPortal(PortalsByPair& byPair, const PortalQuad& p) {
  byPair[{std::min(p.cellA, p.cellB), std::max(p.cellA, p.cellB)}].push_back(&p);
}

// Calls visit(i, j, a, b, axis) for every face between voxel i (cell a) and its +axis neighbour j (cell b
// != a) whose centre-to-centre segment crosses no portal of those two cells: the faces where light or a
// walker could pass from one cell to the other without a portal.
template <class Visit>
void forEachUncoveredFace(const GridFrame& f, const std::vector<int32_t>& cell, const PortalsByPair& byPair,
                          Visit&& visit) {
  const ptrdiff_t strides[3] = {1, f.dims.x, ptrdiff_t(f.dims.x) * f.dims.y};
  const float tolerance = 0.5f * float(f.voxel);
  for (int z = 0; z + 1 < f.dims.z; ++z)
    for (int y = 0; y + 1 < f.dims.y; ++y)
      for (int x = 0; x + 1 < f.dims.x; ++x) {
        const size_t i = f.index(x, y, z);
        const int a = cell[i];
        if (a < 0) continue;
        for (int k = 0; k < 3; ++k) {
          const size_t j = size_t(ptrdiff_t(i) + strides[k]);
          const int b = cell[j];
          if (b < 0 || b == a) continue;
          const auto it = byPair.find({std::min(a, b), std::max(a, b)});
          bool covered = false;
          if (it != byPair.end())
            for (const PortalQuad* q : it->second)
              if ((covered = segmentCrossesPortal(*q, f.centre(i), f.centre(j), tolerance))) break;
          if (!covered) visit(i, j, a, b, k);
        }
      }
}

}  // namespace

std::vector<PortalQuad> quadsOf(const std::vector<FittedPortal>& portals) {
  std::vector<PortalQuad> q;
  for (const FittedPortal& p : portals) q.push_back(p.quad);
  return q;
}

size_t countLeakingFaces(const GridFrame& f, const std::vector<int32_t>& cell,
                         const std::vector<PortalQuad>& portals) {
  PortalsByPair byPair;
  for (const PortalQuad& p : portals) addPortal(byPair, p);
  size_t leaks = 0;
  forEachUncoveredFace(f, cell, byPair, [&](size_t, size_t, int, int, int) { ++leaks; });
  return leaks;
}

std::map<std::pair<int, int>, size_t> leakingFacesByPair(const GridFrame& f, const std::vector<int32_t>& cell,
                                                         const std::vector<PortalQuad>& portals) {
  PortalsByPair byPair;
  for (const PortalQuad& p : portals) addPortal(byPair, p);
  std::map<std::pair<int, int>, size_t> out;
  forEachUncoveredFace(f, cell, byPair, [&](size_t, size_t, int a, int b, int) {
    ++out[{std::min(a, b), std::max(a, b)}];
  });
  return out;
}

namespace {

// Every face between two cells whose segment crosses no portal of those two cells (all of them when
// `portals` is empty), sorted by cell pair.
std::vector<Face> uncoveredFaces(const GridFrame& f, const std::vector<int32_t>& cell,
                                 const DistanceGrid& distance, const std::vector<FittedPortal>& portals) {
  PortalsByPair byPair;
  for (const FittedPortal& p : portals) addPortal(byPair, p.quad);
  std::vector<Face> faces;
  forEachUncoveredFace(f, cell, byPair, [&](size_t i, size_t j, int a, int b, int k) {
    const float s = float(std::min(distance.metres(i), distance.metres(j)));
    faces.push_back({std::min(a, b), std::max(a, b), i, k, a < b ? 1 : -1, s});
  });
  std::sort(faces.begin(), faces.end(), [](const Face& p, const Face& q) {
    return p.a != q.a ? p.a < q.a : p.b != q.b ? p.b < q.b : p.lower < q.lower;
  });
  return faces;
}

// Per pair of cells, openings = faces connected within one voxel (half-coordinates within 2).
std::vector<std::vector<const Face*>> groupOpenings(const GridFrame& f, const std::vector<Face>& faces) {
  std::vector<std::vector<const Face*>> out;
  for (size_t lo = 0; lo < faces.size();) {
    size_t hi = lo;
    while (hi < faces.size() && faces[hi].a == faces[lo].a && faces[hi].b == faces[lo].b) ++hi;
    const int n = int(hi - lo);
    std::unordered_map<uint64_t, int> at;
    std::vector<glm::ivec3> half(static_cast<size_t>(n));
    for (int q = 0; q < n; ++q) {
      const Face& face = faces[lo + size_t(q)];
      glm::ivec3 hc = 2 * f.coord(face.lower);
      hc[face.axis] += 1;
      half[size_t(q)] = hc;
      at[halfKey(hc)] = q;
    }
    std::vector<int> parent(static_cast<size_t>(n));
    std::iota(parent.begin(), parent.end(), 0);
    for (int q = 0; q < n; ++q)
      for (int dz = -2; dz <= 2; ++dz)
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const auto it = at.find(halfKey(half[size_t(q)] + glm::ivec3(dx, dy, dz)));
            if (it != at.end()) parent[size_t(findRoot(parent, q))] = findRoot(parent, it->second);
          }
    std::map<int, std::vector<const Face*>> openings;
    for (int q = 0; q < n; ++q) openings[findRoot(parent, q)].push_back(&faces[lo + size_t(q)]);
    for (auto& [root, members] : openings) out.push_back(std::move(members));
    lo = hi;
  }
  return out;
}

// True when at least 90 % of the opening's faces are crossed along one grid axis: a door or a window
// in a wall, a hole met at the floor's level. A stair's interface, following the steps, is not.
bool alongOneAxis(const std::vector<const Face*>& faces) {
  size_t count[3] = {0, 0, 0};
  for (const Face* face : faces) ++count[face->axis];
  return double(std::max({count[0], count[1], count[2]})) >= 0.9 * double(faces.size());
}

// The portals across the closed sections near a non-planar opening (sections.h), narrowest first, each
// facing away from the side of a's deepest voxel (faceFromAToB checks it once the cells are relabelled);
// none when no section is closed.
std::vector<FittedPortal> sectionPortals(const GridFrame& f, const std::vector<int32_t>& cell,
                                         const DistanceGrid& distance, const std::vector<const Face*>& faces,
                                         const std::vector<size_t>& deepest, const PortalParams& params) {
  const int a = faces.front()->a, b = faces.front()->b;
  const ptrdiff_t strides[3] = {1, f.dims.x, ptrdiff_t(f.dims.x) * f.dims.y};
  std::vector<size_t> voxels;
  for (const Face* face : faces)
    voxels.push_back(face->lower), voxels.push_back(size_t(ptrdiff_t(face->lower) + strides[face->axis]));
  const int search = int(std::ceil(params.searchRange / f.voxel));
  const std::vector<Section> sections =
      closedSections(f, cell, a, b, voxels, search, std::max<size_t>(400, 4 * faces.size()),
                     size_t(std::max(1, params.sectionCandidates)));
  std::vector<FittedPortal> out;
  for (const Section& s : sections) {
    // a is never the outside (numbered last), whose deepest voxel may lie at any corner of the grid.
    const int sign = f.coord(deepest[size_t(a)])[s.axis] > s.layer ? -1 : 1;
    std::vector<Face> cut;
    for (size_t v : s.voxels) cut.push_back({a, b, v, s.axis, sign, float(distance.metres(v))});
    std::vector<const Face*> refs;
    for (const Face& face : cut) refs.push_back(&face);
    FittedPortal fp = fitOpening(f, refs, params.marginVoxels);
    fp.faces = uint32_t(faces.size());
    fp.section = true;
    out.push_back(fp);
  }
  return out;
}

// Turns a portal so that its normal points from cellA into cellB, by the labels half a voxel either side
// of it at 5 × 5 points over the quad (its cells are on either side after relabelAcrossPortals).
void faceFromAToB(const GridFrame& f, const std::vector<int32_t>& cell, PortalQuad& q) {
  const float h = float(f.voxel);
  int vote = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      const float u = (float(i) + 0.5f) / 5.0f, v = (float(j) + 0.5f) / 5.0f;
      const glm::vec3 p =
          q.corners[0] + u * (q.corners[1] - q.corners[0]) + v * (q.corners[3] - q.corners[0]);
      for (float side : {-1.0f, 1.0f}) {
        const glm::ivec3 c = f.voxelOf(p + side * 0.5f * h * q.normal);
        if (!f.contains(c)) continue;
        const int l = cell[f.index(c)];
        vote += (l == q.cellB ? 1 : l == q.cellA ? -1 : 0) * int(side);
      }
    }
  if (vote >= 0) return;
  std::swap(q.corners[1], q.corners[3]);
  q.normal = -q.normal;
}

// Makes the cells of each pair joined by a section portal meet at its quad (relabelAcrossPortals), with
// as few of the pair's portals as cut the two apart. Between two rooms: first each opening's narrowest
// section alone, largest opening first (the hole of a stair); then every opening's narrowest section
// together (a door and a window in one zero-thickness wall, neither of which cuts the rooms apart alone);
// then each opening's wider sections alone (the hole, where a pocket between the steps and the floor's
// edge is narrower); then every portal of the pair. Between a room and the outside every portal of the
// pair (the room's windows and doors all open onto it). The portals left out are dropped. When none of
// these cuts the pair apart, its sections go back to the planes fitted to their interfaces.
void relabelSectionPairs(const GridFrame& f, std::vector<int32_t>& cell, const std::vector<size_t>& deepest,
                         int outsideCell, const PortalParams& params, std::vector<FittedPortal>& fresh,
                         const std::vector<FittedPortal>& planeFits,
                         const std::vector<std::vector<FittedPortal>>& alternatives,
                         const std::vector<char>& planar) {
  std::vector<char> redundant(fresh.size(), 0);
  std::set<std::pair<int, int>> done;
  for (size_t k = 0; k < fresh.size(); ++k) {
    const int a = fresh[k].quad.cellA, b = fresh[k].quad.cellB;
    if (!fresh[k].section || !done.insert({a, b}).second) continue;
    std::vector<size_t> sections, others;
    for (size_t q = 0; q < fresh.size(); ++q)
      if (fresh[q].quad.cellA == a && fresh[q].quad.cellB == b)
        (fresh[q].section ? sections : others).push_back(q);
    std::sort(sections.begin(), sections.end(),
              [&](size_t x, size_t y) { return fresh[x].quad.area > fresh[y].quad.area; });
    std::vector<size_t> all = sections;
    all.insert(all.end(), others.begin(), others.end());
    // True (and the pair relabelled, the portals not used marked redundant) when `used` cuts a from b.
    auto separate = [&](const std::vector<size_t>& used) {
      std::vector<const PortalQuad*> barrier;
      for (size_t q : used) barrier.push_back(&fresh[q].quad);
      if (!relabelAcrossPortals(f, cell, a, b, deepest[size_t(a)], deepest[size_t(b)], barrier)) return false;
      for (size_t q : all) redundant[q] = std::find(used.begin(), used.end(), q) == used.end();
      for (size_t q : used)
        if (fresh[q].section) faceFromAToB(f, cell, fresh[q].quad);
      return true;
    };
    // One section opening's candidates [first, last) alone, in turn (candidate 0 is fresh[q] itself).
    auto cutAlone = [&](size_t first, size_t last) {
      for (size_t q : sections)
        for (size_t c = first; c < std::min(last, alternatives[q].size()); ++c) {
          const FittedPortal kept = fresh[q];
          fresh[q] = alternatives[q][c];
          if (separate({q})) return true;
          fresh[q] = kept;
        }
      return false;
    };
    // Each section opening's candidates in turn with the pair's planar openings (a door beside the stair's
    // hole): the narrowest section can close the hole only with the slivers fitted round a balustrade.
    auto cutWithPlanar = [&]() {
      std::vector<size_t> used;
      for (size_t q : others)
        if (planar[q]) used.push_back(q);
      if (used.empty()) return false;
      for (size_t q : sections)
        for (size_t c = 0; c < alternatives[q].size(); ++c) {
          const FittedPortal kept = fresh[q];
          fresh[q] = alternatives[q][c];
          used.push_back(q);
          if (separate(used)) return true;
          used.pop_back();
          fresh[q] = kept;
        }
      return false;
    };
    const bool rooms = a != outsideCell && b != outsideCell;
    if (rooms && (cutAlone(0, 1) || (sections.size() > 1 && separate(sections)) ||
                  cutAlone(1, std::numeric_limits<size_t>::max()) || cutWithPlanar()))
      continue;
    if ((!others.empty() || !rooms || sections.size() == 1) && separate(all)) continue;
    for (size_t q : sections) {
      fresh[q] = planeFits[q];
      centreInConstriction(fresh[q], f, cell, params.searchRange);
      relabelSlab(f, fresh[q], cell);
    }
  }
  for (size_t k = fresh.size(); k-- > 0;)
    if (redundant[k]) fresh.erase(fresh.begin() + ptrdiff_t(k));
}

}  // namespace

PortalSet fitPortals(CellLabels cells, const DistanceGrid& distance, const PortalParams& params,
                     Context& ctx) {
  auto timer = ctx.time("portals");
  const GridFrame& f = cells.frame;
  PortalSet out;
  out.cell = std::move(cells.cell);
  // Each cell's deepest voxel, to tell the sides of a section portal apart (SIZE_MAX: none). Not the
  // grid's first voxel to start with: that corner of open ground may lie farther from the walls than a
  // room's middle, and a seed outside its cell parts nothing (or empties the cell).
  std::vector<size_t> deepest(size_t(cells.cellCount()), SIZE_MAX);
  for (size_t i = 0; i < out.cell.size(); ++i) {
    const int c = out.cell[i];
    if (c >= 0 && (deepest[size_t(c)] == SIZE_MAX || distance.d2[i] > distance.d2[deepest[size_t(c)]]))
      deepest[size_t(c)] = i;
  }
  // Round 0 fits every opening; later rounds fit what the earlier portals left uncovered (an interface
  // that bends out of its portal's slab, the fringe of a wide arch), up to params.extraRounds times.
  for (int round = 0; round <= params.extraRounds; ++round) {
    const std::vector<Face> faces = uncoveredFaces(f, out.cell, distance, out.portals);
    if (faces.empty()) break;
    std::vector<FittedPortal> fresh, planeFits;
    std::vector<std::vector<FittedPortal>> alternatives;  // per fresh portal: its section candidates
    std::vector<char> planar;  // per fresh portal: its opening crossed along one axis
    for (const std::vector<const Face*>& opening : groupOpenings(f, faces)) {
      FittedPortal fp = fitOpening(f, opening, params.marginVoxels);
      std::vector<FittedPortal> cuts;
      const bool oneAxis = alongOneAxis(opening);
      if (round == 0 && !oneAxis) cuts = sectionPortals(f, out.cell, distance, opening, deepest, params);
      // Several pieces of one stair's interface find the same section: one portal for them.
      if (!cuts.empty() && std::any_of(fresh.begin(), fresh.end(), [&](const FittedPortal& q) {
            return q.section && q.quad.cellA == cuts.front().quad.cellA &&
                   q.quad.cellB == cuts.front().quad.cellB &&
                   glm::length(q.quad.centre() - cuts.front().quad.centre()) < 2.0f * float(f.voxel);
          }))
        continue;
      planeFits.push_back(fp);
      fresh.push_back(cuts.empty() ? fp : cuts.front());
      alternatives.push_back(std::move(cuts));
      planar.push_back(oneAxis);
    }
    // Each to the middle of its constriction, then the cells made to meet exactly at its quad.
    // Later rounds leave the labels alone: relabelling around a fringe portal moves the interface
    // somewhere else instead of covering it. A section portal's cells are relabelled by side, whole:
    // the stair's interface runs far from the hole the portal covers.
    if (round == 0) {
      for (FittedPortal& fp : fresh)
        if (!fp.section) centreInConstriction(fp, f, out.cell, params.searchRange);
      for (const FittedPortal& fp : fresh)
        if (!fp.section) relabelSlab(f, fp, out.cell);
      relabelSectionPairs(f, out.cell, deepest, cells.outsideCell, params, fresh, planeFits, alternatives,
                          planar);
    }
    out.portals.insert(out.portals.end(), fresh.begin(), fresh.end());
  }
  out.leakingFaces = countLeakingFaces(f, out.cell, quadsOf(out.portals));
  ctx.progress("portals", 1.0);
  return out;
}

}  // namespace cpgi::decomp
