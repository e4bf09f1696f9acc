#include "scenes/contact_scenes.h"

#include <string>

#include "scenes/scene_builder.h"

namespace cpgi {

namespace {

// The faces of box [lo, hi] named by `faces` (BoxFaces bits), each facing out of the box when `outward`,
// into it otherwise.
void box(SceneBuilder& b, glm::vec3 lo, glm::vec3 hi, unsigned faces, bool outward, uint32_t material,
         uint32_t node) {
  const float out = outward ? 1.0f : -1.0f;
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const glm::vec2 l(lo[a1], lo[a2]), h(hi[a1], hi[a2]);
    if (faces & (1u << (2 * axis))) b.rect(axis, lo[axis], -out, l, h, material, node);
    if (faces & (2u << (2 * axis))) b.rect(axis, hi[axis], out, l, h, material, node);
  }
}

// The rectangle [lo, hi] (on the axes after `axis`) with the hole [holeLo, holeHi] cut out, as four.
void rectWithHole(SceneBuilder& b, int axis, float at, float sign, glm::vec2 lo, glm::vec2 hi,
                  glm::vec2 holeLo, glm::vec2 holeHi, uint32_t material, uint32_t node) {
  b.rect(axis, at, sign, lo, {holeLo.x, hi.y}, material, node);
  b.rect(axis, at, sign, {holeHi.x, lo.y}, hi, material, node);
  b.rect(axis, at, sign, {holeLo.x, lo.y}, {holeHi.x, holeLo.y}, material, node);
  b.rect(axis, at, sign, {holeLo.x, holeHi.y}, {holeHi.x, hi.y}, material, node);
}

}  // namespace

SeedScene makePaneRoom(bool throughPane) {
  constexpr float kWall = 0.2f, kPaneLo = 4.09f, kPaneHi = 4.11f;
  const glm::vec3 room(4.0f, 3.0f, 4.0f);
  const glm::vec2 holeLo(1.5f, 1.0f), holeHi(2.5f, 2.0f);  // x, y
  SeedScene s;
  SceneBuilder b(s.scene);
  const uint32_t wall = b.material("wall", glm::vec3(0.7f)), glass = b.material("pane", glm::vec3(0.5f));
  const uint32_t inside = b.node("room/walls"), outside = b.node("outside/walls");
  // The room's faces inward; its north wall (z = 4) pierced.
  box(b, glm::vec3(0.0f), room, BoxFaces::kAll & ~32u, false, wall, inside);
  rectWithHole(b, 2, room.z, -1, {0, 0}, {room.x, room.y}, holeLo, holeHi, wall, inside);
  // The building's faces outward, 20 cm further out; its north face pierced.
  const glm::vec3 lo(-kWall), hi = room + kWall;
  box(b, lo, hi, BoxFaces::kAll & ~32u, true, wall, outside);
  rectWithHole(b, 2, hi.z, +1, {lo.x, lo.y}, {hi.x, hi.y}, holeLo, holeHi, wall, outside);
  // The reveal: soffit, sill and jambs, facing into the hole.
  const auto reveal = [&](float z0, float z1, uint32_t node) {
    b.rect(1, holeHi.y, -1, {z0, holeLo.x}, {z1, holeHi.x}, wall, node);
    b.rect(1, holeLo.y, +1, {z0, holeLo.x}, {z1, holeHi.x}, wall, node);
    b.rect(0, holeLo.x, +1, {holeLo.y, z0}, {holeHi.y, z1}, wall, node);
    b.rect(0, holeHi.x, -1, {holeLo.y, z0}, {holeHi.y, z1}, wall, node);
  };
  const glm::vec3 paneLo(holeLo.x, holeLo.y, kPaneLo), paneHi(holeHi.x, holeHi.y, kPaneHi);
  if (throughPane) {
    reveal(room.z, hi.z, b.node("room/reveal"));
    box(b, paneLo, paneHi, BoxFaces::kAll, true, glass, b.node("outside/pane"));
  } else {
    reveal(room.z, kPaneLo, b.node("room/reveal"));
    reveal(kPaneHi, hi.z, b.node("outside/reveal"));
    box(b, paneLo, paneHi, 16, true, glass, b.node("room/pane"));
    box(b, paneLo, paneHi, 32, true, glass, b.node("outside/pane"));
  }
  cellsFromNodePaths(s.scene, {"room", "outside"}, s.cells);
  s.scene.cameras.push_back(lookAt("room", {2.0f, 1.5f, 1.6f}, {2.0f, 1.5f, 4.2f}));
  return s;
}

SeedScene makeStoreysThroughSlab() {
  constexpr float kSlabLo = 3.0f, kSlabHi = 3.2f, kSunk = 0.05f;
  const glm::vec3 size(4.0f, 3.0f, 4.0f);
  SeedScene s;
  SceneBuilder b(s.scene);
  const uint32_t wall = b.material("wall", glm::vec3(0.7f)), wood = b.material("wood", glm::vec3(0.5f));
  const uint32_t lamp = b.material("lamp", glm::vec3(0.8f), glm::vec3(100.0f));
  const uint32_t lower = b.node("lower/walls"), upper = b.node("upper/walls");
  box(b, glm::vec3(0.0f), size, BoxFaces::kAll, false, wall, lower);
  box(b, {0.0f, kSlabHi, 0.0f}, {size.x, kSlabHi + size.y, size.z}, BoxFaces::kAll, false, wall, upper);
  box(b, {0.0f, kSlabLo, 0.0f}, {size.x, kSlabHi, size.z}, BoxFaces::kSides, true, wall,
      b.node("lower/slab"));
  b.rect(1, kSlabLo - 0.01f, -1, {1.7f, 0.7f}, {2.3f, 1.3f}, lamp, b.node("lower/lamp"));
  // The fin wall, one face from the ground to the roof through the slab.
  box(b, {1.95f, 0.0f, 1.0f}, {2.05f, kSlabHi + size.y, 3.0f}, BoxFaces::kSides, true, wall,
      b.node("lower/fin"));
  // Upstairs, sunk into the slab's top: a cabinet and a table's legs under its top.
  const uint32_t furniture = b.node("upper/furniture");
  box(b, {0.3f, kSlabHi - kSunk, 2.8f}, {1.3f, kSlabHi + 0.9f, 3.4f}, BoxFaces::kNoBottom, true, wood,
      furniture);
  const glm::vec2 table0(2.6f, 0.6f), table1(3.6f, 1.4f);  // x, z
  box(b, {table0.x, kSlabHi + 0.72f, table0.y}, {table1.x, kSlabHi + 0.76f, table1.y}, BoxFaces::kAll, true,
      wood, furniture);
  for (const glm::vec2 leg :
       {table0, glm::vec2(table1.x - 0.05f, table0.y), glm::vec2(table0.x, table1.y - 0.05f), table1 - 0.05f})
    box(b, {leg.x, kSlabHi - kSunk, leg.y}, {leg.x + 0.05f, kSlabHi + 0.72f, leg.y + 0.05f}, BoxFaces::kSides,
        true, wood, furniture);
  // Downstairs, a wardrobe 5 cm up into the slab's underside.
  box(b, {0.3f, 0.0f, 2.8f}, {1.3f, kSlabLo + kSunk, 3.4f}, BoxFaces::kSides, true, wood,
      b.node("lower/wardrobe"));
  cellsFromNodePaths(s.scene, {"lower", "upper"}, s.cells);
  s.scene.cameras.push_back(lookAt("lower", {3.7f, 1.6f, 0.3f}, {1.5f, 2.6f, 2.5f}));
  s.scene.cameras.push_back(lookAt("upper", {3.7f, 4.6f, 3.7f}, {1.5f, kSlabHi, 1.5f}));
  return s;
}

}  // namespace cpgi
