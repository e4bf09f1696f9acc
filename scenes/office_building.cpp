#include "scenes/office_building.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

constexpr float kRoom = 4.0f, kHeight = 3.0f, kWall = 0.2f;
constexpr float kPitch = kRoom + kWall, kStorey = kHeight + kWall;
constexpr float kDoorHalf = 0.5f, kDoorTop = 2.1f, kHatch0 = 0.4f, kHatch1 = 1.6f;
constexpr float kLampHalf = 0.3f, kLampDrop = 0.01f, kLampEmission = 100.0f;

struct Materials {
  uint32_t wall = 0, floor = 0, ceiling = 0, lamp = 0;
};

struct Room {
  std::string name;
  glm::vec3 lo{0.0f}, hi{0.0f};
};

// A rectangle of `b.rect` with an optional hole [h0, h1] (same 2D coordinates), as up to four pieces.
void rectWithHole(SceneBuilder& b, int axis, float at, float sign, glm::vec2 lo, glm::vec2 hi,
                  const glm::vec2* h0, const glm::vec2* h1, uint32_t material, uint32_t node) {
  auto piece = [&](glm::vec2 a, glm::vec2 c) {
    if (c.x - a.x > 1e-4f && c.y - a.y > 1e-4f) b.rect(axis, at, sign, a, c, material, node);
  };
  if (!h0) return piece(lo, hi);
  piece(lo, {h0->x, hi.y});
  piece({h1->x, lo.y}, hi);
  piece({h0->x, lo.y}, {h1->x, h0->y});
  piece({h0->x, h1->y}, {h1->x, hi.y});
}

// A tunnel's wall split at its mid-plane: the part below `mid` (on coordinate `split` of the 2D pair) to
// `a`'s node, the rest to `b`'s.
void splitRect(SceneBuilder& b, int axis, float at, float sign, glm::vec2 lo, glm::vec2 hi, int split,
               float mid, uint32_t material, uint32_t nodeA, uint32_t nodeB) {
  glm::vec2 loB = lo, hiA = hi;
  hiA[split] = mid, loB[split] = mid;
  b.rect(axis, at, sign, lo, hiA, material, nodeA);
  b.rect(axis, at, sign, loB, hi, material, nodeB);
}

PortalQuad portal(const std::string& a, const std::string& b, int cellA, int cellB,
                  std::array<glm::vec3, 4> corners, glm::vec3 aToB) {
  PortalQuad p;
  p.name = "portal:" + a + ":" + b;
  p.corners = corners;
  p.cellA = cellA, p.cellB = cellB;
  computePortalFrame(p);
  if (glm::dot(p.normal, aToB) < 0.0f) {
    std::swap(p.corners[1], p.corners[3]);
    computePortalFrame(p);
  }
  return p;
}

// Which faces of a room have an opening.
struct Openings {
  bool west = false, east = false, south = false, north = false, down = false, up = false;
};

// The inside faces of room `q`, with a door or hatch cut where `o` says, and its lamp when `lamp`.
void addRoomFaces(SceneBuilder& b, const Materials& m, const Room& q, const Openings& o, bool lamp) {
  const glm::vec3 lo = q.lo, hi = q.hi, mid = 0.5f * (lo + hi);
  auto node = [&](const std::string& part) { return b.node(q.name + "/" + part); };
  // Holes: doors in the x walls (coordinates y, z) and z walls (x, y); hatches in the slabs (z, x).
  const glm::vec2 xd0{lo.y, mid.z - kDoorHalf}, xd1{lo.y + kDoorTop, mid.z + kDoorHalf};
  const glm::vec2 zd0{mid.x - kDoorHalf, lo.y}, zd1{mid.x + kDoorHalf, lo.y + kDoorTop};
  const glm::vec2 h0{lo.z + kHatch0, lo.x + kHatch0}, h1{lo.z + kHatch1, lo.x + kHatch1};
  rectWithHole(b, 0, lo.x, 1, {lo.y, lo.z}, {hi.y, hi.z}, o.west ? &xd0 : nullptr, &xd1, m.wall,
               node("wall-west"));
  rectWithHole(b, 0, hi.x, -1, {lo.y, lo.z}, {hi.y, hi.z}, o.east ? &xd0 : nullptr, &xd1, m.wall,
               node("wall-east"));
  rectWithHole(b, 2, lo.z, 1, {lo.x, lo.y}, {hi.x, hi.y}, o.south ? &zd0 : nullptr, &zd1, m.wall,
               node("wall-south"));
  rectWithHole(b, 2, hi.z, -1, {lo.x, lo.y}, {hi.x, hi.y}, o.north ? &zd0 : nullptr, &zd1, m.wall,
               node("wall-north"));
  rectWithHole(b, 1, lo.y, 1, {lo.z, lo.x}, {hi.z, hi.x}, o.down ? &h0 : nullptr, &h1, m.floor,
               node("floor"));
  rectWithHole(b, 1, hi.y, -1, {lo.z, lo.x}, {hi.z, hi.x}, o.up ? &h0 : nullptr, &h1, m.ceiling,
               node("ceiling"));
  if (lamp)
    b.rect(1, hi.y - kLampDrop, -1, {mid.z - kLampHalf, mid.x - kLampHalf},
           {mid.z + kLampHalf, mid.x + kLampHalf}, m.lamp, node("lamp"));
}

// The door from `a` to its east neighbour `e` through x in [a.hi.x, a.hi.x + kWall]: its reveal, and its
// portal.
PortalQuad doorEast(SceneBuilder& b, const Materials& m, const Room& a, int ia, const Room& e, int ie) {
  const uint32_t na = b.node(a.name + "/door-" + e.name), ne = b.node(e.name + "/door-" + a.name);
  const float mz = 0.5f * (a.lo.z + a.hi.z), y0 = a.lo.y, y1 = a.lo.y + kDoorTop;
  const float x0 = a.hi.x, xm = x0 + kWall / 2, x1 = x0 + kWall, z0 = mz - kDoorHalf, z1 = mz + kDoorHalf;
  splitRect(b, 2, z0, 1, {x0, y0}, {x1, y1}, 0, xm, m.wall, na, ne);
  splitRect(b, 2, z1, -1, {x0, y0}, {x1, y1}, 0, xm, m.wall, na, ne);
  splitRect(b, 1, y1, -1, {z0, x0}, {z1, x1}, 1, xm, m.wall, na, ne);
  splitRect(b, 1, y0, 1, {z0, x0}, {z1, x1}, 1, xm, m.floor, na, ne);
  return portal(a.name, e.name, ia, ie,
                {glm::vec3(xm, y0, z0), glm::vec3(xm, y0, z1), glm::vec3(xm, y1, z1), glm::vec3(xm, y1, z0)},
                {1, 0, 0});
}

// The door from `a` to its north neighbour `n` through z in [a.hi.z, a.hi.z + kWall].
PortalQuad doorNorth(SceneBuilder& b, const Materials& m, const Room& a, int ia, const Room& n, int in) {
  const uint32_t na = b.node(a.name + "/door-" + n.name), nn = b.node(n.name + "/door-" + a.name);
  const float mx = 0.5f * (a.lo.x + a.hi.x), y0 = a.lo.y, y1 = a.lo.y + kDoorTop;
  const float z0 = a.hi.z, zm = z0 + kWall / 2, z1 = z0 + kWall, x0 = mx - kDoorHalf, x1 = mx + kDoorHalf;
  splitRect(b, 0, x0, 1, {y0, z0}, {y1, z1}, 1, zm, m.wall, na, nn);
  splitRect(b, 0, x1, -1, {y0, z0}, {y1, z1}, 1, zm, m.wall, na, nn);
  splitRect(b, 1, y1, -1, {z0, x0}, {z1, x1}, 0, zm, m.wall, na, nn);
  splitRect(b, 1, y0, 1, {z0, x0}, {z1, x1}, 0, zm, m.floor, na, nn);
  return portal(a.name, n.name, ia, in,
                {glm::vec3(x0, y0, zm), glm::vec3(x1, y0, zm), glm::vec3(x1, y1, zm), glm::vec3(x0, y1, zm)},
                {0, 0, 1});
}

// The hatch from `a` up to `u` through y in [a.hi.y, a.hi.y + kWall].
PortalQuad hatchUp(SceneBuilder& b, const Materials& m, const Room& a, int ia, const Room& u, int iu) {
  const uint32_t na = b.node(a.name + "/hatch-" + u.name), nu = b.node(u.name + "/hatch-" + a.name);
  const float ya = a.hi.y, ym = ya + kWall / 2, yb = ya + kWall;
  const float x0 = a.lo.x + kHatch0, x1 = a.lo.x + kHatch1, z0 = a.lo.z + kHatch0, z1 = a.lo.z + kHatch1;
  splitRect(b, 0, x0, 1, {ya, z0}, {yb, z1}, 0, ym, m.wall, na, nu);
  splitRect(b, 0, x1, -1, {ya, z0}, {yb, z1}, 0, ym, m.wall, na, nu);
  splitRect(b, 2, z0, 1, {x0, ya}, {x1, yb}, 1, ym, m.wall, na, nu);
  splitRect(b, 2, z1, -1, {x0, ya}, {x1, yb}, 1, ym, m.wall, na, nu);
  return portal(a.name, u.name, ia, iu,
                {glm::vec3(x0, ym, z0), glm::vec3(x1, ym, z0), glm::vec3(x1, ym, z1), glm::vec3(x0, ym, z1)},
                {0, 1, 0});
}

}  // namespace

SeedScene makeOfficeBuilding(const OfficeLayout& layout) {
  for (int n : {layout.storeys, layout.rows, layout.columns})
    if (n < 1 || n > 64) throw std::invalid_argument("office building: counts must be in [1, 64]");
  SeedScene out;
  SceneBuilder b(out.scene);
  Materials m;
  m.wall = b.material("wall", glm::vec3(0.7f));
  m.floor = b.material("floor", glm::vec3(0.5f));
  m.ceiling = b.material("ceiling", glm::vec3(0.8f));
  m.lamp = b.material("light", glm::vec3(0.8f), glm::vec3(kLampEmission));

  const int S = layout.storeys, R = layout.rows, C = layout.columns;
  auto index = [&](int f, int r, int c) { return (f * R + r) * C + c; };
  std::vector<Room> rooms(size_t(S * R * C));
  std::vector<std::string> names;
  for (int f = 0; f < S; ++f)
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < C; ++c) {
        Room& room = rooms[size_t(index(f, r, c))];
        room.name = "F" + std::to_string(f + 1) + "-R" + std::to_string(r + 1) + "-C" + std::to_string(c + 1);
        room.lo = {c * kPitch + kWall / 2, f * kStorey + kWall / 2, r * kPitch + kWall / 2};
        room.hi = room.lo + glm::vec3(kRoom, kHeight, kRoom);
        names.push_back(room.name);
      }

  for (int f = 0; f < S; ++f)
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < C; ++c) {
        const int i = index(f, r, c);
        const bool corner = r == 0 && c == 0;  // the hatches join the corner rooms of consecutive storeys
        addRoomFaces(b, m, rooms[size_t(i)],
                     {c > 0, c + 1 < C, r > 0, r + 1 < R, corner && f > 0, corner && f + 1 < S}, i % 3 == 0);
      }
  // Reveals (split at the wall's or slab's mid-plane between the two rooms) and portals.
  for (int f = 0; f < S; ++f)
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < C; ++c) {
        const int i = index(f, r, c);
        const Room& a = rooms[size_t(i)];
        std::vector<PortalQuad>& portals = out.cells.portals;
        if (c + 1 < C)
          portals.push_back(doorEast(b, m, a, i, rooms[size_t(index(f, r, c + 1))], index(f, r, c + 1)));
        if (r + 1 < R)
          portals.push_back(doorNorth(b, m, a, i, rooms[size_t(index(f, r + 1, c))], index(f, r + 1, c)));
        if (r == 0 && c == 0 && f + 1 < S)
          portals.push_back(hatchUp(b, m, a, i, rooms[size_t(index(f + 1, r, c))], index(f + 1, r, c)));
      }
  cellsFromNodePaths(out.scene, names, out.cells);  // the cells, beside the portals already there

  const Room& first = rooms[0];
  out.scene.cameras.push_back(lookAt(first.name, first.hi - glm::vec3(0.3f, 1.4f, 0.3f),
                                     glm::vec3(first.lo.x + 0.5f, first.lo.y + 1.0f, first.lo.z + 0.5f)));
  return out;
}

}  // namespace cpgi
