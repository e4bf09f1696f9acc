// A small helper for generating scenes out of axis-aligned rectangles, the way architecture is usually
// modelled: every rectangle becomes one quad (two triangles) or a grid of them, facing a chosen side.
#pragma once

#include <string>

#include "core/scene.h"

namespace cpgi {

class SceneBuilder {
 public:
  explicit SceneBuilder(Scene& scene) : scene_(scene) {}

  uint32_t material(const std::string& name, glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f));
  uint32_t node(const std::string& path);

  /// A rectangle perpendicular to `axis` (0 = x, 1 = y, 2 = z) at coordinate `at`, spanning [lo, hi] on
  /// the two other axes (in cyclic order axis+1, axis+2), facing +axis when `sign` > 0 and -axis otherwise.
  /// When `maxCell` > 0 it is cut into a grid of quads no larger than maxCell on either side.
  /// Returns the index of its first triangle; it adds 2 triangles per quad.
  uint32_t rect(int axis, float at, float sign, glm::vec2 lo, glm::vec2 hi, uint32_t material, uint32_t node,
                float maxCell = 0.0f);

  /// The five visible faces of an axis-aligned box standing on y = lo.y (its bottom is hidden).
  void boxOnFloor(glm::vec3 lo, glm::vec3 hi, uint32_t material, uint32_t node);

  /// One quad from its origin and two edges; the normal is normalize(u × v).
  void quad(glm::vec3 origin, glm::vec3 u, glm::vec3 v, uint32_t material, uint32_t node);

 private:
  Scene& scene_;
};

}  // namespace cpgi
