#include "radiosity/gpu/item_mesh.h"
#include <cstring>
#include <glm/geometric.hpp>
#include <unordered_map>

namespace cpgi {
namespace {

// A vertex as the item buffer's vertex shader sees it, compared bit for bit: two corners merge only when
// the shader would compute the same thing for both.
struct VertexKey {
  float bits[7];
  bool operator==(const VertexKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint32_t words[7];
    std::memcpy(words, k.bits, sizeof words);
    uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
    for (uint32_t w : words) h = (h ^ w) * 1099511628211ull;
    return size_t(h);
  }
};

}  // namespace

ItemMesh buildItemMesh(const Scene& scene, const LightmapAtlas& atlas) {
  // Patch ID per triangle; triangles outside the atlas occlude as -2 (never a receiver's ID).
  std::vector<int32_t> patchOf(scene.triangles.size(), -2);
  for (size_t i = 0; i < atlas.patches.size(); ++i)
    for (int32_t t : atlas.patches[i].triangles)
      if (t >= 0) patchOf[size_t(t)] = int32_t(i);
  ItemMesh mesh;
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index;
  index.reserve(scene.triangles.size() * 2);
  mesh.indices.reserve(scene.triangles.size() * 3);
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    const Triangle& tri = scene.triangles[t];
    if (!(tri.area() > 0.0f)) continue;
    // The side a receiver is on: its patch's normal (what receive.comp and shot_coverage.comp test).
    const glm::vec3 n = patchOf[t] >= 0
                            ? atlas.patches[size_t(patchOf[t])].normal
                            : glm::normalize(glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]));
    for (const glm::vec3& q : tri.p) {
      VertexKey key{{q.x, q.y, q.z, n.x, n.y, n.z, 0.0f}};
      std::memcpy(&key.bits[6], &patchOf[t], 4);
      const auto [it, added] = index.try_emplace(key, uint32_t(mesh.positions.size()));
      if (added) {
        mesh.positions.push_back(q);
        mesh.normals.push_back(n);
        mesh.patches.push_back(patchOf[t]);
      }
      mesh.indices.push_back(it->second);
    }
  }
  return mesh;
}

}  // namespace cpgi
