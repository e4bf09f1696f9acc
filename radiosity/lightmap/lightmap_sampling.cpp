#include "radiosity/lightmap/lightmap_sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
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
  for (int y = 0; y < atlas.height; ++y)
    for (int x = 0; x < atlas.width; ++x) {
      const size_t t = size_t(y) * size_t(atlas.width) + size_t(x);
      if (atlas.patch[t] < 0) continue;
      const Patch& p = atlas.patches[size_t(atlas.patch[t])];
      // A quad's chart is affine over both of its triangles, so the first one's coordinates extend to
      // texel centres in the second.
      const int32_t triangle = texelTriangle(p, x - p.x, y - p.y);
      const int32_t from = triangle >= 0 ? source[size_t(triangle)] : -1;
      if (from < 0 || size_t(from) >= uvs.size()) {
        ++unmatched;
        continue;
      }
      const glm::dvec3 w = barycentric(scene.triangles[size_t(triangle)], atlas.position[t]);
      const std::array<glm::vec2, 3>& uv = uvs[size_t(from)];
      const glm::vec2 at(w.x * glm::dvec2(uv[0]) + w.y * glm::dvec2(uv[1]) + w.z * glm::dvec2(uv[2]));
      out[t] = sampleBilinear(width, height, lightmap, at);
    }
  if (missing) *missing = unmatched;
  return out;
}

}  // namespace cpgi
