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
        const Room& q = rooms[size_t(index(f, r, c))];
        const glm::vec3 lo = q.lo, hi = q.hi, mid = 0.5f * (lo + hi);
        auto node = [&](const std::string& part) { return b.node(q.name + "/" + part); };
        // Holes: doors in the x walls (coordinates y, z) and z walls (x, y); hatches in the slabs (z, x) of
        // the corner rooms (0, 0) between storeys.
        const glm::vec2 xd0{lo.y, mid.z - kDoorHalf}, xd1{lo.y + kDoorTop, mid.z + kDoorHalf};
        const glm::vec2 zd0{mid.x - kDoorHalf, lo.y}, zd1{mid.x + kDoorHalf, lo.y + kDoorTop};
        const glm::vec2 h0{lo.z + kHatch0, lo.x + kHatch0}, h1{lo.z + kHatch1, lo.x + kHatch1};
        const bool corner = r == 0 && c == 0;
        rectWithHole(b, 0, lo.x, 1, {lo.y, lo.z}, {hi.y, hi.z}, c > 0 ? &xd0 : nullptr, &xd1, m.wall,
                     node("wall-west"));
        rectWithHole(b, 0, hi.x, -1, {lo.y, lo.z}, {hi.y, hi.z}, c + 1 < C ? &xd0 : nullptr, &xd1, m.wall,
                     node("wall-east"));
        rectWithHole(b, 2, lo.z, 1, {lo.x, lo.y}, {hi.x, hi.y}, r > 0 ? &zd0 : nullptr, &zd1, m.wall,
                     node("wall-south"));
        rectWithHole(b, 2, hi.z, -1, {lo.x, lo.y}, {hi.x, hi.y}, r + 1 < R ? &zd0 : nullptr, &zd1, m.wall,
                     node("wall-north"));
        rectWithHole(b, 1, lo.y, 1, {lo.z, lo.x}, {hi.z, hi.x}, corner && f > 0 ? &h0 : nullptr, &h1, m.floor,
                     node("floor"));
        rectWithHole(b, 1, hi.y, -1, {lo.z, lo.x}, {hi.z, hi.x}, corner && f + 1 < S ? &h0 : nullptr, &h1,
                     m.ceiling, node("ceiling"));
        if (index(f, r, c) % 3 == 0)
          b.rect(1, hi.y - kLampDrop, -1, {mid.z - kLampHalf, mid.x - kLampHalf},
                 {mid.z + kLampHalf, mid.x + kLampHalf}, m.lamp, node("lamp"));
      }

  // Reveals (split at the wall's or slab's mid-plane between the two rooms) and portals.
  for (int f = 0; f < S; ++f)
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < C; ++c) {
        const int ia = index(f, r, c);
        const Room& a = rooms[size_t(ia)];
        const glm::vec3 mid = 0.5f * (a.lo + a.hi);
        const float y0 = a.lo.y, y1 = a.lo.y + kDoorTop;
        if (c + 1 < C) {  // door east, through x in [a.hi.x, a.hi.x + kWall]
          const int ib = index(f, r, c + 1);
          const Room& e = rooms[size_t(ib)];
          const uint32_t na = b.node(a.name + "/door-" + e.name), ne = b.node(e.name + "/door-" + a.name);
          const float x0 = a.hi.x, xm = x0 + kWall / 2, x1 = x0 + kWall, z0 = mid.z - kDoorHalf,
                      z1 = mid.z + kDoorHalf;
          splitRect(b, 2, z0, 1, {x0, y0}, {x1, y1}, 0, xm, m.wall, na, ne);
          splitRect(b, 2, z1, -1, {x0, y0}, {x1, y1}, 0, xm, m.wall, na, ne);
          splitRect(b, 1, y1, -1, {z0, x0}, {z1, x1}, 1, xm, m.wall, na, ne);
          splitRect(b, 1, y0, 1, {z0, x0}, {z1, x1}, 1, xm, m.floor, na, ne);
          out.cells.portals.push_back(portal(
              a.name, e.name, ia, ib,
              {glm::vec3(xm, y0, z0), glm::vec3(xm, y0, z1), glm::vec3(xm, y1, z1), glm::vec3(xm, y1, z0)},
              {1, 0, 0}));
        }
        if (r + 1 < R) {  // door north, through z in [a.hi.z, a.hi.z + kWall]
          const int ib = index(f, r + 1, c);
          const Room& n = rooms[size_t(ib)];
          const uint32_t na = b.node(a.name + "/door-" + n.name), nn = b.node(n.name + "/door-" + a.name);
          const float z0 = a.hi.z, zm = z0 + kWall / 2, z1 = z0 + kWall, x0 = mid.x - kDoorHalf,
                      x1 = mid.x + kDoorHalf;
          splitRect(b, 0, x0, 1, {y0, z0}, {y1, z1}, 1, zm, m.wall, na, nn);
          splitRect(b, 0, x1, -1, {y0, z0}, {y1, z1}, 1, zm, m.wall, na, nn);
          splitRect(b, 1, y1, -1, {z0, x0}, {z1, x1}, 0, zm, m.wall, na, nn);
          splitRect(b, 1, y0, 1, {z0, x0}, {z1, x1}, 0, zm, m.floor, na, nn);
          out.cells.portals.push_back(portal(
              a.name, n.name, ia, ib,
              {glm::vec3(x0, y0, zm), glm::vec3(x1, y0, zm), glm::vec3(x1, y1, zm), glm::vec3(x0, y1, zm)},
              {0, 0, 1}));
        }
        if (r == 0 && c == 0 && f + 1 < S) {  // hatch up, through y in [a.hi.y, a.hi.y + kWall]
          const int ib = index(f + 1, r, c);
          const Room& u = rooms[size_t(ib)];
          const uint32_t na = b.node(a.name + "/hatch-" + u.name), nu = b.node(u.name + "/hatch-" + a.name);
          const float ya = a.hi.y, ym = ya + kWall / 2, yb = ya + kWall;
          const float x0 = a.lo.x + kHatch0, x1 = a.lo.x + kHatch1, z0 = a.lo.z + kHatch0,
                      z1 = a.lo.z + kHatch1;
          splitRect(b, 0, x0, 1, {ya, z0}, {yb, z1}, 0, ym, m.wall, na, nu);
          splitRect(b, 0, x1, -1, {ya, z0}, {yb, z1}, 0, ym, m.wall, na, nu);
          splitRect(b, 2, z0, 1, {x0, ya}, {x1, yb}, 1, ym, m.wall, na, nu);
          splitRect(b, 2, z1, -1, {x0, ya}, {x1, yb}, 1, ym, m.wall, na, nu);
          out.cells.portals.push_back(portal(
              a.name, u.name, ia, ib,
              {glm::vec3(x0, ym, z0), glm::vec3(x1, ym, z0), glm::vec3(x1, ym, z1), glm::vec3(x0, ym, z1)},
              {0, 1, 0}));
        }
      }
  cellsFromNodePaths(out.scene, names, out.cells);  // the cells, beside the portals already there

  const Room& first = rooms[0];
  out.scene.cameras.push_back(lookAt(first.name, first.hi - glm::vec3(0.3f, 1.4f, 0.3f),
                                     glm::vec3(first.lo.x + 0.5f, first.lo.y + 1.0f, first.lo.z + 0.5f)));
  return out;
}

}  // namespace cpgi
