#include "scenes/stability_scenes.h"

#include <stdexcept>

#include "scenes/buildings.h"
#include "scenes/contact_scenes.h"
#include "scenes/office_building.h"
#include "scenes/openings_scene.h"
#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

constexpr float kRoom = 4.0f, kHeight = 3.0f;

struct Palette {
  uint32_t wall, floor, ceiling, black, light;
};

Palette addPalette(SceneBuilder& b, glm::vec3 lightEmission) {
  Palette p;
  p.wall = b.material("wall", glm::vec3(0.7f));
  p.floor = b.material("floor", glm::vec3(0.5f));
  p.ceiling = b.material("ceiling", glm::vec3(0.8f));
  p.black = b.material("black", glm::vec3(0.0f));
  p.light = b.material("light", glm::vec3(0.8f), lightEmission);
  return p;
}

SceneBuilder::Room plainRoom(const std::string& name, float x0, const Palette& p) {
  SceneBuilder::Room r;
  r.name = name;
  r.lo = glm::vec3(x0, 0, 0);
  r.hi = glm::vec3(x0 + kRoom, kHeight, kRoom);
  r.floor = p.floor;
  r.ceiling = p.ceiling;
  r.south = r.north = r.west = r.east = p.wall;
  return r;
}

}  // namespace

namespace {
constexpr float kTwoRoomWall = 0.2f;

struct TwoRooms {
  Palette palette;
  SceneBuilder::Door door;
};

// Plain rooms A | B, kRoom square, on either side of a kTwoRoomWall wall with the seed door and its reveal.
TwoRooms addTwoPlainRooms(SceneBuilder& b, glm::vec3 lightEmission) {
  const Palette p = addPalette(b, lightEmission);
  const float xb = kRoom + kTwoRoomWall;
  SceneBuilder::Room a = plainRoom("A", 0.0f, p), rb = plainRoom("B", xb, p);
  a.doorEast = rb.doorWest = true;
  b.room(a);
  b.room(rb);
  b.doorReveal(kRoom, xb, a.door, "A", "B", p.wall, p.floor);
  return {p, a.door};
}

// Cells A and B from the node paths, the portal in the door at the wall's mid-plane (A → B), and a
// camera in each room, for the two-room scenes of kRoom × kRoom rooms on either side of a `wall`.
void addTwoRoomCellsAndCameras(SeedScene& s, const SceneBuilder::Door& door, float wall) {
  const float xb = kRoom + wall, xm = kRoom + wall / 2;
  cellsFromNodePaths(s.scene, {"A", "B"}, s.cells);
  PortalQuad portal;
  portal.name = "portal:A:B";
  portal.corners = {glm::vec3(xm, 0, door.z0), glm::vec3(xm, door.top, door.z0),
                    glm::vec3(xm, door.top, door.z1), glm::vec3(xm, 0, door.z1)};
  portal.cellA = 0;
  portal.cellB = 1;
  computePortalFrame(portal);
  s.cells.portals.push_back(portal);
  s.scene.cameras.push_back(lookAt("B", {xb + 0.3f, 1.8f, 3.7f}, {xb + kRoom, 1.0f, 2.0f}));
  s.scene.cameras.push_back(lookAt("A", {3.7f, 1.8f, 3.7f}, {0.0f, 1.0f, 2.0f}));
}
}  // namespace

SeedScene makeSpotThroughDoor() {
  SeedScene s;
  SceneBuilder b(s.scene);
  // 0.1 m × 0.1 m at 5000 W/m²: 50 W, about what the seed scenes' 1 m² lights put into a room.
  const TwoRooms rooms = addTwoPlainRooms(b, glm::vec3(5000.0f));
  const Palette& p = rooms.palette;

  // The lamp: a black tube 0.5 m long, 0.1 m square inside (1 cm walls), its open end facing +x at door
  // height, the emitter at its closed end. Its beam half-angle is atan(0.1 / 0.5) ≈ 11°.
  const glm::vec3 lo(0.05f, 0.95f, 1.95f), hi(0.55f, 1.05f, 2.05f);
  const float t = 0.01f;
  const uint32_t lamp = b.node("A/lamp");
  b.rect(0, lo.x + 0.001f, +1, {lo.y, lo.z}, {hi.y, hi.z}, p.light, lamp);  // emitter
  b.rect(0, lo.x, +1, {lo.y, lo.z}, {hi.y, hi.z}, p.black, lamp);           // back, inside
  b.rect(1, lo.y, +1, {lo.z, lo.x}, {hi.z, hi.x}, p.black, lamp);           // inside faces
  b.rect(1, hi.y, -1, {lo.z, lo.x}, {hi.z, hi.x}, p.black, lamp);
  b.rect(2, lo.z, +1, {lo.x, lo.y}, {hi.x, hi.y}, p.black, lamp);
  b.rect(2, hi.z, -1, {lo.x, lo.y}, {hi.x, hi.y}, p.black, lamp);
  const glm::vec3 olo = lo - glm::vec3(t), ohi = hi + glm::vec3(0, t, t);
  b.rect(0, olo.x, -1, {olo.y, olo.z}, {ohi.y, ohi.z}, p.black, lamp);  // outside faces
  b.rect(1, olo.y, -1, {olo.z, olo.x}, {ohi.z, ohi.x}, p.black, lamp);
  b.rect(1, ohi.y, +1, {olo.z, olo.x}, {ohi.z, ohi.x}, p.black, lamp);
  b.rect(2, olo.z, -1, {olo.x, olo.y}, {ohi.x, ohi.y}, p.black, lamp);
  b.rect(2, ohi.z, +1, {olo.x, olo.y}, {ohi.x, ohi.y}, p.black, lamp);
  b.rect(0, hi.x, +1, {olo.y, olo.z}, {lo.y, ohi.z}, p.black, lamp);  // rim at the open end
  b.rect(0, hi.x, +1, {hi.y, olo.z}, {ohi.y, ohi.z}, p.black, lamp);
  b.rect(0, hi.x, +1, {lo.y, olo.z}, {hi.y, lo.z}, p.black, lamp);
  b.rect(0, hi.x, +1, {lo.y, hi.z}, {hi.y, ohi.z}, p.black, lamp);

  addTwoRoomCellsAndCameras(s, rooms.door, kTwoRoomWall);
  return s;
}

namespace {
// Two plain rooms A | B with the seed door between them, its portal and cells, and no emissive surface:
// the punctual-light scenes add their lamp.
SeedScene twoDarkRooms() {
  SeedScene s;
  SceneBuilder b(s.scene);
  addTwoRoomCellsAndCameras(s, addTwoPlainRooms(b, glm::vec3(0.0f)).door, kTwoRoomWall);
  return s;
}
}  // namespace

SeedScene makePointLightRooms() {
  SeedScene s = twoDarkRooms();
  PunctualLight lamp;
  lamp.kind = PunctualLight::Kind::Point;
  lamp.name = "lamp";
  lamp.position = glm::vec3(2.0f, 2.2f, 2.0f);
  lamp.intensity = glm::vec3(8.0f);  // W/sr: 4π × 8 ≈ 100 W, the seed scenes' lamp
  s.scene.lights.push_back(lamp);
  return s;
}

SeedScene makeSpotLightThroughDoor() {
  SeedScene s = twoDarkRooms();
  PunctualLight spot;
  spot.kind = PunctualLight::Kind::Spot;
  spot.name = "spot";
  spot.position = glm::vec3(0.3f, 1.05f, 2.0f);
  spot.direction = glm::vec3(1.0f, 0.0f, 0.0f);
  spot.innerCone = 0.14f, spot.outerCone = 0.19f;  // ≈ 8° and 11°, the lamp housing of spot-door
  spot.intensity = glm::vec3(600.0f);              // W/sr on the axis: about 47 W in all
  s.scene.lights.push_back(spot);
  return s;
}

SeedScene makeThinWall(float thickness, float shiftB) {
  if (!(thickness >= 0.0f)) throw std::invalid_argument("wall thickness must be >= 0");
  SeedScene s;
  SceneBuilder b(s.scene);
  const Palette p = addPalette(b, glm::vec3(100.0f));
  b.room(plainRoom("A", 0.0f, p));
  SceneBuilder::Room rb = plainRoom("B", kRoom + thickness, p);
  rb.lo.z += shiftB;
  rb.hi.z += shiftB;
  b.room(rb);
  const float c = kRoom / 2;
  b.rect(1, kHeight - 0.01f, -1, {c - 0.5f, c - 0.5f}, {c + 0.5f, c + 0.5f}, p.light, b.node("A/light"));
  cellsFromNodePaths(s.scene, {"A", "B"}, s.cells);
  s.scene.cameras.push_back(
      lookAt("B", {kRoom + thickness + 3.7f, 1.6f, 3.7f + shiftB}, {kRoom, 1.0f, 0.5f + shiftB}));
  return s;
}

const std::vector<std::string>& builtinSceneNames() {
  // Every building too, from buildings.cpp's own list: a name missing here is one `generate --help`
  // and its error message would not tell the user about.
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = {"seed1",     "seed2",         "seed3",   "spot-door",
                                    "thin-wall", "thin-wall-5cm", "openings"};
    all.insert(all.end(), buildingNames().begin(), buildingNames().end());
    all.insert(all.end(), {"point-light", "spot-light", "office", "office-small"});
    all.insert(all.end(), {"pane-through", "pane-split", "slab-through"});
    return all;
  }();
  return names;
}

SeedScene makeBuiltinScene(const std::string& name) {
  if (name == "seed1") return makeSeedScene(1);
  if (name == "seed2") return makeSeedScene(2);
  if (name == "seed3") return makeSeedScene(3);
  if (name == "spot-door") return makeSpotThroughDoor();
  if (name == "thin-wall") return makeThinWall(0.0f);
  if (name == "thin-wall-5cm") return makeThinWall(0.05f);
  if (name == "openings") return makeOpeningsScene();
  if (name == "point-light") return makePointLightRooms();
  if (name == "spot-light") return makeSpotLightThroughDoor();
  if (name == "pane-through") return makePaneRoom(true);
  if (name == "pane-split") return makePaneRoom(false);
  if (name == "slab-through") return makeStoreysThroughSlab();
  // Many rooms for cell jobs (issue 16): 108 rooms on 3 storeys, and 4 rooms on 2 for the tests.
  if (name == "office") return makeOfficeBuilding(OfficeLayout{3, 6, 6});
  if (name == "office-small") return makeOfficeBuilding(OfficeLayout{2, 1, 2});
  for (const std::string& building : buildingNames())
    if (name == building) return makeBuilding(name).seed;
  throw std::invalid_argument("unknown built-in scene '" + name + "'");
}

}  // namespace cpgi
