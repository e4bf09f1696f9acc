#include "scenes/openings_scene.h"

#include <string>
#include <vector>

#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

using L = OpeningsLayout;

struct Opening {
  float z0, z1, y0, y1;
};

// The face of a wall at x = `at` facing `sign`·x over the room's full height and depth, with `openings`
// (sorted by z, disjoint in z) cut out: full-height strips between them, and the parts below and above
// each opening.
void wallWithOpenings(SceneBuilder& b, float at, float sign, const std::vector<Opening>& openings,
                      uint32_t material, uint32_t node) {
  float z = 0.0f;
  for (const Opening& o : openings) {
    if (o.z0 > z) b.rect(0, at, sign, {0.0f, z}, {L::kHeight, o.z0}, material, node);
    if (o.y0 > 0.0f) b.rect(0, at, sign, {0.0f, o.z0}, {o.y0, o.z1}, material, node);
    if (o.y1 < L::kHeight) b.rect(0, at, sign, {o.y1, o.z0}, {L::kHeight, o.z1}, material, node);
    z = o.z1;
  }
  if (z < L::kRoom) b.rect(0, at, sign, {0.0f, z}, {L::kHeight, L::kRoom}, material, node);
}

// The reveal of an opening through a wall spanning x in [x0, x1], cut at the mid-plane: the half at x0
// belongs to cell `west`, the other to `east` (as SceneBuilder::doorReveal).
void reveal(SceneBuilder& b, float x0, float x1, const Opening& o, const std::string& west,
            const std::string& east, uint32_t wall, uint32_t floor) {
  const float xm = 0.5f * (x0 + x1);
  for (int side = 0; side < 2; ++side) {
    const float a = side == 0 ? x0 : xm, c = side == 0 ? xm : x1;
    const uint32_t n = b.node((side == 0 ? west : east) + "/reveal");
    b.rect(2, o.z0, +1, {a, o.y0}, {c, o.y1}, wall, n);
    b.rect(2, o.z1, -1, {a, o.y0}, {c, o.y1}, wall, n);
    b.rect(1, o.y1, -1, {o.z0, a}, {o.z1, c}, wall, n);
    b.rect(1, o.y0, +1, {o.z0, a}, {o.z1, c}, o.y0 > 0.0f ? wall : floor, n);
  }
}

PortalQuad portalAt(const std::string& name, float x, const Opening& o, int cellA, int cellB) {
  PortalQuad p;
  p.name = name;
  p.corners = {glm::vec3(x, o.y0, o.z0), glm::vec3(x, o.y0, o.z1), glm::vec3(x, o.y1, o.z1),
               glm::vec3(x, o.y1, o.z0)};
  p.cellA = cellA;
  p.cellB = cellB;
  computePortalFrame(p);
  if (p.normal.x < 0) {  // from A towards B: +x
    std::swap(p.corners[1], p.corners[3]);
    computePortalFrame(p);
  }
  return p;
}

}  // namespace

SeedScene makeOpeningsScene() {
  SeedScene out;
  SceneBuilder b(out.scene);
  const uint32_t wall = b.material("wall", glm::vec3(0.7f)), floor = b.material("floor", glm::vec3(0.5f)),
                 ceiling = b.material("ceiling", glm::vec3(0.8f)),
                 blue = b.material("wall-blue", {0.2f, 0.3f, 0.7f}),
                 light = b.material("light", glm::vec3(0.8f), glm::vec3(L::kLampEmission));

  const float ax0 = 0.0f, ax1 = L::kRoom;                       // A
  const float bx0 = ax1 + L::kThickWall, bx1 = bx0 + L::kRoom;  // B
  const float cx0 = bx1, cx1 = cx0 + L::kRoom;                  // C: its west face is B's east face's back
  const Opening wide{L::kWideDoorZ0, L::kWideDoorZ1, 0.0f, L::kDoorTop};
  const Opening window{L::kWindowZ0, L::kWindowZ1, L::kWindowY0, L::kWindowY1};
  const Opening narrow{L::kNarrowDoorZ0, L::kNarrowDoorZ1, 0.0f, L::kDoorTop};

  struct RoomSpec {
    std::string name;
    float x0, x1;
    std::vector<Opening> west, east;
    uint32_t westMaterial;
  };
  const RoomSpec rooms[3] = {{"A", ax0, ax1, {}, {wide, window}, wall},
                             {"B", bx0, bx1, {wide, window}, {narrow}, wall},
                             {"C", cx0, cx1, {narrow}, {}, wall}};
  for (const RoomSpec& r : rooms) {
    b.rect(1, 0.0f, +1, {0.0f, r.x0}, {L::kRoom, r.x1}, floor, b.node(r.name + "/floor"));
    b.rect(1, L::kHeight, -1, {0.0f, r.x0}, {L::kRoom, r.x1}, ceiling, b.node(r.name + "/ceiling"));
    b.rect(2, 0.0f, +1, {r.x0, 0.0f}, {r.x1, L::kHeight}, r.name == "C" ? blue : wall,
           b.node(r.name + "/wall-south"));
    b.rect(2, L::kRoom, -1, {r.x0, 0.0f}, {r.x1, L::kHeight}, wall, b.node(r.name + "/wall-north"));
    wallWithOpenings(b, r.x0, +1, r.west, r.westMaterial, b.node(r.name + "/wall-west"));
    wallWithOpenings(b, r.x1, -1, r.east, wall, b.node(r.name + "/wall-east"));
  }
  reveal(b, ax1, bx0, wide, "A", "B", wall, floor);
  reveal(b, ax1, bx0, window, "A", "B", wall, floor);

  const float c = 0.5f * L::kRoom, h = 0.5f * L::kLampSize;
  b.rect(1, L::kHeight - 0.01f, -1, {c - h, c - h}, {c + h, c + h}, light, b.node("A/light"));

  cellsFromNodePaths(out.scene, {"A", "B", "C"}, out.cells);
  const float abMid = 0.5f * (ax1 + bx0);
  out.cells.portals.push_back(portalAt("portal:A:B", abMid, wide, 0, 1));
  out.cells.portals.push_back(portalAt("portal:A:B.window", abMid, window, 0, 1));
  out.cells.portals.push_back(portalAt("portal:B:C", cx0, narrow, 1, 2));

  out.scene.cameras.push_back(lookAt("A", {0.3f, 1.6f, 2.7f}, {ax1, 1.0f, 1.0f}));
  out.scene.cameras.push_back(lookAt("B", {bx0 + 0.3f, 1.8f, 0.3f}, {bx1, 0.8f, 2.6f}));
  out.scene.cameras.push_back(lookAt("C", {cx1 - 0.3f, 1.6f, 0.3f}, {cx0, 0.8f, 2.5f}));
  return out;
}

}  // namespace cpgi
