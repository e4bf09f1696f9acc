#include "scenes/seed_scenes.h"

#include <stdexcept>
#include <string>

#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

// Dimensions of design.md §4 (metres). Rooms run along +x, y is up (glTF), doors in the x walls.
constexpr float kRoom = 4.0f, kHeight = 3.0f, kWall = 0.2f;
constexpr float kDoorZ0 = 1.5f, kDoorZ1 = 2.5f, kDoorTop = 2.1f;
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

// A wall perpendicular to x at `x`, facing `sign`, with the door opening cut out when `door`.
void xWall(SceneBuilder& b, float x, float sign, bool door, uint32_t mat, uint32_t node, float maxCell) {
  if (!door) {
    b.rect(0, x, sign, {0, 0}, {kHeight, kRoom}, mat, node, maxCell);
    return;
  }
  b.rect(0, x, sign, {0, 0}, {kHeight, kDoorZ0}, mat, node, maxCell);
  b.rect(0, x, sign, {0, kDoorZ1}, {kHeight, kRoom}, mat, node, maxCell);
  b.rect(0, x, sign, {kDoorTop, kDoorZ0}, {kHeight, kDoorZ1}, mat, node, maxCell);
}

void addRoom(SceneBuilder& b, const Materials& m, int r, int level) {
  const std::string name = kNames[r];
  const float x0 = roomX0(r), x1 = x0 + kRoom;
  const float sub = (level >= 3 && r == 1) ? kSubdivision : 0.0f;
  b.rect(1, 0.0f, +1, {0, x0}, {kRoom, x1}, m.floor, b.node(name + "/floor"), sub);
  b.rect(1, kHeight, -1, {0, x0}, {kRoom, x1}, m.ceiling, b.node(name + "/ceiling"), sub);
  b.rect(2, 0.0f, +1, {x0, 0}, {x1, kHeight}, m.wall, b.node(name + "/wall-south"), sub);
  b.rect(2, kRoom, -1, {x0, 0}, {x1, kHeight}, m.wall, b.node(name + "/wall-north"), sub);
  xWall(b, x0, +1, r > 0, r == 0 ? m.red : m.wall, b.node(name + "/wall-west"), sub);
  xWall(b, x1, -1, r < 2, r == 2 ? m.green : m.wall, b.node(name + "/wall-east"), sub);

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

// The door's reveal (two sides, lintel soffit, threshold) inside the wall between rooms r and r+1, cut
// at the wall's mid-plane so each half belongs to the room on its side.
void addDoor(SceneBuilder& b, const Materials& m, int r) {
  const float xw = roomX0(r) + kRoom, xm = xw + kWall / 2, xe = xw + kWall;
  for (int side = 0; side < 2; ++side) {
    const float a = side == 0 ? xw : xm, c = side == 0 ? xm : xe;
    const uint32_t node = b.node(std::string(kNames[r + side]) + "/door-" + kNames[r] + kNames[r + 1]);
    b.rect(2, kDoorZ0, +1, {a, 0}, {c, kDoorTop}, m.wall, node);
    b.rect(2, kDoorZ1, -1, {a, 0}, {c, kDoorTop}, m.wall, node);
    b.rect(1, kDoorTop, -1, {kDoorZ0, a}, {kDoorZ1, c}, m.wall, node);
    b.rect(1, 0.0f, +1, {kDoorZ0, a}, {kDoorZ1, c}, m.floor, node);
  }
}

Camera lookAt(const std::string& name, glm::vec3 eye, glm::vec3 target) {
  Camera cam;
  cam.name = name;
  cam.position = eye;
  cam.forward = glm::normalize(target - eye);
  cam.up = glm::normalize(glm::vec3(0, 1, 0) - cam.forward * cam.forward.y);
  cam.yfov = glm::radians(60.0f);
  cam.aspect = 4.0f / 3.0f;
  return cam;
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
  for (int r = 0; r < 2; ++r) addDoor(b, m, r);

  // Cells from the first component of each node path ("B/door-AB" belongs to B).
  for (int r = 0; r < 3; ++r) out.cells.cells.push_back({kNames[r], {}, {}});
  for (uint32_t t = 0; t < out.scene.triangles.size(); ++t) {
    const std::string& path = out.scene.nodePaths[out.scene.triangles[t].node];
    out.cells.cells[out.cells.findCell(path.substr(0, path.find('/')))].triangles.push_back(t);
  }
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
  out.scene.cameras.push_back(lookAt("C", {roomX0(2) + 0.3f, y, 3.7f}, {roomX0(2) + 3.8f, 1.0f, 0.5f}));
  return out;
}

}  // namespace cpgi
