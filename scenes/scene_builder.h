// A small helper for generating scenes out of axis-aligned rectangles, the way architecture is usually
// modelled: every rectangle becomes one quad (two triangles) or a grid of them, facing a chosen side.
#pragma once

#include <string>

#include "core/cell_graph.h"
#include "core/scene.h"

namespace cpgi {

/// One flat-shaded triangle: its corners in order, their normals all the winding's.
Triangle flatTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material, uint32_t node);

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

  /// The inside faces of a box room spanning [lo, hi] (y up), facing inwards, under node paths
  /// "NAME/floor", "NAME/wall-west", ... . Walls perpendicular to x get `door` cut out when asked.
  struct Door {
    float z0 = 1.5f, z1 = 2.5f, top = 2.1f;  ///< the opening in the x walls, metres
  };
  struct Room {
    std::string name;
    glm::vec3 lo{0.0f}, hi{1.0f};
    uint32_t floor = 0, ceiling = 0, south = 0, north = 0, west = 0, east = 0;  ///< materials
    bool doorWest = false, doorEast = false;
    Door door;
    float maxCell = 0.0f;  ///< > 0: cut every face into quads no larger than this
  };
  void room(const Room& r);

  /// The reveal of a door through a wall spanning x in [x0, x1] (sides, lintel soffit, threshold), cut at
  /// the wall's mid-plane: the half at x0 goes under node "WEST/door-WESTEAST", the other under EAST's.
  void doorReveal(float x0, float x1, const Door& door, const std::string& west, const std::string& east,
                  uint32_t wallMaterial, uint32_t floorMaterial);

  /// One quad from its origin and two edges; the normal is normalize(u × v).
  void quad(glm::vec3 origin, glm::vec3 u, glm::vec3 v, uint32_t material, uint32_t node);
  /// One flat triangle; its normal follows the winding a → b → c.
  void triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material, uint32_t node);

 private:
  Scene& scene_;
};

/// A 60° camera at `eye` looking at `target`, y up.
Camera lookAt(const std::string& name, glm::vec3 eye, glm::vec3 target);

/// The twelve triangles of the box [lo, hi], its faces outward, appended to `out`: a room given as a volume
/// (CellGraph's cell volume).
void appendBoxVolume(glm::vec3 lo, glm::vec3 hi, std::vector<Triangle>& out);

/// One cell per name; each triangle goes to the cell named by the first component of its node path
/// ("B/door-AB" belongs to B), the convention of every generated scene.
void cellsFromNodePaths(const Scene& scene, const std::vector<std::string>& names, CellGraph& cells);

}  // namespace cpgi
