// A box open to the sky for the sky tests (core/sky.h): [0, 2]³ with inward faces, its ceiling (y = 2)
// pierced by a 1 m × 1 m hole over the floor's centre; the floor grey, everything else black by default, so
// that (with black walls) the floor's light is the sky seen through the hole, π Lz F(point → hole) under a
// uniform sky.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi::testing {

/// The hole's corners, in order (for pointToPolygonFormFactor).
inline std::array<glm::dvec3, 4> skyHole() {
  return {glm::dvec3(0.5, 2, 0.5), glm::dvec3(1.5, 2, 0.5), glm::dvec3(1.5, 2, 1.5), glm::dvec3(0.5, 2, 1.5)};
}

/// Triangles 0–1 are the floor (albedo `floorAlbedo`), the rest of albedo `wallAlbedo`.
inline Scene boxOpenToTheSky(float floorAlbedo, float wallAlbedo = 0.0f) {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(floorAlbedo)), black = addMaterial(s, glm::vec3(wallAlbedo));
  addRect(s, {0, 0, 0}, {0, 0, 2}, {2, 0, 0}, grey);   // floor, normal +y
  addRect(s, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, black);  // z = 0
  addRect(s, {0, 0, 2}, {0, 2, 0}, {2, 0, 0}, black);  // z = 2
  addRect(s, {0, 0, 0}, {0, 2, 0}, {0, 0, 2}, black);  // x = 0
  addRect(s, {2, 0, 0}, {0, 0, 2}, {0, 2, 0}, black);  // x = 2
  // The ceiling, normal −y, as four strips around the hole.
  addRect(s, {0, 2, 0}, {2, 0, 0}, {0, 0, 0.5f}, black);
  addRect(s, {0, 2, 1.5f}, {2, 0, 0}, {0, 0, 0.5f}, black);
  addRect(s, {0, 2, 0.5f}, {0.5f, 0, 0}, {0, 0, 1}, black);
  addRect(s, {1.5f, 2, 0.5f}, {0.5f, 0, 0}, {0, 0, 1}, black);
  return s;
}

/// boxOpenToTheSky's floor and walls without the ceiling (a court), each in `tiles` × `tiles` squares of a
/// material of their own (a patch each): a game map's many small sky-lit patches.
inline Scene tiledCourt(int tiles, float albedo) {
  const Scene box = boxOpenToTheSky(albedo, albedo);
  Scene court;
  for (size_t k = 0; k < 10; k += 2) {
    const Triangle& t = box.triangles[k];
    const glm::vec3 o = t.p[0], u = (t.p[1] - t.p[0]) / float(tiles), v = (t.p[2] - t.p[1]) / float(tiles);
    for (int i = 0; i < tiles; ++i)
      for (int j = 0; j < tiles; ++j)
        addRect(court, o + float(i) * u + float(j) * v, u, v, addMaterial(court, glm::vec3(albedo)));
  }
  return court;
}

}  // namespace cpgi::testing
