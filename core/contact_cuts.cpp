#include "core/contact_cuts.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Cartesian_converter.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include "core/quads.h"

namespace cpgi {

namespace {

// Exact predicates filter the candidate pairs; the segments and the cuts in a face's plane are constructed
// exactly (real exports hold near-degenerate pairs whose inexact constructions come out NaN); the rays that
// find buried pieces need neither.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using Plain = CGAL::Simple_cartesian<double>;
using Point3 = K::Point_3;
using Triangle3 = K::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, uint32_t>;
using RayTriangles = std::vector<Plain::Triangle_3>;
using Tree = CGAL::AABB_tree<
    CGAL::AABB_traits<Plain, CGAL::AABB_triangle_primitive<Plain, RayTriangles::const_iterator>>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Exact,
    CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_2<Exact>,
                                         CGAL::Constrained_triangulation_face_base_2<Exact>>,
    CGAL::Exact_intersections_tag>;

Point3 point(const glm::dvec3& p) {
  return {p.x, p.y, p.z};
}
glm::dvec3 vec(const Exact::Point_3& p) {
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

// Whether triangles a and b share an edge: then they meet along it alone, which cuts neither.
bool shareEdge(const Triangle& a, const Triangle& b) {
  int shared = 0;
  for (const glm::vec3& p : a.p)
    for (const glm::vec3& q : b.p) shared += p == q;
  return shared >= 2;
}

struct Segment {
  glm::dvec3 a, b;
  /// Where a solid standing on the face's front meets it (the outline of its foot), rather than where one
  /// runs through it.
  bool standing = false;
};

// The segment of face `f` under the foot of `s` when `s` stands on f's front: one edge of s lies within
// `standOff` of f's plane and the rest of s in front of it. The edge is projected onto the plane (exactly:
// a foot a few millimetres up must cut as one that touches) and clipped to f.
std::optional<Segment> footOn(const Triangle& f, const Triangle3& fExact, const Triangle& s,
                              double standOff) {
  const glm::dvec3 o(f.p[0]);
  const glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(f.p[1]) - o, glm::dvec3(f.p[2]) - o));
  int low[3], lows = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = glm::dot(glm::dvec3(s.p[k]) - o, n);
    if (d < -standOff) return std::nullopt;  // through f or behind it
    if (d <= standOff) low[lows++] = k;
  }
  if (lows != 2) return std::nullopt;  // a corner on f, or s lying on it
  const CGAL::Cartesian_converter<K, Exact> exact;
  const Exact::Triangle_3 face = exact(fExact);
  const Exact::Plane_3 plane = face.supporting_plane();
  const Exact::Segment_3 edge(plane.projection(exact(point(s.p[low[0]]))),
                              plane.projection(exact(point(s.p[low[1]]))));
  // An edge across the plane shorter than twice the stand-off projects to a point: no outline (CGAL's
  // segment-triangle intersection asserts on a degenerate segment).
  if (edge.is_degenerate()) return std::nullopt;
  const auto hit = CGAL::intersection(edge, face);
  if (!hit) return std::nullopt;
  if (const Exact::Segment_3* g = boost::get<Exact::Segment_3>(&*hit))
    return Segment{vec(g->source()), vec(g->target()), true};
  return std::nullopt;
}

// Per scene triangle, the segments where other triangles meet it: where one runs through it, and where
// one stands on its front within `standOff` (coplanar overlaps left out: a face lying on another hides
// nothing the cut would show).
std::vector<std::vector<Segment>> contactSegments(const Scene& scene, const std::vector<Triangle3>& tris,
                                                  const std::vector<char>& valid, double standOff) {
  std::vector<Box> boxes;
  for (uint32_t i = 0; i < tris.size(); ++i)
    if (valid[i]) {
      const CGAL::Bbox_3 b = tris[i].bbox();
      boxes.emplace_back(CGAL::Bbox_3(b.xmin() - standOff, b.ymin() - standOff, b.zmin() - standOff,
                                      b.xmax() + standOff, b.ymax() + standOff, b.zmax() + standOff),
                         i);
    }
  std::vector<std::vector<Segment>> out(tris.size());
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const uint32_t i = x.info(), j = y.info();
    const Triangle &ti = scene.triangles[i], &tj = scene.triangles[j];
    if (std::abs(glm::dot(ti.geometricNormal(), tj.geometricNormal())) > 1.0f - 1e-6f)
      return;  // parallel: apart, or coplanar
    if (shareEdge(ti, tj)) return;
    // A solid standing on a face meets it along its foot's edges alone, which lie on the solid's own
    // boundary: only the face under it is cut.
    const std::optional<Segment> jOnI = footOn(ti, tris[i], tj, standOff);
    const std::optional<Segment> iOnJ = footOn(tj, tris[j], ti, standOff);
    if (jOnI) out[i].push_back(*jOnI);
    if (iOnJ) out[j].push_back(*iOnJ);
    if (jOnI || iOnJ || !CGAL::do_intersect(tris[i], tris[j])) return;
    const CGAL::Cartesian_converter<K, Exact> exact;
    const auto hit = CGAL::intersection(exact(tris[i]), exact(tris[j]));
    if (!hit) return;
    if (const Exact::Segment_3* s = boost::get<Exact::Segment_3>(&*hit)) {
      const Segment seg{vec(s->source()), vec(s->target())};
      out[i].push_back(seg), out[j].push_back(seg);
    }
  });
  return out;
}

// `segs` with the collinear ones that overlap or touch joined: a line across a face meets each of the
// triangles of the solid's face (and of this face's quad) apart, and only the whole line runs edge to edge.
std::vector<Segment> joinCollinear(std::vector<Segment> segs, double tol) {
  for (bool joined = true; joined;) {
    joined = false;
    for (size_t i = 0; i < segs.size() && !joined; ++i)
      for (size_t j = i + 1; j < segs.size() && !joined; ++j) {
        const glm::dvec3 a = segs[i].a, d = segs[i].b - a;
        const double len = glm::length(d);
        if (len < tol) continue;
        const glm::dvec3 u = d / len;
        const auto off = [&](const glm::dvec3& p) { return glm::length((p - a) - glm::dot(p - a, u) * u); };
        if (off(segs[j].a) > tol || off(segs[j].b) > tol) continue;
        const double t0 = glm::dot(segs[j].a - a, u), t1 = glm::dot(segs[j].b - a, u);
        const double lo = std::min(t0, t1), hi = std::max(t0, t1);
        if (lo > len + tol || hi < -tol) continue;
        const double from = std::min(0.0, lo), to = std::max(len, hi);
        segs[i] = {a + from * u, a + to * u, segs[i].standing || segs[j].standing};
        segs.erase(segs.begin() + std::ptrdiff_t(j));
        joined = true;
      }
  }
  return segs;
}

// Whether the point `p` lifted off a face of normal `n` lies inside a solid: most rays over its front
// hemisphere first meet a face from behind.
class BuriedTest {
 public:
  BuriedTest(const Scene& scene, const std::vector<Triangle3>& tris, const std::vector<char>& valid,
             const ContactCutParams& params)
      : params_(params) {
    for (size_t i = 0; i < tris.size(); ++i)
      if (valid[i]) {
        const Triangle& t = scene.triangles[i];
        kept_.emplace_back(plain(t.p[0]), plain(t.p[1]), plain(t.p[2]));
        normals_.push_back(glm::dvec3(t.geometricNormal()));
      }
    tree_.insert(kept_.begin(), kept_.end());
    tree_.build();
  }

  /// `lift`: metres off the face the rays leave from (past a foot standing up to that far off it).
  bool operator()(const glm::dvec3& p, const glm::dvec3& n, double lift) const {
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t = glm::normalize(glm::cross(n, helper)), b = glm::cross(n, t);
    const Plain::Point_3 origin = plain(p + lift * n);
    const int rays = std::max(1, params_.rays);
    int behind = 0;
    for (int k = 0; k < rays; ++k) {
      // A Fibonacci spiral over the hemisphere, grazing directions (cosine under 0.2) left out.
      const double z = 1.0 - 0.8 * (k + 0.5) / rays, r = std::sqrt(1.0 - z * z), phi = 2.39996323 * k;
      const glm::dvec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + z * n;
      const auto hit =
          tree_.first_intersected_primitive(Plain::Ray_3(origin, Plain::Vector_3(d.x, d.y, d.z)));
      if (hit && glm::dot(normals_[size_t(*hit - kept_.begin())], d) > 0.0) ++behind;
    }
    return behind >= params_.buriedShare * rays;
  }

 private:
  static Plain::Point_3 plain(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

  const ContactCutParams& params_;
  RayTriangles kept_;
  std::vector<glm::dvec3> normals_;
  Tree tree_;
};

// The normal at `p` interpolated over whichever of `sources` holds it (the first when none does).
glm::vec3 normalAt(std::span<const Triangle* const> sources, const glm::dvec3& p) {
  for (size_t k = 0; k < sources.size(); ++k) {
    const Triangle& t = *sources[k];
    const glm::dvec3 a(t.p[0]), e1 = glm::dvec3(t.p[1]) - a, e2 = glm::dvec3(t.p[2]) - a, q = p - a;
    const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
    const double d20 = glm::dot(q, e1), d21 = glm::dot(q, e2), den = d00 * d11 - d01 * d01;
    if (den <= 0.0) continue;
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den, u = 1.0 - v - w;
    if (k + 1 < sources.size() && (u < -1e-6 || v < -1e-6 || w < -1e-6)) continue;
    const glm::vec3 n = float(u) * t.n[0] + float(v) * t.n[1] + float(w) * t.n[2];
    const float len = glm::length(n);
    return len > 0.0f ? n / len : t.geometricNormal();
  }
  return sources[0]->geometricNormal();
}

// A piece of `source` with corners `p` (wound as `source`), its normals interpolated over `sources`.
Triangle piece(const Triangle& source, std::span<const Triangle* const> sources,
               const std::array<glm::dvec3, 3>& p) {
  Triangle t = source;
  for (int k = 0; k < 3; ++k) t.p[k] = glm::vec3(p[k]), t.n[k] = normalAt(sources, p[k]);
  return t;
}

struct FaceResult {
  bool cut = false;
  bool leftWhole = false;
  std::vector<Triangle> pieces;
  std::vector<Triangle> buriedPieces;  ///< the pieces dropped, for Scene::buriedPieces
  size_t buried = 0;
  double buriedArea = 0.0;
};

// Sorted coordinates in [0, 1] with those closer than `eps` merged; 0 and 1 included.
std::vector<double> breaks(std::vector<double> at, double eps) {
  at.push_back(0.0), at.push_back(1.0);
  std::sort(at.begin(), at.end());
  std::vector<double> out;
  for (double x : at) {
    x = std::clamp(x, 0.0, 1.0);
    if (out.empty() || x - out.back() > eps) out.push_back(x);
  }
  if (out.back() < 1.0) out.back() = 1.0;
  return out;
}

// An axis-parallel cut of a quad in its (s, t) frame: at `at` along one axis, over [lo, hi] of the other.
struct AxisCut {
  double at, lo, hi;
};

// A quad's cuts in its (s, t) frame from the segments on it: through-cuts from edge to edge, feet's outlines
// (QuadCuts::standing when there is one). nullopt when a through-cut runs askew to its edges.
struct QuadCuts {
  std::vector<AxisCut> s, t;
  bool standing = false;
};
std::optional<QuadCuts> quadCuts(const std::vector<Segment>& segs, const glm::dvec3& c0, const glm::dvec3& u,
                                 const glm::dvec3& v, const ContactCutParams& params) {
  const double w = glm::length(u), h = glm::length(v), tol = params.tolerance;
  QuadCuts cuts;
  const auto onBorder = [&](const glm::dvec2& p) {
    return std::min(p.x, 1.0 - p.x) * w < tol || std::min(p.y, 1.0 - p.y) * h < tol;
  };
  for (const Segment& g : segs) {
    const glm::dvec2 a(glm::dot(g.a - c0, u) / (w * w), glm::dot(g.a - c0, v) / (h * h));
    const glm::dvec2 b(glm::dot(g.b - c0, u) / (w * w), glm::dot(g.b - c0, v) / (h * h));
    const double length = glm::length(g.b - g.a);
    if (length < tol) continue;
    const bool sConst = std::abs(a.x - b.x) * w < tol, tConst = std::abs(a.y - b.y) * h < tol;
    const double sLo = std::min(a.y, b.y), sHi = std::max(a.y, b.y), tLo = std::min(a.x, b.x),
                 tHi = std::max(a.x, b.x);
    if (g.standing) {
      // A foot's outline: an edge of it narrower than minFootprint (a table's leg) or askew to the quad
      // cuts nothing, and one within standOff of the quad's edge lies on that edge (a wardrobe set a few
      // millimetres off the wall leaves no sliver behind it); its ends likewise.
      if (length < params.minFootprint || (!sConst && !tConst)) continue;
      const double near = params.standOff;
      const auto snapped = [&](double lo, double hi, double size) {
        return std::pair(lo * size < near ? 0.0 : lo, (1.0 - hi) * size < near ? 1.0 : hi);
      };
      if (sConst) {
        const double at = 0.5 * (a.x + b.x);
        if (at * w < near || (1.0 - at) * w < near) continue;
        const auto [lo, hi] = snapped(sLo, sHi, h);
        cuts.s.push_back({at, lo, hi});
      } else {
        const double at = 0.5 * (a.y + b.y);
        if (at * h < near || (1.0 - at) * h < near) continue;
        const auto [lo, hi] = snapped(tLo, tHi, w);
        cuts.t.push_back({at, lo, hi});
      }
      cuts.standing = true;
      continue;
    }
    // A solid through the face cuts it from edge to edge only: one sunk into it mid-face (a cabinet 5 cm into
    // a slab) meets it along no edge of its own and shades its foot as a contact shadow.
    if (sConst) {
      const double at = 0.5 * (a.x + b.x);
      if (at * w > tol && (1.0 - at) * w > tol && sLo * h < tol && (1.0 - sHi) * h < tol)
        cuts.s.push_back({at, sLo, sHi});
    } else if (tConst) {
      const double at = 0.5 * (a.y + b.y);
      if (at * h > tol && (1.0 - at) * h > tol && tLo * w < tol && (1.0 - tHi) * w < tol)
        cuts.t.push_back({at, tLo, tHi});
    } else if (onBorder(a) && onBorder(b)) {
      return std::nullopt;  // askew from edge to edge: cut by triangles
    }
  }
  return cuts;
}

// A quad cut into rectangles: the grid through its cuts, each cell buried or not, the visible cells merged
// into the largest rectangles that cross no cut. nullopt when a cut runs askew to its edges.
std::optional<FaceResult> cutQuad(const Scene& scene, const Quad& q, const std::vector<Segment>& segs,
                                  const BuriedTest& buried, const ContactCutParams& params) {
  const glm::dvec3 c0(q.corners[0]), u = glm::dvec3(q.corners[1]) - c0, v = glm::dvec3(q.corners[3]) - c0;
  const double w = glm::length(u), h = glm::length(v), tol = params.tolerance;
  const std::optional<QuadCuts> cuts = quadCuts(segs, c0, u, v, params);
  if (!cuts) return std::nullopt;
  const std::vector<AxisCut>&sCuts = cuts->s, &tCuts = cuts->t;
  const bool standing = cuts->standing;
  FaceResult r;
  if (sCuts.empty() && tCuts.empty()) return r;
  std::vector<double> sAt, tAt;
  for (const AxisCut& c : sCuts) sAt.push_back(c.at);
  for (const AxisCut& c : tCuts) tAt.push_back(c.at);
  const std::vector<double> sb = breaks(sAt, tol / w), tb = breaks(tAt, tol / h);
  const int ns = int(sb.size()) - 1, nt = int(tb.size()) - 1;
  if (size_t(ns) * size_t(nt) > 4 * params.maxPiecesPerFace) {
    r.leftWhole = true;
    return r;
  }
  // Whether the grid line at `at` (index i of `lines`) is cut over the middle of [lo, hi].
  const auto covered = [&](const std::vector<AxisCut>& cuts, double at, double lo, double hi, double scale) {
    const double mid = 0.5 * (lo + hi);
    return std::any_of(cuts.begin(), cuts.end(), [&](const AxisCut& c) {
      return std::abs(c.at - at) * scale < tol && mid >= c.lo && mid <= c.hi;
    });
  };
  // vCut(i, j): the line between columns i−1 and i cut along row j; hCut(i, j): between rows j−1 and j.
  const auto vCut = [&](int i, int j) {
    return covered(sCuts, sb[size_t(i)], tb[size_t(j)], tb[size_t(j) + 1], w);
  };
  const auto hCut = [&](int i, int j) {
    return covered(tCuts, tb[size_t(j)], sb[size_t(i)], sb[size_t(i) + 1], h);
  };
  const glm::dvec3 n = glm::normalize(glm::cross(u, v));
  const double lift = params.lift + (standing ? params.standOff : 0.0);
  const auto at = [&](double s, double t) { return c0 + s * u + t * v; };
  // A cell is buried when its centre and its corners, pulled standOff into it, all are: a foot edge too short
  // to cut (a 5 cm panel's end) leaves a cell that runs past the foot, of which only a part is covered.
  const auto buriedCell = [&](glm::dvec2 lo, glm::dvec2 hi) {
    if (!buried(at(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)), n, lift)) return false;
    const double ds = std::min(params.standOff / w, 0.25 * (hi.x - lo.x)),
                 dt = std::min(params.standOff / h, 0.25 * (hi.y - lo.y));
    for (const glm::dvec2 c : {glm::dvec2(lo.x + ds, lo.y + dt), glm::dvec2(hi.x - ds, lo.y + dt),
                               glm::dvec2(hi.x - ds, hi.y - dt), glm::dvec2(lo.x + ds, hi.y - dt)})
      if (!buried(at(c.x, c.y), n, lift)) return false;
    return true;
  };
  std::vector<char> visible(size_t(ns * nt)), taken(size_t(ns * nt), 0);
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < ns; ++i) {
      const glm::dvec2 lo(sb[i], tb[j]), hi(sb[i + 1], tb[j + 1]);
      visible[size_t(j * ns + i)] = !buriedCell(lo, hi);
    }
  const Triangle* sources[2] = {&scene.triangles[q.triangles[0]], &scene.triangles[q.triangles[1]]};
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < ns; ++i) {
      if (visible[size_t(j * ns + i)]) continue;
      ++r.buried;
      r.buriedArea += (sb[i + 1] - sb[i]) * w * (tb[j + 1] - tb[j]) * h;
      const glm::dvec3 p00 = at(sb[i], tb[j]), p10 = at(sb[i + 1], tb[j]), p11 = at(sb[i + 1], tb[j + 1]),
                       p01 = at(sb[i], tb[j + 1]);
      r.buriedPieces.push_back(piece(*sources[0], sources, {p00, p10, p11}));
      r.buriedPieces.push_back(piece(*sources[0], sources, {p00, p11, p01}));
    }
  const auto free = [&](int i, int j) { return visible[size_t(j * ns + i)] && !taken[size_t(j * ns + i)]; };
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < ns; ++i) {
      if (!free(i, j)) continue;
      int i1 = i;
      while (i1 + 1 < ns && free(i1 + 1, j) && !vCut(i1 + 1, j)) ++i1;
      int j1 = j;
      for (;;) {
        const int jn = j1 + 1;
        bool ok = jn < nt;
        for (int k = i; ok && k <= i1; ++k) ok = free(k, jn) && !hCut(k, jn) && (k == i || !vCut(k, jn));
        if (!ok) break;
        j1 = jn;
      }
      for (int jj = j; jj <= j1; ++jj)
        for (int ii = i; ii <= i1; ++ii) taken[size_t(jj * ns + ii)] = 1;
      const glm::dvec3 p00 = at(sb[i], tb[j]), p10 = at(sb[i1 + 1], tb[j]), p11 = at(sb[i1 + 1], tb[j1 + 1]),
                       p01 = at(sb[i], tb[j1 + 1]);
      // Its material, node and texture map from the quad's triangle that holds its centre.
      const glm::dvec3 mid = 0.5 * (p00 + p11);
      const glm::dvec3 a(sources[1]->p[0]);
      const bool second =
          glm::dot(glm::cross(glm::dvec3(sources[1]->p[1]) - a, mid - a), n) >= 0.0 &&
          glm::dot(glm::cross(glm::dvec3(sources[1]->p[2]) - glm::dvec3(sources[1]->p[1]),
                              mid - glm::dvec3(sources[1]->p[1])),
                   n) >= 0.0 &&
          glm::dot(glm::cross(a - glm::dvec3(sources[1]->p[2]), mid - glm::dvec3(sources[1]->p[2])), n) >=
              0.0;
      const Triangle& source = *sources[second ? 1 : 0];
      r.pieces.push_back(piece(source, sources, {p00, p10, p11}));
      r.pieces.push_back(piece(source, sources, {p00, p11, p01}));
    }
  r.cut = r.buried > 0 || r.pieces.size() > 2;
  if (r.pieces.size() / 2 > params.maxPiecesPerFace) r = FaceResult{}, r.leftWhole = true;
  return r;
}

// A triangle cut by a constrained Delaunay triangulation of its edges and the segments across it.
FaceResult cutTriangle(const Triangle& t, const std::vector<Segment>& segs, const BuriedTest& buried,
                       const ContactCutParams& params) {
  FaceResult r;
  const double tol = params.tolerance;
  const glm::dvec3 o(t.p[0]), p1(t.p[1]), p2(t.p[2]);
  const glm::dvec3 n = glm::normalize(glm::cross(p1 - o, p2 - o));
  const glm::dvec3 e1 = glm::normalize(p1 - o), e2 = glm::cross(n, e1);
  const std::array<glm::dvec3, 3> corner{o, p1, p2};
  // An end within the tolerance of a corner or an edge is put on it: no sliver along the edge.
  const auto snap = [&](glm::dvec3 p, double near) {
    p -= glm::dot(p - o, n) * n;
    for (const glm::dvec3& c : corner)
      if (glm::length(p - c) < near) return c;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 a = corner[k], d = corner[(k + 1) % 3] - a;
      const double f = std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0, 1.0);
      if (glm::length(a + f * d - p) < near) return a + f * d;
    }
    return p;
  };
  const auto onEdge = [&](const glm::dvec3& a, const glm::dvec3& b) {
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 c = corner[k], d = glm::normalize(corner[(k + 1) % 3] - c);
      const auto off = [&](const glm::dvec3& p) { return glm::length((p - c) - glm::dot(p - c, d) * d); };
      if (off(a) < tol && off(b) < tol) return true;
    }
    return false;
  };
  const auto onBoundary = [&](const glm::dvec3& p) {
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 c = corner[k], d = corner[(k + 1) % 3] - c;
      const double f = std::clamp(glm::dot(p - c, d) / glm::dot(d, d), 0.0, 1.0);
      if (glm::length(c + f * d - p) < tol) return true;
    }
    return false;
  };
  const auto flat = [&](const glm::dvec3& p) {
    return Exact::Point_2(glm::dot(p - o, e1), glm::dot(p - o, e2));
  };
  std::vector<std::pair<glm::dvec3, glm::dvec3>> inside;
  bool standing = false;
  for (const Segment& g : segs) {
    if (g.standing) {
      // A foot's outline, as on quads (cutQuad): not a leg's, not along the face's edge.
      const glm::dvec3 a = snap(g.a, params.standOff), b = snap(g.b, params.standOff);
      if (glm::length(b - a) >= params.minFootprint && !onEdge(a, b))
        inside.push_back({a, b}), standing = true;
      continue;
    }
    const glm::dvec3 a = snap(g.a, tol), b = snap(g.b, tol);
    // Through-cuts from edge to edge only, as on quads (cutQuad).
    if (glm::length(b - a) >= tol && !onEdge(a, b) && onBoundary(a) && onBoundary(b))
      inside.push_back({a, b});
  }
  const double lift = params.lift + (standing ? params.standOff : 0.0);
  if (inside.empty()) return r;
  if (inside.size() > 4 * params.maxPiecesPerFace) {
    r.leftWhole = true;
    return r;
  }
  Cdt cdt;
  for (int k = 0; k < 3; ++k) cdt.insert_constraint(flat(corner[k]), flat(corner[(k + 1) % 3]));
  for (const auto& [a, b] : inside) cdt.insert_constraint(flat(a), flat(b));
  const Triangle* sources[1] = {&t};
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    std::array<glm::dvec3, 3> p;
    for (int k = 0; k < 3; ++k) {
      const Exact::Point_2& q = f->vertex(k)->point();
      p[k] = o + CGAL::to_double(q.x()) * e1 + CGAL::to_double(q.y()) * e2;
    }
    const double area = 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    if (area < tol * tol) continue;
    // Buried when its centroid and its corners pulled standOff towards it all are, as a quad's cells.
    const glm::dvec3 centroid = (p[0] + p[1] + p[2]) / 3.0;
    const bool covered =
        buried(centroid, n, lift) && std::all_of(p.begin(), p.end(), [&](const glm::dvec3& c) {
          const double d = glm::length(centroid - c);
          return buried(c + std::min(params.standOff, 0.5 * d) / std::max(d, 1e-12) * (centroid - c), n,
                        lift);
        });
    if (covered) {
      ++r.buried, r.buriedArea += area;
      r.buriedPieces.push_back(piece(t, sources, p));
      continue;
    }
    r.pieces.push_back(piece(t, sources, p));
  }
  r.cut = true;
  if (r.pieces.size() > params.maxPiecesPerFace) r = FaceResult{}, r.leftWhole = true;
  return r;
}

}  // namespace

ContactCuts cutAtContacts(Scene& scene, CellGraph& cells, const ContactCutParams& params) {
  ContactCuts stats;
  const size_t count = scene.triangles.size();
  stats.trianglesBefore = stats.trianglesAfter = count;
  std::vector<Triangle3> tris(count);
  std::vector<char> valid(count, 0);
  for (size_t i = 0; i < count; ++i) {
    const Triangle& t = scene.triangles[i];
    tris[i] = Triangle3(point(t.p[0]), point(t.p[1]), point(t.p[2]));
    valid[i] = !tris[i].is_degenerate() && t.area() > 0.0f;
  }
  const std::vector<std::vector<Segment>> segs = contactSegments(scene, tris, valid, params.standOff);
  if (std::all_of(segs.begin(), segs.end(), [](const auto& s) { return s.empty(); })) return stats;
  const BuriedTest buried(scene, tris, valid, params);
  const QuadSet quads = findQuads(scene);

  // Per scene triangle, what replaces it: nothing cut (nullopt), or its pieces (a quad's all on its first).
  std::vector<std::optional<std::vector<Triangle>>> replaced(count);
  std::vector<Triangle> buriedPieces;
  const auto take = [&](const FaceResult& r, std::initializer_list<uint32_t> faceTriangles) {
    if (r.leftWhole) ++stats.leftWhole;
    if (!r.cut || r.leftWhole) return;
    ++stats.facesCut, stats.buriedPieces += r.buried, stats.buriedArea += r.buriedArea;
    buriedPieces.insert(buriedPieces.end(), r.buriedPieces.begin(), r.buriedPieces.end());
    bool first = true;
    for (uint32_t i : faceTriangles) replaced[i] = first ? r.pieces : std::vector<Triangle>{}, first = false;
  };
  std::vector<char> done(count, 0);
  for (const Quad& q : quads.quads) {
    const uint32_t a = q.triangles[0], b = q.triangles[1];
    if (segs[a].empty() && segs[b].empty()) continue;
    std::vector<Segment> both = segs[a];
    both.insert(both.end(), segs[b].begin(), segs[b].end());
    if (const std::optional<FaceResult> r =
            cutQuad(scene, q, joinCollinear(std::move(both), params.tolerance), buried, params)) {
      take(*r, {a, b});
      done[a] = done[b] = 1;
    }
  }
  for (uint32_t i = 0; i < count; ++i)
    if (!done[i] && valid[i] && !segs[i].empty())
      take(cutTriangle(scene.triangles[i], joinCollinear(segs[i], params.tolerance), buried, params), {i});
  if (stats.facesCut == 0) return stats;

  std::vector<Triangle> out;
  std::vector<std::vector<uint32_t>> newOf(count);
  for (size_t i = 0; i < count; ++i) {
    if (!replaced[i]) {
      newOf[i].push_back(uint32_t(out.size())), out.push_back(scene.triangles[i]);
      continue;
    }
    for (const Triangle& p : *replaced[i]) newOf[i].push_back(uint32_t(out.size())), out.push_back(p);
  }
  for (Cell& c : cells.cells) {
    std::vector<uint32_t> mapped;
    for (uint32_t i : c.triangles)
      if (i < count) mapped.insert(mapped.end(), newOf[i].begin(), newOf[i].end());
    c.triangles = std::move(mapped);
  }
  scene.triangles = std::move(out);
  scene.buriedPieces.insert(scene.buriedPieces.end(), buriedPieces.begin(), buriedPieces.end());
  stats.trianglesAfter = scene.triangles.size();
  return stats;
}

}  // namespace cpgi
