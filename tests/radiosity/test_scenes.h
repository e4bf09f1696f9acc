// Small scenes built in code for the radiosity tests: rectangles as two triangles that findQuads pairs,
// closed boxes, single triangles.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "scenes/scene_builder.h"

namespace cpgi::testing {

inline uint32_t addMaterial(Scene& scene, glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f)) {
  scene.materials.push_back({"m" + std::to_string(scene.materials.size()), albedo, emission});
  return uint32_t(scene.materials.size() - 1);
}

inline void addTriangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material,
                        uint32_t node = 0) {
  scene.triangles.push_back(flatTriangle(a, b, c, material, node));
  if (scene.nodePaths.size() <= node) scene.nodePaths.resize(node + 1, "node");
}

/// The rectangle origin, origin+u, origin+u+v, origin+v; its normal is u × v.
inline void addRect(Scene& scene, glm::vec3 origin, glm::vec3 u, glm::vec3 v, uint32_t material,
                    uint32_t node = 0) {
  const glm::vec3 c0 = origin, c1 = origin + u, c2 = origin + u + v, c3 = origin + v;
  addTriangle(scene, c0, c1, c2, material, node);
  addTriangle(scene, c0, c2, c3, material, node);
}

// A copy of the scene's first triangle with two corners at one point: zero area, which no atlas charts
// (faces cut where other geometry runs through them leave such triangles: oa_dm2 had two).
inline void addZeroAreaTriangle(Scene& scene) {
  Triangle flat = scene.triangles.front();
  flat.p[2] = flat.p[1];
  scene.triangles.push_back(flat);
}

/// The atlas of `scene` at `density` texels a metre, every other parameter the default.
inline LightmapAtlas atlasAtDensity(const Scene& scene, float density) {
  Context ctx;
  AtlasParams p;
  p.density = density;
  return buildAtlas(scene, findQuads(scene), p, ctx);
}

/// The six inward-facing faces of the box [lo, hi].
inline void addClosedBox(Scene& scene, glm::vec3 lo, glm::vec3 hi, uint32_t material) {
  const glm::vec3 d = hi - lo;
  const glm::vec3 X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
  addRect(scene, lo, X, Y, material);      // z = lo, normal +z
  addRect(scene, lo + Z, Y, X, material);  // z = hi, normal -z
  addRect(scene, lo, Y, Z, material);      // x = lo, normal +x
  addRect(scene, lo + X, Z, Y, material);  // x = hi, normal -x
  addRect(scene, lo, Z, X, material);      // y = lo, normal +y
  addRect(scene, lo + Y, X, Z, material);  // y = hi, normal -y
}

/// Two 3 × 3 × 2.5 m rooms along x (z up), joined by a 1 × 2 m door in a zero-thickness partition at
/// x = 3; a 0.6 m lamp 1 cm under the first room's ceiling. The second room is lit only through the door.
inline Scene twoRoomsThroughADoor() {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.6f));
  const uint32_t lamp = addMaterial(s, glm::vec3(0.0f), glm::vec3(50.0f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(6.0f, 3.0f, 2.5f), grey);
  // The partition's pieces round the door (y 1..2, z 0..2), each with a face into either room.
  auto piece = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v) {
    addRect(s, o, v, u, grey);  // faces −x
    addRect(s, o, u, v, grey);  // faces +x
  };
  piece({3, 0, 0}, {0, 1, 0}, {0, 0, 2.5f});
  piece({3, 2, 0}, {0, 1, 0}, {0, 0, 2.5f});
  piece({3, 1, 2}, {0, 1, 0}, {0, 0, 0.5f});
  addRect(s, {1.2f, 1.2f, 2.49f}, {0, 0.6f, 0}, {0.6f, 0, 0}, lamp);
  return s;
}

/// Calls visit(t) for every atlas texel t of the patch that holds triangle `triangle`.
template <typename Visit>
void forEachTexelOf(const LightmapAtlas& atlas, int triangle, Visit visit) {
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    const int p = atlas.patch[t];
    if (p < 0) continue;
    const std::vector<int32_t>& tris = atlas.patches[p].triangles;
    if (std::find(tris.begin(), tris.end(), triangle) != tris.end()) visit(t);
  }
}

}  // namespace cpgi::testing
