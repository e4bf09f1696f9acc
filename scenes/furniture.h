// Furniture, rails and fittings as a modelling tool exports them: closed meshes of boxes and faceted
// cylinders in many small triangles, standing on the floor or touching the walls. The real house of
// issue 12 had 34k triangles, most of them in such pieces, and its bake is what a user judges; the
// procedural buildings' massing alone has ~2k. Y up, metres. Every call names the node its triangles go
// under, so a hand-made cell takes a piece with the room it stands in.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scenes/buildings.h"
#include "scenes/scene_builder.h"

namespace cpgi {

/// Which way a chair's seat or a sofa faces (the side a person sits towards).
enum class Facing { PlusX, MinusX, PlusZ, MinusZ };

class Furniture {
 public:
  /// Adds the furniture's materials (wood, fabric, metal, white, three book colours) to the scene.
  explicit Furniture(SceneBuilder& b);

  uint32_t wood() const { return wood_; }
  uint32_t fabric() const { return fabric_; }

  /// A closed box, its six faces cut into quads no larger than `maxCell` when > 0.
  void block(const Box3& box, uint32_t material, uint32_t node, float maxCell = 0.0f);
  /// A vertical cylinder of `segments` flat sides, capped at both ends.
  void column(glm::vec3 base, float radius, float height, int segments, uint32_t material, uint32_t node);

  /// A table on four round legs (round = one leg under a round top), its top at 0.75 m.
  void table(glm::vec3 centreOnFloor, glm::vec2 size, bool round, uint32_t node);
  /// A chair on four legs with a back on the side away from `facing`.
  void chair(glm::vec3 centreOnFloor, Facing facing, uint32_t node);
  /// A bed of `size` (x, z) with its head at the -x or +x end (`headAtMinusX`), mattress and pillows.
  void bed(glm::vec3 cornerOnFloor, glm::vec2 size, bool headAtMinusX, uint32_t node);
  /// A sofa of `size` (along, deep) whose seat faces `facing`, with arms and cushions.
  void sofa(glm::vec3 centreOnFloor, glm::vec2 size, Facing facing, uint32_t node);
  /// A shelf unit of `shelves` boards in the box `unit` (open towards -x, +x, -z or +z: `facing`), each
  /// board filled with books of varied sizes (deterministic from `seed`).
  void bookshelf(const Box3& unit, int shelves, Facing facing, uint32_t seed, uint32_t node);
  /// A run of base cabinets with a worktop and a round handle per door, doors facing `facing`.
  void cabinets(const Box3& run, int doors, Facing facing, uint32_t node);
  /// A balustrade along a path of points on a floor (axis-aligned legs): round spindles about every
  /// `spacing`, a rail on each leg.
  void balustrade(const std::vector<glm::vec3>& path, float height, float spacing, uint32_t node);
  /// A ceiling rose and a cord hanging `drop` metres from a point on the ceiling (the lamp's fitting).
  void pendant(glm::vec3 onCeiling, float drop, uint32_t node);

 private:
  SceneBuilder& b_;
  uint32_t wood_, fabric_, metal_, white_;
  std::array<uint32_t, 3> books_;
};

}  // namespace cpgi

namespace cpgi {

/// Furnishes the spiral-stair house of makeTwoStoreyHouse(true): furniture, bookshelves, a balustrade
/// round the stair hole, open door leaves, pendant fittings, sloping terrain round the house, and its
/// lights as KHR_lights_punctual point lights (one per room) and a spot over the dining table.
void furnishSpiralHouse(SceneBuilder& b, std::vector<PunctualLight>& lights);

}  // namespace cpgi
