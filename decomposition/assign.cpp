#include "decomposition/assign.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <map>
#include <unordered_map>

namespace cpgi::decomp {
namespace {

// Per voxel, the nearest labelled voxel's cell (breadth-first over face neighbours), for triangles that
// see no cell from either side and have none nearby. The grid's border layer is left out (it is padding),
// so the search runs on linear indices without bounds checks.
std::vector<int32_t> nearestCells(const GridFrame& f, const std::vector<int32_t>& cell) {
  std::vector<int32_t> near = cell;
  std::vector<char> border(f.count(), 0);
  for (int z = 0; z < f.dims.z; ++z)
    for (int y = 0; y < f.dims.y; ++y) {
      const bool wholeRow = z == 0 || y == 0 || z == f.dims.z - 1 || y == f.dims.y - 1;
      for (int x = 0; x < f.dims.x; x += (wholeRow ? 1 : std::max(1, f.dims.x - 1)))
        border[f.index(x, y, z)] = 1;
    }
  const ptrdiff_t sy = f.dims.x, sz = ptrdiff_t(f.dims.x) * f.dims.y;
  const ptrdiff_t offsets[6] = {-1, 1, -sy, sy, -sz, sz};
  std::vector<size_t> queue;
  for (size_t i = 0; i < near.size(); ++i)
    if (near[i] >= 0 && !border[i]) queue.push_back(i);
  for (size_t head = 0; head < queue.size(); ++head) {
    const size_t i = queue[head];
    for (ptrdiff_t o : offsets) {
      const size_t j = size_t(ptrdiff_t(i) + o);
      if (near[j] >= 0 || border[j]) continue;
      near[j] = near[i];
      queue.push_back(j);
    }
  }
  return near;
}

// The scene's triangles and the portals' quads in the buckets of a hash grid, for segments short against
// the scene: does a step from a surface pass through another surface, or into another cell?
class SurfaceIndex {
 public:
  SurfaceIndex(const Scene& scene, const std::vector<PortalQuad>& portals, float bucket)
      : scene_(scene), bucket_(bucket) {
    for (const PortalQuad& q : portals) {
      Triangle a, b;
      a.p = {q.corners[0], q.corners[1], q.corners[2]};
      b.p = {q.corners[0], q.corners[2], q.corners[3]};
      portalTriangles_.push_back(a), portalTriangles_.push_back(b);
    }
    for (size_t t = 0; t < scene.triangles.size() + portalTriangles_.size(); ++t) {
      const Triangle& tri = triangle(uint32_t(t));
      const glm::ivec3 lo = cellOf(glm::min(glm::min(tri.p[0], tri.p[1]), tri.p[2]));
      const glm::ivec3 hi = cellOf(glm::max(glm::max(tri.p[0], tri.p[1]), tri.p[2]));
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) buckets_[key({x, y, z})].push_back(uint32_t(t));
    }
  }

  /// True when the segment a→b passes through a triangle of the scene or a portal (Möller–Trumbore), a
  /// itself left out: a lies on the surface the step starts from, and on any face coincident with it.
  bool blocks(const glm::vec3& a, const glm::vec3& b) const {
    const glm::ivec3 lo = cellOf(glm::min(a, b)), hi = cellOf(glm::max(a, b));
    const glm::vec3 d = b - a;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const auto it = buckets_.find(key({x, y, z}));
          if (it == buckets_.end()) continue;
          for (uint32_t t : it->second)
            if (crosses(triangle(t), a, d)) return true;
        }
    return false;
  }

 private:
  const Triangle& triangle(uint32_t t) const {
    return t < scene_.triangles.size() ? scene_.triangles[t] : portalTriangles_[t - scene_.triangles.size()];
  }
  glm::ivec3 cellOf(const glm::vec3& p) const { return glm::ivec3(glm::floor(p / bucket_)); }
  static uint64_t key(const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) |
           uint64_t(uint32_t(c.z) & 0x1FFFFF);
  }
  // The segment a + s·d, s in (1e-4, 1], through triangle t.
  static bool crosses(const Triangle& t, const glm::vec3& a, const glm::vec3& d) {
    const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
    const glm::vec3 q = glm::cross(d, e2);
    const float det = glm::dot(e1, q);
    if (std::abs(det) < 1e-12f) return false;  // parallel to the triangle, or the triangle degenerate
    const glm::vec3 o = a - t.p[0];
    const float u = glm::dot(o, q) / det;
    if (u < 0.0f || u > 1.0f) return false;
    const glm::vec3 r = glm::cross(o, e1);
    const float v = glm::dot(d, r) / det;
    if (v < 0.0f || u + v > 1.0f) return false;
    const float s = glm::dot(e2, r) / det;
    return s > 1e-4f && s <= 1.0f;
  }

  const Scene& scene_;
  std::vector<Triangle> portalTriangles_;
  float bucket_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> buckets_;
};

// The cell in front of p, a point strictly inside a piece facing dir: the first labelled voxel stepping
// along dir whose centre p sees, else the nearest labelled voxel centre in front of p within 3 voxels that
// p sees; -1 when none. A voxel holds its centre's label: one that straddles a wall meeting this face (the
// corner of two zero-thickness walls) holds the room beyond that wall, and a step into it passes through
// the wall; one beyond a portal's plane holds the cell on its far side (a door's threshold cut at the
// portal, its voxels straddling the cut). A step past the grid is in `outsideCell`.
int cellInFront(const GridFrame& f, const std::vector<int32_t>& cell, int outsideCell,
                const SurfaceIndex& surfaces, const glm::vec3& p, const glm::vec3& dir) {
  const float h = float(f.voxel);
  auto seenLabel = [&](const glm::ivec3& v) {
    if (!f.contains(v)) return outsideCell;
    return cell[f.index(v)] >= 0 && !surfaces.blocks(p, f.centre(v)) ? cell[f.index(v)] : -1;
  };
  for (float step : {1.0f, 1.5f, 2.0f, 3.0f})
    if (const int l = seenLabel(f.voxelOf(p + step * h * dir)); l >= 0) return l;
  std::vector<std::pair<float, glm::ivec3>> ahead;
  const glm::ivec3 c = f.voxelOf(p);
  for (int dz = -3; dz <= 3; ++dz)
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx) {
        const glm::ivec3 v = c + glm::ivec3(dx, dy, dz);
        const glm::vec3 offset = f.centre(v) - p;
        if (f.contains(v) && cell[f.index(v)] >= 0 && glm::dot(offset, dir) > 0.25f * h)
          ahead.push_back({glm::dot(offset, offset), v});
      }
  std::sort(ahead.begin(), ahead.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (const auto& [d2, v] : ahead)
    if (const int l = seenLabel(v); l >= 0) return l;
  return -1;
}

struct Piece {
  Triangle tri;
  uint32_t source;
  int depth;
};

// Splits t by the plane (c, n) into pieces on either side, keeping the winding and interpolating normals.
std::vector<Triangle> splitByPlane(const Triangle& t, const glm::vec3& c, const glm::vec3& n) {
  std::array<float, 3> s{};
  for (int i = 0; i < 3; ++i) s[size_t(i)] = glm::dot(t.p[size_t(i)] - c, n);
  // The vertex alone on its side.
  int lone = -1;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if ((s[size_t(i)] > 0) != (s[size_t(j)] > 0) && (s[size_t(j)] > 0) == (s[size_t(k)] > 0)) lone = i;
  }
  if (lone < 0) return {t};
  const int j = (lone + 1) % 3, k = (lone + 2) % 3;
  auto cut = [&](int a, int b, glm::vec3& p, glm::vec3& nn) {
    const float w = s[size_t(a)] / (s[size_t(a)] - s[size_t(b)]);
    p = glm::mix(t.p[size_t(a)], t.p[size_t(b)], w);
    nn = glm::mix(t.n[size_t(a)], t.n[size_t(b)], w);
    const float len = glm::length(nn);
    nn = len > 0.0f ? nn / len : t.n[size_t(a)];
  };
  glm::vec3 pj, nj, pk, nk;
  cut(lone, j, pj, nj);
  cut(lone, k, pk, nk);
  Triangle a = t, b = t, d = t;
  a.p = {t.p[size_t(lone)], pj, pk}, a.n = {t.n[size_t(lone)], nj, nk};
  b.p = {pj, t.p[size_t(j)], t.p[size_t(k)]}, b.n = {nj, t.n[size_t(j)], t.n[size_t(k)]};
  d.p = {pj, t.p[size_t(k)], pk}, d.n = {nj, t.n[size_t(k)], nk};
  std::vector<Triangle> out;
  for (const Triangle& q : {a, b, d})
    if (q.area() > 0.0f) out.push_back(q);
  return out;
}

// The cell with the most votes (the first of equals, in cell order).
int mostVoted(const std::map<int, double>& votes) {
  int best = -1;
  double bestVotes = -1.0;
  for (const auto& [c, w] : votes)
    if (w > bestVotes) best = c, bestVotes = w;
  return best;
}

// The first portal between two voted cells whose plane `tri` crosses, or null.
const PortalQuad* crossedPortal(const Triangle& tri, const std::map<int, double>& votes,
                                const std::vector<PortalQuad>& portals) {
  for (const PortalQuad& p : portals) {
    if (!votes.count(p.cellA) || !votes.count(p.cellB)) continue;
    const glm::vec3 c = p.centre();
    float lo = 0.0f, hi = 0.0f;
    for (const glm::vec3& q : tri.p)
      lo = std::min(lo, glm::dot(q - c, p.normal)), hi = std::max(hi, glm::dot(q - c, p.normal));
    if (lo < -1e-4f && hi > 1e-4f) return &p;
  }
  return nullptr;
}

}  // namespace

Assignment assignTriangles(const Scene& scene, const GridFrame& f, const std::vector<int32_t>& cell,
                           const std::vector<PortalQuad>& portals, int outsideCell,
                           const AssignParams& params, Context& ctx) {
  auto timer = ctx.time("assign");
  Assignment out;
  out.scene.materials = scene.materials;
  out.scene.nodePaths = scene.nodePaths;
  out.scene.cameras = scene.cameras;
  // The nearest-cell grid costs a pass over every voxel; most scenes never need it.
  std::vector<int32_t> near;
  int farSearches = 0;
  const float h = float(f.voxel);

  auto labelAt = [&](const glm::vec3& p) -> int {
    const glm::ivec3 v = f.voxelOf(p);
    return f.contains(v) ? cell[f.index(v)] : outsideCell;
  };
  auto nearestAt = [&](const glm::vec3& p) -> int {
    const glm::ivec3 v = glm::clamp(f.voxelOf(p), glm::ivec3(0), f.dims - 1);
    // First shell by shell (cubes of growing radius), the nearest of the first shell that holds a
    // labelled voxel (approximately the nearest overall): up to 40 voxels for the first 64 such
    // searches, after which the grid of nearest cells pays off.
    int best = -1, bestD = INT32_MAX;
    const int radius = near.empty() && farSearches < 64 ? 40 : 12;
    for (int r = 0; r <= radius && best < 0; ++r) {
      if (r == 13) ++farSearches;
      for (int dz = -r; dz <= r; ++dz)
        for (int dy = -r; dy <= r; ++dy)
          for (int dx = -r; dx <= r; ++dx) {
            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;
            const glm::ivec3 q = v + glm::ivec3(dx, dy, dz);
            const int d2 = dx * dx + dy * dy + dz * dz;
            if (d2 >= bestD || !f.contains(q)) continue;
            const int l = cell[f.index(q)];
            if (l >= 0) best = l, bestD = d2;
          }
    }
    if (best >= 0) return best;
    const glm::ivec3 inner = glm::clamp(v, glm::ivec3(1), glm::max(f.dims - 2, glm::ivec3(1)));
    if (near.empty()) {
      auto t = ctx.time("assign.nearest");
      near = nearestCells(f, cell);
    }
    return near[f.index(inner)];
  };
  const SurfaceIndex surfaces(scene, portals, 8.0f * h);
  auto faced = [&](const glm::vec3& p, const glm::vec3& dir) {
    return cellInFront(f, cell, outsideCell, surfaces, p, dir);
  };

  // Behind a face that sees no cell (an outside wall, the underside of the ground floor): through the
  // wall to the room it bounds, up to backSearch metres.
  const int backSteps = std::max(3, int(std::ceil(params.backSearch / h)));
  auto throughWall = [&](const glm::vec3& p, const glm::vec3& dir) -> int {
    for (int step = 1; step <= backSteps; ++step) {
      const int l = labelAt(p + float(step) * h * dir);
      if (l >= 0) return l;
    }
    return -1;
  };

  std::vector<Piece> work;
  for (size_t t = scene.triangles.size(); t-- > 0;) work.push_back({scene.triangles[t], uint32_t(t), 0});
  std::vector<char> wasSplit(scene.triangles.size(), 0);
  while (!work.empty()) {
    const Piece piece = work.back();
    work.pop_back();
    const Triangle& tri = piece.tri;
    const glm::vec3 n = tri.geometricNormal();
    std::map<int, double> votes;
    bool fellBack = false;
    if (n == glm::vec3(0.0f)) {
      votes[nearestAt(tri.centroid())] = 1.0;
    } else {
      float longest = 0.0f;
      for (int i = 0; i < 3; ++i)
        longest = std::max(longest, glm::length(tri.p[size_t(i)] - tri.p[size_t((i + 1) % 3)]));
      const int k = std::clamp(int(std::ceil(longest / (float(params.sampleSpacing) * h))), 1,
                               params.maxSamplesPerEdge);
      const float pieceArea = tri.area() / float(k * k);
      // Centroids of the k² sub-triangles of the regular subdivision, in barycentric steps of 1/k.
      for (int a = 0; a < k; ++a)
        for (int b = 0; a + b < k; ++b)
          for (int up = 0; up < 2; ++up) {
            if (up && a + b + 1 >= k) continue;
            const float ba = (a + (up ? 2.0f : 1.0f) / 3.0f) / float(k);
            const float bb = (b + (up ? 2.0f : 1.0f) / 3.0f) / float(k);
            const glm::vec3 p = tri.p[0] + ba * (tri.p[1] - tri.p[0]) + bb * (tri.p[2] - tri.p[0]);
            int front = faced(p, n);
            const int back = labelAt(p - h * n);
            if (front >= 0 && back >= 0 && back != front) out.thinWallArea += pieceArea;
            if (front < 0) front = throughWall(p, -n);
            if (front >= 0) votes[front] += 1.0;  // a sample that sees no cell does not vote
          }
      if (votes.empty()) votes[nearestAt(tri.centroid())] = 1.0, fellBack = true;
    }
    // Two cells seen: split on the plane of a portal between them that the triangle crosses.
    const int best = mostVoted(votes);
    if (votes.size() > 1 && piece.depth < params.maxSplitDepth) {
      if (const PortalQuad* splitter = crossedPortal(tri, votes, portals)) {
        const std::vector<Triangle> parts = splitByPlane(tri, splitter->centre(), splitter->normal);
        if (parts.size() > 1) {
          wasSplit[piece.source] = 1;
          for (size_t q = parts.size(); q-- > 0;) work.push_back({parts[q], piece.source, piece.depth + 1});
          continue;
        }
      }
    }
    out.fallbackTriangles += fellBack;
    out.scene.triangles.push_back(tri);
    out.cellOfTriangle.push_back(best);
    out.sourceTriangle.push_back(piece.source);
  }
  for (char s : wasSplit) out.splitTriangles += s;
  ctx.progress("assign", 1.0);
  return out;
}

}  // namespace cpgi::decomp
