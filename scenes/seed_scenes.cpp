#include "scenes/seed_scenes.h"

#include <stdexcept>
#include <string>

#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

// Dimensions of design.md §4 (metres). Rooms run along +x, y is up (glTF), doors in the x walls.
constexpr float kRoom = 4.0f, kHeight = 3.0f, kWall = 0.2f;
constexpr float kDoorZ0 = 1.5f, kDoorZ1 = 2.5f, kDoorTop = 2.1f;
constexpr SceneBuilder::Door kDoor{kDoorZ0, kDoorZ1, kDoorTop};
constexpr float kLightSize = 1.0f, kLightDrop = 0.01f, kLightEmission = 100.0f;
// seed3: B's surfaces cut into squares of at most this size; 0.28 m brings seed3 to 1204 quads (thesis:
// 1224).
constexpr float kSubdivision = 0.28f;
const char* const kNames[3] = {"A", "B", "C"};

float roomX0(int r) {
  return r * (kRoom + kWall);
}

struct Materials {
  uint32_t wall, red, green, floor, ceiling, light, occluder;
};

void addRoom(SceneBuilder& b, const Materials& m, int r, int level) {
  const std::string name = kNames[r];
  const float x0 = roomX0(r), x1 = x0 + kRoom;
  SceneBuilder::Room room;
  room.name = name;
  room.lo = glm::vec3(x0, 0, 0);
  room.hi = glm::vec3(x1, kHeight, kRoom);
  room.floor = m.floor;
  room.ceiling = m.ceiling;
  room.south = room.north = m.wall;
  room.west = r == 0 ? m.red : m.wall;
  room.east = r == 2 ? m.green : m.wall;
  room.doorWest = r > 0;
  room.doorEast = r < 2;
  room.door = kDoor;
  room.maxCell = (level >= 3 && r == 1) ? kSubdivision : 0.0f;
  b.room(room);

  // The light: 1 m², facing down, 1 cm under the ceiling centre of A and C.
  if (r != 1) {
    const float c = kRoom / 2, h = kLightSize / 2;
    b.rect(1, kHeight - kLightDrop, -1, {c - h, x0 + c - h}, {c + h, x0 + c + h}, m.light,
           b.node(name + "/light"));
  }
  if (level < 2) return;

  // Occluders: a 1 m cube and a 2 m × 1.5 m panel (5 cm thick) per room, placed clear of the doors'
  // line of sight in A and B and between seed3's columns in C.
  const glm::vec3 cube[3] = {{0.5f, 0, 0.5f}, {1.5f, 0, 0.3f}, {1.5f, 0, 1.5f}};
  const glm::vec3 panel[3] = {{1.0f, 0, 3.0f}, {1.0f, 0, 3.0f}, {1.0f, 0, 0.8f}};
  const glm::vec3 origin(x0, 0, 0);
  b.boxOnFloor(origin + cube[r], origin + cube[r] + glm::vec3(1.0f), m.occluder, b.node(name + "/cube"));
  b.boxOnFloor(origin + panel[r], origin + panel[r] + glm::vec3(2.0f, 1.5f, 0.05f), m.occluder,
               b.node(name + "/panel"));

  if (level >= 3 && r == 2) {
    // 4 × 4 floor-to-ceiling columns, 0.3 m square, spaced to keep clear of the light's footprint,
    // the cube and the panel.
    const float at[4] = {0.4f, 1.3f, 2.7f, 3.6f};
    const uint32_t node = b.node(name + "/columns");
    for (float cx : at)
      for (float cz : at) {
        const glm::vec3 lo = origin + glm::vec3(cx - 0.15f, 0, cz - 0.15f);
        const glm::vec3 hi = lo + glm::vec3(0.3f, kHeight, 0.3f);
        b.rect(0, lo.x, -1, {lo.y, lo.z}, {hi.y, hi.z}, m.wall, node);
        b.rect(0, hi.x, +1, {lo.y, lo.z}, {hi.y, hi.z}, m.wall, node);
        b.rect(2, lo.z, -1, {lo.x, lo.y}, {hi.x, hi.y}, m.wall, node);
        b.rect(2, hi.z, +1, {lo.x, lo.y}, {hi.x, hi.y}, m.wall, node);
      }
  }
}

}  // namespace

SeedScene makeSeedScene(int level) {
  if (level < 1 || level > 3) throw std::invalid_argument("seed scene level must be 1, 2 or 3");
  SeedScene out;
  SceneBuilder b(out.scene);
  Materials m;
  m.wall = b.material("wall", glm::vec3(0.7f));
  m.red = b.material("wall-red", {0.7f, 0.15f, 0.1f});
  m.green = b.material("wall-green", {0.15f, 0.6f, 0.2f});
  m.floor = b.material("floor", glm::vec3(0.5f));
  m.ceiling = b.material("ceiling", glm::vec3(0.8f));
  m.light = b.material("light", glm::vec3(0.8f), glm::vec3(kLightEmission));
  m.occluder = b.material("occluder", glm::vec3(0.6f));

  for (int r = 0; r < 3; ++r) addRoom(b, m, r, level);
  for (int r = 0; r < 2; ++r)
    b.doorReveal(roomX0(r) + kRoom, roomX0(r + 1), kDoor, kNames[r], kNames[r + 1], m.wall, m.floor);

  cellsFromNodePaths(out.scene, {"A", "B", "C"}, out.cells);
  // Portals: exactly the door openings at the wall mid-planes, normals from the lower room into the next.
  for (int r = 0; r < 2; ++r) {
    const float xm = roomX0(r) + kRoom + kWall / 2;
    PortalQuad p;
    p.name = std::string("portal:") + kNames[r] + ":" + kNames[r + 1];
    p.corners = {glm::vec3(xm, 0, kDoorZ0), glm::vec3(xm, 0, kDoorZ1), glm::vec3(xm, kDoorTop, kDoorZ1),
                 glm::vec3(xm, kDoorTop, kDoorZ0)};
    p.cellA = r;
    p.cellB = r + 1;
    computePortalFrame(p);
    if (p.normal.x < 0) {
      std::swap(p.corners[1], p.corners[3]);
      computePortalFrame(p);
    }
    out.cells.portals.push_back(p);
  }

  const float y = 1.6f;
  out.scene.cameras.push_back(lookAt("A", {3.7f, y, 3.7f}, {0.2f, 1.0f, 0.5f}));
  out.scene.cameras.push_back(lookAt("B", {roomX0(1) + 2.0f, 2.2f, 3.8f}, {roomX0(1) + 2.0f, 0.8f, 0.0f}));
  // Between seed3's columns (x 0.55..1.15) and north of their last row (z > 3.75).
  out.scene.cameras.push_back(lookAt("C", {roomX0(2) + 0.85f, y, 3.9f}, {roomX0(2) + 3.8f, 1.0f, 0.5f}));
  return out;
}

}  // namespace cpgi
