#include "radiosity/lightmap/quad_grids.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <unordered_map>

namespace cpgi {
namespace {

constexpr float kSnap = 1e-4f;  // m: corners this close are the same point

using Key = std::tuple<int64_t, int64_t, int64_t>;
Key keyOf(const glm::vec3& p) {
  return {std::llround(p.x / kSnap), std::llround(p.y / kSnap), std::llround(p.z / kSnap)};
}

// A quad re-expressed from one of its corners so that neighbouring tiles agree on u and v.
struct Tile {
  glm::vec3 origin, u, v;
};

Tile orient(const Quad& q, const glm::vec3& axis) {
  Tile best{};
  float bestDot = -2.0f;
  for (int k = 0; k < 4; ++k) {
    const glm::vec3 o = q.corners[k], u = q.corners[(k + 1) % 4] - o, v = q.corners[(k + 3) % 4] - o;
    const float d = glm::dot(glm::normalize(u), axis);
    if (d > bestDot + 1e-6f) bestDot = d, best = {o, u, v};
  }
  return best;
}

bool near(const glm::vec3& a, const glm::vec3& b) {
  return glm::length(a - b) <= kSnap;
}

struct Segment {
  glm::vec3 a, b;
};

// Edges of triangles standing on a plane (both ends on it, the triangle not lying in it): a wall on a
// floor, a box's base. Tiles sharing an edge that such a segment overlaps are not merged, so a chart
// never runs under a wall from one room into the next (one shooter would carry light through it).
// Only an edge that reaches the plane's tiles can block one of their shared edges, so the triangles are
// binned once in a uniform grid of their bounds and each plane looks only among those near its tiles:
// scanning every triangle for every plane took 5-8 s of the furnished house's layout (36 398 triangles,
// thousands of planes), none of it stoppable at a deadline.
class StandingEdges {
 public:
  explicit StandingEdges(const Scene& scene) : scene_(scene), normals_(scene.triangles.size()) {
    lo_ = glm::vec3(3.0e38f), hi_ = glm::vec3(-3.0e38f);
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
      normals_[t] = scene.triangles[t].geometricNormal();
      for (const glm::vec3& p : scene.triangles[t].p) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
    }
    if (scene.triangles.empty()) lo_ = hi_ = glm::vec3(0.0f);
    bins_ = std::clamp(int(std::cbrt(double(scene.triangles.size()) / 2.0)), 1, 64);
    cells_.resize(size_t(bins_) * bins_ * bins_);
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
      const Triangle& tri = scene.triangles[t];
      forCells(glm::min(glm::min(tri.p[0], tri.p[1]), tri.p[2]),
               glm::max(glm::max(tri.p[0], tri.p[1]), tri.p[2]),
               [&](std::vector<uint32_t>& cell) { cell.push_back(uint32_t(t)); });
    }
    seen_.assign(scene.triangles.size(), 0);
  }

  // The standing edges of the plane of unit `normal` at `offset` along it that may reach the box [lo, hi].
  std::vector<Segment> around(const glm::vec3& normal, float offset, const glm::vec3& lo,
                              const glm::vec3& hi) {
    std::vector<Segment> out;
    ++stamp_;
    forCells(lo - glm::vec3(2.0f * kSnap), hi + glm::vec3(2.0f * kSnap), [&](std::vector<uint32_t>& cell) {
      for (uint32_t t : cell) {
        if (seen_[t] == stamp_) continue;
        seen_[t] = stamp_;
        if (!(std::abs(glm::dot(normals_[t], normal)) < 0.999f)) continue;
        const Triangle& tri = scene_.triangles[t];
        for (int k = 0; k < 3; ++k) {
          const glm::vec3 a = tri.p[k], b = tri.p[(k + 1) % 3];
          if (std::abs(glm::dot(a, normal) - offset) <= kSnap &&
              std::abs(glm::dot(b, normal) - offset) <= kSnap)
            out.push_back({a, b});
        }
      }
    });
    return out;
  }

 private:
  template <class F>
  void forCells(const glm::vec3& lo, const glm::vec3& hi, F&& f) {
    const glm::vec3 scale = float(bins_) / glm::max(hi_ - lo_, glm::vec3(1e-6f));
    const glm::ivec3 a = glm::clamp(glm::ivec3(glm::floor((lo - lo_) * scale)), 0, bins_ - 1);
    const glm::ivec3 b = glm::clamp(glm::ivec3(glm::floor((hi - lo_) * scale)), 0, bins_ - 1);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) f(cells_[(size_t(z) * bins_ + y) * bins_ + x]);
  }

  const Scene& scene_;
  std::vector<glm::vec3> normals_;
  glm::vec3 lo_, hi_;
  int bins_ = 1;
  std::vector<std::vector<uint32_t>> cells_;
  std::vector<uint32_t> seen_;
  uint32_t stamp_ = 0;
};

// Whether a standing edge runs along the shared tile edge s (collinear, overlapping by more than kSnap).
bool blocked(const Segment& s, const std::vector<Segment>& standing) {
  const glm::vec3 d = s.b - s.a;
  const float len = glm::length(d);
  if (!(len > 0.0f)) return false;
  const glm::vec3 dir = d / len;
  auto offLine = [&](const glm::vec3& p) { return glm::length(glm::cross(p - s.a, dir)); };
  for (const Segment& e : standing) {
    if (offLine(e.a) > kSnap || offLine(e.b) > kSnap) continue;
    float lo = glm::dot(e.a - s.a, dir), hi = glm::dot(e.b - s.a, dir);
    if (lo > hi) std::swap(lo, hi);
    if (std::min(hi, len) - std::max(lo, 0.0f) > kSnap) return true;
  }
  return false;
}

}  // namespace

std::vector<QuadGrid> findQuadGrids(const QuadSet& quads, const std::vector<char>& usable, const Scene& scene,
                                    int maxQuads, const std::vector<uint32_t>* group) {
  const size_t n = quads.quads.size();
  maxQuads = std::max(maxQuads, 1);
  // Planes: material (and group), normal and offset, snapped. Each plane's first quad sets the axis u
  // turns towards.
  std::map<std::tuple<uint32_t, uint32_t, Key, int64_t>, std::vector<uint32_t>> planes;
  for (uint32_t q = 0; q < n; ++q) {
    if (!usable[q]) continue;
    const Quad& quad = quads.quads[q];
    const uint32_t material = scene.triangles[quad.triangles[0]].material;
    const glm::vec3 nrm = glm::normalize(quad.normal);
    const Key nk{std::llround(nrm.x * 1e4), std::llround(nrm.y * 1e4), std::llround(nrm.z * 1e4)};
    const uint32_t g = group ? (*group)[q] : 0;
    planes[{material, g, nk, std::llround(glm::dot(nrm, quad.corners[0]) / kSnap)}].push_back(q);
  }
  std::vector<int> gridOf(n, -1);
  std::vector<QuadGrid> grids;
  std::vector<Tile> tiles(n);
  StandingEdges standingEdges(scene);
  for (auto& [plane, members] : planes) {
    const Quad& lead = quads.quads[members.front()];
    const glm::vec3 leadNormal = glm::normalize(lead.normal);
    glm::vec3 lo(3.0e38f), hi(-3.0e38f);
    for (uint32_t q : members)
      for (const glm::vec3& c : quads.quads[q].corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
    const std::vector<Segment> standing =
        standingEdges.around(leadNormal, glm::dot(leadNormal, lead.corners[0]), lo, hi);
    const glm::vec3 axis =
        glm::normalize(quads.quads[members.front()].corners[1] - quads.quads[members.front()].corners[0]);
    std::map<Key, uint32_t> byOrigin;
    for (uint32_t q : members) {
      tiles[q] = orient(quads.quads[q], axis);
      byOrigin.emplace(keyOf(tiles[q].origin), q);
    }
    auto neighbour = [&](uint32_t q, int di, int dj) -> int {
      const Tile& t = tiles[q];
      const glm::vec3 at = t.origin + float(di) * t.u + float(dj) * t.v;
      const auto it = byOrigin.find(keyOf(at));
      if (it == byOrigin.end()) return -1;
      const Tile& o = tiles[it->second];
      if (!near(o.origin, at) || !near(o.u, t.u) || !near(o.v, t.v)) return -1;
      // The shared edge: the side of t towards the neighbour.
      const glm::vec3 lo = t.origin + float(std::max(di, 0)) * t.u + float(std::max(dj, 0)) * t.v;
      const Segment shared{lo, lo + (di != 0 ? t.v : t.u)};
      return blocked(shared, standing) ? -1 : int(it->second);
    };
    // Lattice coordinates by flooding each component of edge-sharing equal tiles.
    std::unordered_map<uint32_t, glm::ivec2> cell;
    for (uint32_t seed : members) {
      if (cell.count(seed)) continue;
      std::vector<uint32_t> component{seed};
      cell[seed] = glm::ivec2(0);
      for (size_t k = 0; k < component.size(); ++k) {
        const uint32_t q = component[k];
        for (const glm::ivec2 d :
             {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
          const int o = neighbour(q, d.x, d.y);
          if (o >= 0 && !cell.count(uint32_t(o)))
            cell[uint32_t(o)] = cell[q] + d, component.push_back(uint32_t(o));
        }
      }
      // Greedy rectangles in row order: extend along u, then add whole rows along v.
      std::map<std::pair<int, int>, uint32_t> at;  // (j, i) → quad
      for (uint32_t q : component) at[{cell[q].y, cell[q].x}] = q;
      auto free = [&](int i, int j) {
        const auto it = at.find({j, i});
        return it != at.end() && gridOf[it->second] < 0 ? int(it->second) : -1;
      };
      for (const auto& [ji, first] : at) {
        if (gridOf[first] >= 0) continue;
        const int i0 = ji.second, j0 = ji.first;
        int i1 = i0 + 1;
        while (i1 - i0 < maxQuads && free(i1, j0) >= 0) ++i1;
        int j1 = j0 + 1;
        auto rowFree = [&](int j) {
          for (int i = i0; i < i1; ++i)
            if (free(i, j) < 0) return false;
          return true;
        };
        while (j1 - j0 < maxQuads && rowFree(j1)) ++j1;
        QuadGrid g;
        g.size = {i1 - i0, j1 - j0};
        for (int j = j0; j < j1; ++j)
          for (int i = i0; i < i1; ++i) {
            const uint32_t q = at.at({j, i});
            gridOf[q] = int(grids.size());
            g.quads.push_back(q);
          }
        if (g.quads.size() == 1) {
          g.corners = quads.quads[first].corners;  // a lone quad keeps its own orientation
        } else {
          const Tile& t = tiles[first];
          const glm::vec3 u = float(g.size.x) * t.u, v = float(g.size.y) * t.v;
          g.corners = {t.origin, t.origin + u, t.origin + u + v, t.origin + v};
        }
        grids.push_back(std::move(g));
      }
    }
  }
  // Order by first quad, so the atlas's chart order follows the scene's order as before.
  std::stable_sort(grids.begin(), grids.end(),
                   [](const QuadGrid& a, const QuadGrid& b) { return a.quads.front() < b.quads.front(); });
  return grids;
}

}  // namespace cpgi
