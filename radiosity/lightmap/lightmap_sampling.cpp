#include "radiosity/lightmap/lightmap_sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>

namespace cpgi {

namespace {

// A triangle's nine coordinates as bits: positions written to a glb and read back are the same floats.
struct CornerKey {
  std::array<uint32_t, 9> bits{};
  bool operator==(const CornerKey&) const = default;
};

struct CornerKeyHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (uint32_t b : k.bits) h = (h ^ b) * 0x100000001B3ull;
    return size_t(h ^ (h >> 29));
  }
};

CornerKey keyOf(const Triangle& t) {
  CornerKey k;
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a) k.bits[size_t(3 * c + a)] = std::bit_cast<uint32_t>(t.p[c][a] + 0.0f);
  return k;
}

// Barycentric coordinates of `p` projected onto the plane of triangle `t`.
glm::dvec3 barycentric(const Triangle& t, const glm::vec3& p) {
  const glm::dvec3 a(t.p[0]), e1 = glm::dvec3(t.p[1]) - a, e2 = glm::dvec3(t.p[2]) - a, d = glm::dvec3(p) - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double denom = d11 * d22 - d12 * d12;
  if (!(denom > 0.0)) return glm::dvec3(1.0, 0.0, 0.0);
  const double v = (d22 * glm::dot(d, e1) - d12 * glm::dot(d, e2)) / denom;
  const double w = (d11 * glm::dot(d, e2) - d12 * glm::dot(d, e1)) / denom;
  return {1.0 - v - w, v, w};
}

// The point of triangle `t` nearest to `x` (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closestPointOnTriangle(const Triangle& t, const glm::dvec3& x) {
  const glm::dvec3 a(t.p[0]), b(t.p[1]), c(t.p[2]);
  const glm::dvec3 ab = b - a, ac = c - a, ap = x - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const glm::dvec3 bp = x - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = x - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return a;  // degenerate
  return a + ab * (vb / denom) + ac * (vc / denom);
}

// How far a piece's corner may lie off the triangle it was cut from: the cut's float rounding, far below a
// texel.
constexpr double kPieceTolerance = 1e-3;  // metres

bool liesOn(const Triangle& piece, const Triangle& whole) {
  if (glm::dot(piece.geometricNormal(), whole.geometricNormal()) < 0.99f) return false;
  for (const glm::vec3& corner : piece.p)
    if (glm::distance(closestPointOnTriangle(whole, glm::dvec3(corner)), glm::dvec3(corner)) >
        kPieceTolerance)
      return false;
  return true;
}

// A scene whose triangles `other` holds as they are (`source`) or cut into pieces, and `other`'s lightmap
// coordinates per triangle.
struct SplitSurface {
  const Scene& scene;
  std::span<const int32_t> source;
  const std::vector<std::vector<int32_t>>& pieces;
  const Scene& other;
  std::span<const std::array<glm::vec2, 3>> uvs;

  glm::vec2 at(int32_t k, const glm::dvec3& point) const {
    const glm::dvec3 w = barycentric(other.triangles[size_t(k)], glm::vec3(point));
    const std::array<glm::vec2, 3>& uv = uvs[size_t(k)];
    return glm::vec2(w.x * glm::dvec2(uv[0]) + w.y * glm::dvec2(uv[1]) + w.z * glm::dvec2(uv[2]));
  }

  // The lightmap coordinates of point `x` of a texel on scene triangle `whole` (the one of its quad that
  // holds it, holdingTriangle): x held onto that triangle (a border texel's centre lies off it), then read
  // through its match in `other`, else on the nearest of its pieces (which holds x unless a sliver of the
  // cut was dropped). None when that triangle has neither.
  std::optional<glm::vec2> coordinates(int32_t whole, glm::vec3 x) const {
    const glm::dvec3 onWhole = closestPointOnTriangle(scene.triangles[size_t(whole)], glm::dvec3(x));
    if (source[size_t(whole)] >= 0) return this->at(source[size_t(whole)], onWhole);
    int32_t best = -1;
    glm::dvec3 bestPoint(0.0);
    double bestGap = std::numeric_limits<double>::max();
    for (int32_t k : pieces[size_t(whole)]) {
      const glm::dvec3 onPiece = closestPointOnTriangle(other.triangles[size_t(k)], onWhole);
      const double gap = glm::distance(onPiece, onWhole);
      if (gap < bestGap) best = k, bestGap = gap, bestPoint = onPiece;
      if (gap == 0.0) break;
    }
    if (best < 0) return std::nullopt;
    return this->at(best, bestPoint);
  }
};

// The triangle of texel centre x's quad that holds it. texelTriangle names a quad's first triangle for
// every texel of its chart (the chart is affine over both), but a bake that cut one of the two on a portal's
// plane and not the other charts them apart: the first's coordinates carried past its edge then land
// outside its chart, on another surface's texels. So x is read through the nearer of the two.
int32_t holdingTriangle(const Scene& scene, const Patch& p, int32_t first, const glm::vec3& x) {
  const auto at = std::find(p.triangles.begin(), p.triangles.end(), first);
  const size_t index = size_t(at - p.triangles.begin());
  if (p.quad < 0 || index % 2 != 0 || index + 1 >= p.triangles.size()) return first;
  const int32_t second = p.triangles[index + 1];
  const auto gap = [&](int32_t k) {
    return glm::distance(closestPointOnTriangle(scene.triangles[size_t(k)], glm::dvec3(x)), glm::dvec3(x));
  };
  return gap(second) < gap(first) ? second : first;
}

// Calls f(texel, the triangle of `scene` that holds its centre) for every valid texel of `atlas`, or -1
// for a texel whose chart names none.
template <class F>
void forEachTexelTriangle(const LightmapAtlas& atlas, const Scene& scene, F&& f) {
  for (int y = 0; y < atlas.height; ++y)
    for (int x = 0; x < atlas.width; ++x) {
      const size_t t = size_t(y) * size_t(atlas.width) + size_t(x);
      if (atlas.patch[t] < 0) continue;
      const Patch& p = atlas.patches[size_t(atlas.patch[t])];
      const int32_t first = texelTriangle(p, x - p.x, y - p.y);
      f(t, first >= 0 ? holdingTriangle(scene, p, first, atlas.position[t]) : first);
    }
}

}  // namespace

glm::vec3 sampleBilinear(int width, int height, std::span<const glm::vec3> lightmap, glm::vec2 uv) {
  const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  auto at = [&](int i, int j) {
    i = std::clamp(i, 0, width - 1);
    j = std::clamp(j, 0, height - 1);
    return lightmap[size_t(j) * size_t(width) + size_t(i)];
  };
  const int i = int(fx), j = int(fy);
  return (1.0f - ty) * ((1.0f - tx) * at(i, j) + tx * at(i + 1, j)) +
         ty * ((1.0f - tx) * at(i, j + 1) + tx * at(i + 1, j + 1));
}

std::vector<int32_t> matchTriangles(const Scene& scene, const Scene& other) {
  std::unordered_map<CornerKey, int32_t, CornerKeyHash> index;
  index.reserve(other.triangles.size());
  for (size_t i = 0; i < other.triangles.size(); ++i) index.emplace(keyOf(other.triangles[i]), int32_t(i));
  std::vector<int32_t> match(scene.triangles.size(), -1);
  for (size_t i = 0; i < scene.triangles.size(); ++i)
    if (auto it = index.find(keyOf(scene.triangles[i])); it != index.end()) match[i] = it->second;
  return match;
}

std::vector<std::vector<int32_t>> matchSplitPieces(const Scene& scene, const Scene& other,
                                                   std::span<const int32_t> source) {
  if (source.size() != scene.triangles.size())
    throw std::invalid_argument("matchSplitPieces: not one source entry per scene triangle");
  std::vector<char> matched(other.triangles.size(), 0);
  for (int32_t s : source)
    if (s >= 0 && size_t(s) < matched.size()) matched[size_t(s)] = 1;
  std::vector<int32_t> loose;
  for (size_t i = 0; i < matched.size(); ++i)
    if (!matched[i]) loose.push_back(int32_t(i));
  std::vector<std::vector<int32_t>> pieces(scene.triangles.size());
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    if (source[t] >= 0 || loose.empty()) continue;
    const Triangle& whole = scene.triangles[t];
    const glm::vec3 lo = glm::min(glm::min(whole.p[0], whole.p[1]), whole.p[2]) - float(kPieceTolerance),
                    hi = glm::max(glm::max(whole.p[0], whole.p[1]), whole.p[2]) + float(kPieceTolerance);
    for (int32_t k : loose) {
      const Triangle& piece = other.triangles[size_t(k)];
      const glm::vec3 c = piece.centroid();
      if (glm::any(glm::lessThan(c, lo)) || glm::any(glm::greaterThan(c, hi))) continue;
      if (liesOn(piece, whole)) pieces[t].push_back(k);
    }
  }
  return pieces;
}

size_t sampleOnSplitPieces(const LightmapAtlas& atlas, const Scene& scene, std::span<const int32_t> source,
                           const std::vector<std::vector<int32_t>>& pieces, const Scene& other,
                           std::span<const std::array<glm::vec2, 3>> uvs, int width, int height,
                           std::span<const glm::vec3> lightmap, std::vector<glm::vec3>& out,
                           std::vector<char>& unread) {
  if (source.size() != scene.triangles.size() || pieces.size() != scene.triangles.size())
    throw std::invalid_argument("sampleOnSplitPieces: not one source and piece entry per scene triangle");
  if (uvs.size() != other.triangles.size() || out.size() != atlas.texelCount())
    throw std::invalid_argument("sampleOnSplitPieces: not one lightmap entry per piece, or per texel");
  if (width <= 0 || height <= 0 || lightmap.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("sampleOnSplitPieces: the lightmap is not width × height texels");
  const SplitSurface surface{scene, source, pieces, other, uvs};
  unread.assign(atlas.texelCount(), 0);
  size_t unreadCount = 0;
  forEachTexelTriangle(atlas, scene, [&](size_t t, int32_t triangle) {
    if (triangle >= 0 && source[size_t(triangle)] >= 0) return;
    const std::optional<glm::vec2> at =
        triangle >= 0 ? surface.coordinates(triangle, atlas.position[t]) : std::nullopt;
    if (at) out[t] = sampleBilinear(width, height, lightmap, *at);
    unread[t] = !at;
    unreadCount += !at;
  });
  return unreadCount;
}

std::vector<glm::vec3> sampleAtTexels(const LightmapAtlas& atlas, const Scene& scene,
                                      std::span<const int32_t> source,
                                      std::span<const std::array<glm::vec2, 3>> uvs, int width, int height,
                                      std::span<const glm::vec3> lightmap, size_t* missing) {
  if (source.size() != scene.triangles.size())
    throw std::invalid_argument("sampleAtTexels: not one source entry per scene triangle");
  if (width <= 0 || height <= 0 || lightmap.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("sampleAtTexels: the lightmap is not width × height texels");
  std::vector<glm::vec3> out(atlas.texelCount(), glm::vec3(0.0f));
  size_t unmatched = 0;
  forEachTexelTriangle(atlas, scene, [&](size_t t, int32_t triangle) {
    const int32_t from = triangle >= 0 ? source[size_t(triangle)] : -1;
    if (from < 0 || size_t(from) >= uvs.size()) {
      ++unmatched;
      return;
    }
    const glm::dvec3 w = barycentric(scene.triangles[size_t(triangle)], atlas.position[t]);
    const std::array<glm::vec2, 3>& uv = uvs[size_t(from)];
    const glm::vec2 at(w.x * glm::dvec2(uv[0]) + w.y * glm::dvec2(uv[1]) + w.z * glm::dvec2(uv[2]));
    out[t] = sampleBilinear(width, height, lightmap, at);
  });
  if (missing) *missing = unmatched;
  return out;
}

}  // namespace cpgi
