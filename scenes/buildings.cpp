#include "scenes/buildings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "scenes/furniture.h"
#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

constexpr float kWall = 0.2f;
constexpr float kStorey = 2.7f, kSlab = 0.25f;  // clear height of a storey, thickness of a floor
constexpr float kDoorTop = 2.1f, kSill = 0.9f, kHead = 2.1f;
constexpr float kLevel2 = kStorey + kSlab;  // the upper floor's finished level

// A building as solid massing: `body` boxes minus `carved` ones (rooms, openings) plus `added` ones
// (steps, posts, the ground, furniture). Its surface is found on the grid of every box coordinate, so
// faces never overlap and each one separates exactly one solid cell from one empty cell.
struct Massing {
  std::vector<Box3> body, carved, added;

  bool solidAt(const glm::vec3& p) const {
    auto inAny = [&](const std::vector<Box3>& boxes) {
      return std::any_of(boxes.begin(), boxes.end(), [&](const Box3& b) { return b.contains(p); });
    };
    return inAny(added) || (inAny(body) && !inAny(carved));
  }
};

struct Owner {
  uint32_t node, material;
};

// Emits the surface of `m`: for every grid face between a solid and an empty cell, a rectangle facing the
// empty side, runs of equal owner along one axis merged into one rectangle. `ownerOf(front, axis, sign)`
// names the node and material of a face from a point just in front of it.
template <class OwnerOf>
void emitSurface(const Massing& m, SceneBuilder& b, OwnerOf&& ownerOf) {
  std::vector<float> coords[3];
  for (const auto* list : {&m.body, &m.carved, &m.added})
    for (const Box3& box : *list)
      for (int a = 0; a < 3; ++a) coords[a].push_back(box.lo[a]), coords[a].push_back(box.hi[a]);
  for (auto& c : coords) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end(), [](float x, float y) { return std::abs(x - y) < 1e-5f; }),
            c.end());
  }
  const glm::ivec3 n(int(coords[0].size()) - 1, int(coords[1].size()) - 1, int(coords[2].size()) - 1);
  std::vector<char> solid(size_t(n.x) * size_t(n.y) * size_t(n.z));
  auto index = [&](const glm::ivec3& c) {
    return (size_t(c.z) * size_t(n.y) + size_t(c.y)) * size_t(n.x) + size_t(c.x);
  };
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const glm::vec3 centre(0.5f * (coords[0][x] + coords[0][x + 1]),
                               0.5f * (coords[1][y] + coords[1][y + 1]),
                               0.5f * (coords[2][z] + coords[2][z + 1]));
        solid[index({x, y, z})] = m.solidAt(centre);
      }
  auto solidCell = [&](glm::ivec3 c) {
    for (int a = 0; a < 3; ++a)
      if (c[a] < 0 || c[a] >= n[a]) return false;
    return bool(solid[index(c)]);
  };
  for (int a = 0; a < 3; ++a) {
    const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    for (int s = 0; s <= n[a]; ++s)
      for (int j = 0; j < n[a2]; ++j) {
        // One run at a time along a1: [start, i) with equal sign and owner.
        int start = -1;
        float runSign = 0.0f;
        Owner runOwner{0, 0};
        auto flush = [&](int end) {
          if (start < 0) return;
          b.rect(a, coords[a][s], runSign, {coords[a1][start], coords[a2][j]},
                 {coords[a1][end], coords[a2][j + 1]}, runOwner.material, runOwner.node);
          start = -1;
        };
        for (int i = 0; i < n[a1]; ++i) {
          glm::ivec3 below, above;
          below[a] = s - 1, above[a] = s;
          below[a1] = above[a1] = i;
          below[a2] = above[a2] = j;
          const bool sb = solidCell(below), sa = solidCell(above);
          if (sb == sa) {
            flush(i);
            continue;
          }
          const float sign = sb ? 1.0f : -1.0f;
          glm::vec3 front;
          front[a] = coords[a][s] + 0.01f * sign;
          front[a1] = 0.5f * (coords[a1][i] + coords[a1][i + 1]);
          front[a2] = 0.5f * (coords[a2][j] + coords[a2][j + 1]);
          const Owner o = ownerOf(front, a, sign);
          if (start >= 0 && (sign != runSign || o.node != runOwner.node || o.material != runOwner.material))
            flush(i);
          if (start < 0) start = i, runSign = sign, runOwner = o;
        }
        flush(n[a1]);
      }
  }
}

float boxDistance(const Box3& b, const glm::vec3& p) {
  return glm::length(glm::max(glm::max(b.lo - p, p - b.hi), glm::vec3(0.0f)));
}

// Builds a Building from rooms, openings and massing: surfaces owned by the room in front of them (the
// nearest room for the reveals of openings inside the body, "outside" beyond the body), a lamp per room,
// a camera per room, hand-made cells with the rooms as `cellvolume:` boxes and one portal per opening.
class BuildingMaker {
 public:
  BuildingMaker() : b_(out_.seed.scene) {
    floor_ = b_.material("floor", glm::vec3(0.5f));
    ceiling_ = b_.material("ceiling", glm::vec3(0.8f));
    wall_ = b_.material("wall", glm::vec3(0.7f));
    facade_ = b_.material("facade", glm::vec3(0.6f, 0.55f, 0.5f));
    ground_ = b_.material("ground", glm::vec3(0.3f, 0.35f, 0.25f));
    lamp_ = b_.material("lamp", glm::vec3(0.8f), glm::vec3(50.0f));
  }

  Massing massing;

  void room(const std::string& name, std::vector<Box3> boxes) {
    for (const Box3& box : boxes) massing.carved.push_back(box);
    out_.rooms.push_back({name, std::move(boxes)});
  }
  /// Exterior openings are left solid: the same building with its doors and windows shut.
  bool closedOutside = false;
  /// false: no 0.6 m emissive panel under each room's ceiling (the lights come as `lights` instead).
  bool panelLamps = true;
  std::vector<PunctualLight> lights;

  void opening(const std::string& name, Box3 box, int axis, const std::string& a, const std::string& b) {
    if (closedOutside && (a == "outside" || b == "outside")) return;
    massing.carved.push_back(box);
    out_.openings.push_back({name, box, axis, a, b});
  }
  /// For triangles added by hand (the spiral stair's wedges).
  Scene& scene() { return out_.seed.scene; }
  uint32_t nodeOf(const std::string& room, const std::string& what) { return b_.node(room + "/" + what); }
  uint32_t wallMaterial() const { return wall_; }

  Building finish() {
    emitSurface(massing, b_,
                [&](const glm::vec3& p, int axis, float sign) { return ownerOf(p, axis, sign); });
    std::vector<std::string> names;
    for (const BuildingRoom& r : out_.rooms) {
      const Box3& box = r.boxes.front();
      const glm::vec3 c = box.centre();
      const float half = 0.3f;
      if (panelLamps)
        b_.rect(1, box.hi.y - 0.01f, -1, {c.z - half, c.x - half}, {c.z + half, c.x + half}, lamp_,
                b_.node(r.name + "/lamp"));
      // No camera of its own: a fixed corner of the room stood inside the furnished house's fridge (its
      // kitchen view was black); a bake's default cameras find each room's empty floor by rays.
      names.push_back(r.name);
    }
    names.push_back("outside");
    for (const PunctualLight& l : lights) out_.seed.scene.lights.push_back(l);
    CellGraph& cells = out_.seed.cells;
    cellsFromNodePaths(out_.seed.scene, names, cells);
    for (size_t r = 0; r < out_.rooms.size(); ++r)
      for (const Box3& box : out_.rooms[r].boxes) appendBoxVolume(box.lo, box.hi, cells.cells[r].volume);
    for (const BuildingOpening& o : out_.openings) cells.portals.push_back(portalOf(o));
    return std::move(out_);
  }

 private:
  PortalQuad portalOf(const BuildingOpening& o) const {
    const int a = o.axis, a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    const float mid = 0.5f * (o.box.lo[a] + o.box.hi[a]);
    PortalQuad p;
    p.name = "portal:" + o.a + ":" + o.b;
    glm::vec3 c[4];
    const float u[4] = {o.box.lo[a1], o.box.hi[a1], o.box.hi[a1], o.box.lo[a1]};
    const float v[4] = {o.box.lo[a2], o.box.lo[a2], o.box.hi[a2], o.box.hi[a2]};
    for (int k = 0; k < 4; ++k) c[k][a] = mid, c[k][a1] = u[k], c[k][a2] = v[k];
    p.corners = {c[0], c[1], c[2], c[3]};
    computePortalFrame(p);
    if (p.normal[a] < 0.0f) std::swap(p.corners[1], p.corners[3]), computePortalFrame(p);
    const CellGraph& cells = out_.seed.cells;
    p.cellA = cells.findCell(o.a);
    p.cellB = cells.findCell(o.b);
    return p;
  }

  Owner ownerOf(const glm::vec3& p, int axis, float sign) {
    std::string room;
    for (const BuildingRoom& r : out_.rooms)
      for (const Box3& box : r.boxes)
        if (room.empty() && box.contains(p)) room = r.name;
    const bool inBody =
        std::any_of(massing.body.begin(), massing.body.end(), [&](const Box3& b) { return b.contains(p); });
    if (room.empty() && inBody) {  // the reveal of an opening: the nearest room
      float best = 1e30f;
      for (const BuildingRoom& r : out_.rooms)
        for (const Box3& box : r.boxes)
          if (const float d = boxDistance(box, p); d < best) best = d, room = r.name;
    }
    if (room.empty()) return {b_.node("outside/surface"), axis == 1 && sign > 0 ? ground_ : facade_};
    const uint32_t material = axis != 1 ? wall_ : sign > 0 ? floor_ : ceiling_;
    return {b_.node(room + "/surface"), material};
  }

  Building out_;
  SceneBuilder b_;
  uint32_t floor_ = 0, ceiling_ = 0, wall_ = 0, facade_ = 0, ground_ = 0, lamp_ = 0;
};

Box3 box(float x0, float y0, float z0, float x1, float y1, float z1) {
  return {{x0, y0, z0}, {x1, y1, z1}};
}

// A door (floor to kDoorTop) or window (kSill to kHead) through the wall at `at` along `axis` (0: a wall
// across x, 2: a wall across z), spanning [from, to] along the wall, on the storey whose floor is `level`.
Box3 hole(int axis, float at, float from, float to, float y0, float y1) {
  return axis == 0 ? box(at, y0, from, at + kWall, y1, to) : box(from, y0, at, to, y1, at + kWall);
}

// The house body (walls, floor slab, roof) of `storeys` over x in [0, sx], z in [0, sz], and the ground
// around it, `apron` metres wide (more towards -z by `frontApron`).
void houseShell(BuildingMaker& m, float sx, float sz, int storeys, float apron, float frontApron) {
  const float top = storeys * kLevel2;
  m.massing.body.push_back(box(0, -0.3f, 0, sx, top, sz));
  m.massing.added.push_back(box(-apron, -0.3f, -frontApron, sx + apron, 0.0f, sz + apron));
}

}  // namespace

Building makeOpenHouse() {
  BuildingMaker m;
  houseShell(m, 10.0f, 8.0f, 1, 1.0f, 1.0f);
  const float H = kStorey;
  m.room("hall", {box(0.2f, 0, 0.2f, 3.0f, H, 7.8f)});
  m.room("living", {box(3.2f, 0, 0.2f, 9.8f, H, 4.6f)});
  m.room("kitchen", {box(3.2f, 0, 4.8f, 6.4f, H, 7.8f)});
  m.room("bedroom", {box(6.6f, 0, 4.8f, 9.8f, H, 7.8f)});
  m.opening("front-door", hole(2, 0.0f, 1.0f, 2.0f, 0, kDoorTop), 2, "outside", "hall");
  m.opening("terrace-door", hole(0, 9.8f, 1.2f, 3.2f, 0, 2.2f), 0, "living", "outside");
  m.opening("door-hall-living", hole(0, 3.0f, 1.5f, 2.4f, 0, kDoorTop), 0, "hall", "living");
  m.opening("door-hall-kitchen", hole(0, 3.0f, 6.0f, 6.9f, 0, kDoorTop), 0, "hall", "kitchen");
  m.opening("door-living-bedroom", hole(2, 4.6f, 8.0f, 8.9f, 0, kDoorTop), 2, "living", "bedroom");
  m.opening("window-living", hole(2, 0.0f, 5.0f, 6.5f, kSill, kHead), 2, "outside", "living");
  m.opening("window-kitchen", hole(2, 7.8f, 4.2f, 5.4f, 1.0f, kHead), 2, "kitchen", "outside");
  m.opening("window-bedroom", hole(0, 9.8f, 5.6f, 7.0f, kSill, kHead), 0, "bedroom", "outside");
  m.opening("window-hall", hole(0, 0.0f, 4.0f, 5.0f, kSill, kHead), 0, "outside", "hall");
  return m.finish();
}

namespace {

// The spiral stair's wedge treads (closed prisms, 8 cm thick) round a column at `centre`, rising `rise`
// per step through a full turn, the last tread pointing +x.
void spiralTreads(BuildingMaker& m, glm::vec2 centre, int steps, float rise, float inner, float outer) {
  Scene& scene = m.scene();
  const uint32_t node = m.nodeOf("hall", "stair"), material = m.wallMaterial();
  const float dTheta = 2.0f * float(M_PI) / float(steps);
  for (int k = 0; k < steps; ++k) {
    const float t0 = float(k - steps) * dTheta, t1 = t0 + dTheta;
    const float top = float(k + 1) * rise, bottom = top - 0.08f;
    auto at = [&](float r, float t, float y) {
      return glm::vec3(centre.x + r * std::cos(t), y, centre.y + r * std::sin(t));
    };
    const glm::vec3 p[8] = {at(inner, t0, bottom), at(outer, t0, bottom), at(outer, t1, bottom),
                            at(inner, t1, bottom), at(inner, t0, top),    at(outer, t0, top),
                            at(outer, t1, top),    at(inner, t1, top)};
    // Angles grow from +x towards +z, so the corners 0-1-2-3 (inner, outer at t0; outer, inner at t1)
    // wind about -y: each face below is listed so that its normal points out of the prism.
    auto face = [&](int a, int c, int d, int e) {
      for (const auto& [i, j, k] : {std::array<int, 3>{a, c, d}, std::array<int, 3>{a, d, e}}) {
        Triangle t;
        t.p = {p[i], p[j], p[k]};
        const glm::vec3 n = t.geometricNormal();
        t.n = {n, n, n};
        t.material = material;
        t.node = node;
        scene.triangles.push_back(t);
      }
    };
    face(4, 7, 6, 5);  // top
    face(0, 1, 2, 3);  // bottom
    face(0, 4, 5, 1);  // the side at t0
    face(3, 2, 6, 7);  // the side at t1
    face(1, 5, 6, 2);  // outer
    face(0, 3, 7, 4);  // inner
  }
}

}  // namespace

namespace {

// The two-storey house's shell, rooms, openings and stair into `m`.
void twoStoreyHouse(BuildingMaker& m, bool spiral) {
  houseShell(m, 10.0f, 8.0f, 2, 1.0f, 1.0f);
  const float H = kStorey, y2 = kLevel2, H2 = kLevel2 + kStorey;
  m.room("hall", {box(0.2f, 0, 0.2f, 3.4f, H, 7.8f)});
  m.room("living", {box(3.6f, 0, 0.2f, 9.8f, H, 4.9f)});
  m.room("kitchen", {box(3.6f, 0, 5.1f, 9.8f, H, 7.8f)});
  m.room("landing", {box(0.2f, y2, 0.2f, 3.4f, H2, 7.8f)});
  m.room("bedroom1", {box(3.6f, y2, 0.2f, 9.8f, H2, 3.9f)});
  m.room("bedroom2", {box(3.6f, y2, 4.1f, 9.8f, H2, 7.8f)});
  m.opening("front-door", hole(2, 0.0f, 1.6f, 2.6f, 0, kDoorTop), 2, "outside", "hall");
  m.opening("terrace-door", hole(0, 9.8f, 1.2f, 3.2f, 0, 2.2f), 0, "living", "outside");
  m.opening("door-hall-living", hole(0, 3.4f, 1.0f, 1.9f, 0, kDoorTop), 0, "hall", "living");
  m.opening("door-hall-kitchen", hole(0, 3.4f, 6.4f, 7.3f, 0, kDoorTop), 0, "hall", "kitchen");
  m.opening("door-living-kitchen", hole(2, 4.9f, 7.5f, 8.4f, 0, kDoorTop), 2, "living", "kitchen");
  m.opening("door-landing-bedroom1", hole(0, 3.4f, 1.0f, 1.9f, y2, y2 + kDoorTop), 0, "landing", "bedroom1");
  m.opening("door-landing-bedroom2", hole(0, 3.4f, 6.4f, 7.3f, y2, y2 + kDoorTop), 0, "landing", "bedroom2");
  m.opening("window-living", hole(2, 0.0f, 5.5f, 7.5f, kSill, kHead), 2, "outside", "living");
  m.opening("window-kitchen", hole(2, 7.8f, 6.0f, 7.2f, 1.0f, kHead), 2, "kitchen", "outside");
  m.opening("window-bedroom1", hole(2, 0.0f, 5.5f, 7.0f, y2 + kSill, y2 + kHead), 2, "outside", "bedroom1");
  m.opening("window-bedroom2", hole(2, 7.8f, 5.5f, 7.0f, y2 + kSill, y2 + kHead), 2, "bedroom2", "outside");
  m.opening("window-landing", hole(2, 0.0f, 1.6f, 2.6f, y2 + kSill, y2 + kHead), 2, "outside", "landing");
  const int steps = 16;
  const float rise = y2 / float(steps);
  if (!spiral) {
    // Along the hall's west wall, rising +z; the hole over its upper 3 m, a 1 m balustrade beside it.
    const float run = 0.26f, z0 = 2.0f, zEnd = z0 + steps * run;
    for (int k = 0; k < steps; ++k)
      m.massing.added.push_back(box(0.2f, 0, z0 + k * run, 1.2f, (k + 1) * rise, z0 + (k + 1) * run));
    m.opening("stair", box(0.2f, H, zEnd - 3.0f, 1.2f, y2, zEnd), 1, "hall", "landing");
    m.massing.added.push_back(box(1.2f, y2, zEnd - 3.0f, 1.25f, y2 + 1.0f, zEnd));
  } else {
    const glm::vec2 c(1.3f, 5.0f);
    m.opening("stair", box(c.x - 1.0f, H, c.y - 1.0f, c.x + 1.0f, y2, c.y + 1.0f), 1, "hall", "landing");
    m.massing.added.push_back(box(c.x - 0.1f, 0, c.y - 0.1f, c.x + 0.1f, y2, c.y + 0.1f));
    spiralTreads(m, c, steps, rise, 0.1f, 0.95f);
  }
}

}  // namespace

Building makeTwoStoreyHouse(bool spiral, bool closedOutside) {
  BuildingMaker m;
  m.closedOutside = closedOutside;
  twoStoreyHouse(m, spiral);
  return m.finish();
}

Building makeFurnishedHouse() {
  BuildingMaker m;
  m.panelLamps = false;
  twoStoreyHouse(m, true);
  SceneBuilder b(m.scene());
  furnishSpiralHouse(b, m.lights);
  return m.finish();
}

Building makeGalleryHouse() {
  BuildingMaker m;
  houseShell(m, 10.0f, 8.0f, 2, 1.0f, 1.0f);
  const float H = kStorey, y2 = kLevel2, H2 = kLevel2 + kStorey;
  m.room("hall", {box(0.2f, 0, 0.2f, 3.4f, H, 7.8f)});
  m.room("living", {box(3.6f, 0, 0.2f, 9.8f, H2, 4.9f)});  // double height, no floor above it
  m.room("kitchen", {box(3.6f, 0, 5.1f, 9.8f, H, 7.8f)});
  m.room("gallery", {box(0.2f, y2, 0.2f, 3.4f, H2, 7.8f)});
  m.room("bedroom", {box(3.6f, y2, 5.1f, 9.8f, H2, 7.8f)});
  m.opening("front-door", hole(2, 0.0f, 1.6f, 2.6f, 0, kDoorTop), 2, "outside", "hall");
  m.opening("door-hall-living", hole(0, 3.4f, 1.0f, 1.9f, 0, kDoorTop), 0, "hall", "living");
  m.opening("door-hall-kitchen", hole(0, 3.4f, 6.4f, 7.3f, 0, kDoorTop), 0, "hall", "kitchen");
  m.opening("door-gallery-bedroom", hole(0, 3.4f, 6.4f, 7.3f, y2, y2 + kDoorTop), 0, "gallery", "bedroom");
  m.opening("window-living", hole(2, 0.0f, 5.5f, 7.5f, kSill, kHead), 2, "outside", "living");
  m.opening("window-kitchen", hole(2, 7.8f, 6.0f, 7.2f, 1.0f, kHead), 2, "kitchen", "outside");
  m.opening("window-bedroom", hole(2, 7.8f, 5.5f, 7.0f, y2 + kSill, y2 + kHead), 2, "bedroom", "outside");
  // The gallery looks over the living room above a 1 m balustrade, along the whole of their shared wall.
  m.opening("gallery", box(3.4f, y2 + 1.0f, 0.2f, 3.6f, H2, 4.9f), 0, "gallery", "living");
  const int steps = 16;
  const float rise = y2 / float(steps), run = 0.26f, z0 = 2.0f, zEnd = z0 + steps * run;
  for (int k = 0; k < steps; ++k)
    m.massing.added.push_back(box(0.2f, 0, z0 + k * run, 1.2f, (k + 1) * rise, z0 + (k + 1) * run));
  m.opening("stair", box(0.2f, H, zEnd - 3.0f, 1.2f, y2, zEnd), 1, "hall", "gallery");
  m.massing.added.push_back(box(1.2f, y2, zEnd - 3.0f, 1.25f, y2 + 1.0f, zEnd));
  return m.finish();
}

Building makeOpenPlanHouse() {
  BuildingMaker m;
  houseShell(m, 12.0f, 9.0f, 1, 1.0f, 1.0f);
  const float H = kStorey;
  m.room("open-plan", {box(0.2f, 0, 0.2f, 11.8f, H, 4.6f), box(0.2f, 0, 4.5f, 6.0f, H, 8.8f)});
  m.room("bedroom", {box(6.2f, 0, 4.8f, 9.0f, H, 8.8f)});
  m.room("bathroom", {box(9.2f, 0, 4.8f, 11.8f, H, 8.8f)});
  m.opening("front-door", hole(2, 0.0f, 2.0f, 3.0f, 0, kDoorTop), 2, "outside", "open-plan");
  m.opening("door-bedroom", hole(2, 4.6f, 7.0f, 7.9f, 0, kDoorTop), 2, "open-plan", "bedroom");
  m.opening("door-bathroom", hole(2, 4.6f, 10.0f, 10.8f, 0, kDoorTop), 2, "open-plan", "bathroom");
  m.opening("window-south-1", hole(2, 0.0f, 5.0f, 7.0f, kSill, kHead), 2, "outside", "open-plan");
  m.opening("window-south-2", hole(2, 0.0f, 9.0f, 10.5f, kSill, kHead), 2, "outside", "open-plan");
  m.opening("window-west", hole(0, 0.0f, 5.5f, 7.5f, kSill, kHead), 0, "outside", "open-plan");
  m.opening("window-north", hole(2, 8.8f, 2.0f, 4.0f, kSill, kHead), 2, "open-plan", "outside");
  m.opening("window-bedroom", hole(2, 8.8f, 7.0f, 8.4f, kSill, kHead), 2, "bedroom", "outside");
  m.opening("window-bathroom", hole(0, 11.8f, 6.0f, 7.0f, 1.4f, kHead), 0, "bathroom", "outside");
  // Kitchen island, sofa, dining table on legs.
  m.massing.added.push_back(box(2.0f, 0, 6.0f, 4.0f, 0.9f, 6.9f));
  m.massing.added.push_back(box(1.0f, 0, 1.0f, 3.0f, 0.8f, 1.9f));
  m.massing.added.push_back(box(8.0f, 0.72f, 1.5f, 9.6f, 0.76f, 2.4f));
  for (float x : {8.0f, 9.5f})
    for (float z : {1.5f, 2.3f}) m.massing.added.push_back(box(x, 0, z, x + 0.1f, 0.72f, z + 0.1f));
  return m.finish();
}

Building makePorchHouse() {
  BuildingMaker m;
  houseShell(m, 10.0f, 8.0f, 1, 1.0f, 3.5f);
  const float H = kStorey;
  m.room("hall", {box(0.2f, 0, 0.2f, 3.0f, H, 7.8f)});
  m.room("living", {box(3.2f, 0, 0.2f, 9.8f, H, 4.6f)});
  m.room("kitchen", {box(3.2f, 0, 4.8f, 9.8f, H, 7.8f)});
  m.opening("front-door", hole(2, 0.0f, 1.0f, 2.0f, 0, kDoorTop), 2, "outside", "hall");
  m.opening("door-hall-living", hole(0, 3.0f, 1.5f, 2.4f, 0, kDoorTop), 0, "hall", "living");
  m.opening("door-hall-kitchen", hole(0, 3.0f, 6.0f, 6.9f, 0, kDoorTop), 0, "hall", "kitchen");
  m.opening("window-living", hole(2, 0.0f, 5.0f, 6.5f, kSill, kHead), 2, "outside", "living");
  m.opening("window-kitchen", hole(2, 7.8f, 5.0f, 6.5f, 1.0f, kHead), 2, "kitchen", "outside");
  // The porch: a roof slab on two posts in front of the door, its floor the ground.
  m.massing.added.push_back(box(0.3f, H, -2.5f, 3.7f, kLevel2, 0.0f));
  for (float x : {0.3f, 3.55f}) m.massing.added.push_back(box(x, 0, -2.5f, x + 0.15f, H, -2.35f));
  return m.finish();
}

namespace {

// The kind of stair between the IFC-like house's storeys.
enum class IfcStair { Straight, OpenRiser, LShaped, Spiral };

// Whether the IFC-like house's living room rises through both storeys, and what stands along the edge of
// the landing that overlooks it: a 1 m parapet wall, or a balustrade of spindles on the floor's edge.
enum class IfcGallery { None, Parapet, Balustrade };

// A glass pane (2 cm, opaque to the decomposition as an IFC window's glazing is) across the middle of a
// window hole through the wall at `at` along `axis`.
void glazedWindow(BuildingMaker& m, int axis, float at, float from, float to, float y0, float y1) {
  const Box3 h = hole(axis, at, from, to, y0, y1);
  m.massing.carved.push_back(h);
  Box3 pane = h;
  const float mid = 0.5f * (h.lo[axis] + h.hi[axis]);
  pane.lo[axis] = mid - 0.01f, pane.hi[axis] = mid + 0.01f;
  m.massing.added.push_back(pane);
}

// The IFC-like house's stair, 16 risers up the hall's west side; returns the hole over it where a person's
// head would meet the slab.
Box3 ifcStair(BuildingMaker& m, IfcStair stair) {
  const float H = kStorey, y2 = kLevel2;
  const int steps = 16;
  const float rise = y2 / float(steps), run = 0.27f, width = 1.0f;
  Box3 hl;
  if (stair == IfcStair::Straight || stair == IfcStair::OpenRiser) {
    const float z0 = 1.2f, zEnd = z0 + steps * run;
    for (int k = 0; k < steps; ++k) {
      const float top = float(k + 1) * rise;
      // A flight's waist under its treads (space under the flight stays open), or 4 cm treads alone.
      const float bottom = stair == IfcStair::OpenRiser ? top - 0.04f : std::max(0.0f, top - 0.35f);
      m.massing.added.push_back(box(0.2f, bottom, z0 + k * run, 0.2f + width, top, z0 + (k + 1) * run));
    }
    hl = box(0.2f, H, zEnd - 3.3f, 0.2f + width, y2, zEnd);
  } else if (stair == IfcStair::LShaped) {
    // Up +z along the west wall to a quarter landing in the hall's north-west corner, then +x.
    const float z0 = 2.2f;
    const int first = 8;
    const float zl = z0 + first * run;  // the landing's south edge
    for (int k = 0; k < first; ++k)
      m.massing.added.push_back(box(0.2f, std::max(0.0f, (k + 1) * rise - 0.35f), z0 + k * run, 0.2f + width,
                                    (k + 1) * rise, z0 + (k + 1) * run));
    m.massing.added.push_back(
        box(0.2f, (first + 1) * rise - 0.35f, zl, 0.2f + width, (first + 1) * rise, zl + width));
    const float x0 = 0.2f + width;
    for (int k = first + 1; k < steps; ++k) {
      const float x = x0 + float(k - first - 1) * run;
      m.massing.added.push_back(box(x, (k + 1) * rise - 0.35f, zl, x + run, (k + 1) * rise, zl + width));
    }
    const float xEnd = x0 + float(steps - first - 1) * run;
    hl = box(0.2f, H, zl - 1.2f, xEnd, y2, zl + width);
  } else {
    const glm::vec2 c(1.3f, 4.4f);
    m.massing.added.push_back(box(c.x - 0.1f, 0, c.y - 0.1f, c.x + 0.1f, y2, c.y + 0.1f));
    spiralTreads(m, c, steps, rise, 0.1f, 0.95f);
    hl = box(c.x - 1.0f, H, c.y - 1.0f, c.x + 1.0f, y2, c.y + 1.0f);
  }
  return hl;
}

// The IFC-like house's furniture, and a balustrade of spindles along the open sides of the stair's hole
// `hl` on the landing.
void ifcFurniture(BuildingMaker& m, IfcStair stair, const Box3& hl, IfcGallery gallery) {
  const float y2 = kLevel2, width = 1.0f;
  const bool spiral = stair == IfcStair::Spiral;
  SceneBuilder b(m.scene());
  Furniture f(b);
  auto in = [&](const char* room) { return b.node(std::string(room) + "/furniture"); };
  // The balustrade round the hole on the landing, open where the stair arrives (the hole's +z end for a
  // straight stair, its +x end for the L, the spiral's +x side).
  const float rail = 0.9f, spacing = 0.12f, e = 0.05f;
  const float west = hl.lo.x + 0.05f, south = hl.lo.z - e, north = hl.hi.z + e, east = hl.hi.x + e;
  if (stair == IfcStair::Straight || stair == IfcStair::OpenRiser) {
    f.balustrade({{west, y2, south}, {east, y2, south}, {east, y2, hl.hi.z}}, rail, spacing, in("landing"));
  } else {
    // The arrival: the hole's east edge beside the last flight (L) or the last tread (spiral).
    const float gapLo = spiral ? 0.5f * (hl.lo.z + hl.hi.z) - 0.5f : hl.hi.z - width;
    const float gapHi = spiral ? 0.5f * (hl.lo.z + hl.hi.z) + 0.1f : hl.hi.z;
    f.balustrade({{west, y2, south}, {east, y2, south}, {east, y2, gapLo}}, rail, spacing, in("landing"));
    if (gapHi < hl.hi.z)
      f.balustrade({{west, y2, north}, {east, y2, north}, {east, y2, gapHi}}, rail, spacing, in("landing"));
    else
      f.balustrade({{west, y2, north}, {east, y2, north}}, rail, spacing, in("landing"));
  }

  // Hall: a shoe cabinet and a coat stand. Living: a sofa, a dining table and chairs, a bookshelf.
  f.cabinets({{2.9f, 0, 0.2f}, {3.55f, 0.9f, 0.8f}}, 2, Facing::MinusX, in("hall"));
  f.column({3.2f, 0, 5.8f}, 0.02f, 1.8f, 12, f.wood(), in("hall"));
  f.sofa({7.0f, 0, 5.6f}, {2.2f, 0.9f}, Facing::MinusZ, in("living"));
  f.table({6.0f, 0, 2.6f}, {1.6f, 0.9f}, false, in("living"));
  for (float x : {5.6f, 6.4f}) {
    f.chair({x, 0, 1.9f}, Facing::PlusZ, in("living"));
    f.chair({x, 0, 3.3f}, Facing::MinusZ, in("living"));
  }
  f.bookshelf({{11.4f, 0, 4.0f}, {11.75f, 2.1f, 5.8f}}, 6, Facing::MinusX, 5, in("living"));
  // Kitchen: cabinets along the north wall, a fridge, a table.
  f.cabinets({{0.3f, 0, 9.2f}, {4.0f, 0.9f, 9.8f}}, 6, Facing::MinusZ, in("kitchen"));
  f.block({{4.2f, 0, 9.1f}, {4.95f, 1.9f, 9.75f}}, f.fabric(), in("kitchen"), 0.3f);
  f.table({2.4f, 0, 7.6f}, {1.2f, 0.8f}, false, in("kitchen"));
  // Bathroom: a shower enclosure of 1 cm glass 2 m high in the north-east corner, open above, its door
  // a gap; a basin cabinet.
  const uint32_t glass = b.material("glass", glm::vec3(0.8f));
  f.block({{6.65f, 0, 8.85f}, {6.66f, 2.0f, 9.8f}}, glass, in("bathroom"));
  f.block({{6.65f, 0, 8.84f}, {7.6f, 2.0f, 8.85f}}, glass, in("bathroom"));
  f.block({{6.65f, 0, 8.85f}, {7.6f, 0.05f, 9.8f}}, f.wood(), in("bathroom"));  // its tray
  f.cabinets({{5.2f, 0, 6.4f}, {6.2f, 0.85f, 6.9f}}, 2, Facing::PlusZ, in("bathroom"));
  // Bedroom: a double bed and a wardrobe of boards (hollow, doors shut: an enclosure of 2.5 m3).
  f.bed({9.6f, 0, 7.5f}, {2.0f, 1.6f}, false, in("bedroom"));
  const float wx0 = 7.8f, wx1 = 9.8f, wz0 = 9.15f, wz1 = 9.78f, wt = 0.02f, wh = 2.2f;
  f.block({{wx0, 0, wz0}, {wx1, wt, wz1}}, f.wood(), in("bedroom"));
  f.block({{wx0, wh - wt, wz0}, {wx1, wh, wz1}}, f.wood(), in("bedroom"));
  f.block({{wx0, wt, wz0}, {wx0 + wt, wh - wt, wz1}}, f.wood(), in("bedroom"));
  f.block({{wx1 - wt, wt, wz0}, {wx1, wh - wt, wz1}}, f.wood(), in("bedroom"));
  f.block({{wx0 + wt, wt, wz1 - wt}, {wx1 - wt, wh - wt, wz1}}, f.wood(), in("bedroom"));
  f.block({{wx0 + wt, wt, wz0}, {wx1 - wt, wh - wt, wz0 + wt}}, f.wood(), in("bedroom"));
  // Upstairs: beds, a desk, a bath tub (with the gallery, no room1 or room2 over the living room).
  if (gallery == IfcGallery::None) {
    f.bed({5.0f, y2, 3.0f}, {2.0f, 0.9f}, true, in("room1"));
    f.table({9.5f, y2, 1.0f}, {1.2f, 0.6f}, false, in("room2"));
    f.chair({9.5f, y2, 1.5f}, Facing::MinusZ, in("room2"));
  }
  f.bed({9.6f, y2, 7.2f}, {2.0f, 1.6f}, false, in("room3"));
  f.block({{0.3f, y2, 8.9f}, {2.0f, y2 + 0.55f, 9.75f}}, glass, in("bath2"), 0.3f);
}

// The house in the shape an IFC export has (issue 46): two storeys of rooms behind doorways whose leaves
// are missing, windows glazed (closed), two exterior doors open, furniture, a shower enclosure of glass
// and a wardrobe, and a stair of `stair`'s kind from the hall up to the landing through a hole in the
// floor with a balustrade of spindles round it. With a `gallery` the living room rises through both storeys
// (no room1 or room2 over it, its upper windows high ones of its own) and the landing overlooks it along
// their whole shared wall, over a 1 m parapet or a balustrade; room3 is then reached through bath2.
void ifcHouse(BuildingMaker& m, IfcStair stair, IfcGallery gallery) {
  const bool open = gallery != IfcGallery::None;
  houseShell(m, 12.0f, 10.0f, 2, 1.0f, 1.0f);
  const float H = kStorey, y2 = kLevel2, H2 = kLevel2 + kStorey, w = 0.15f;  // interior walls 15 cm
  const float hx = 3.6f;  // the hall's and the landing's east wall
  m.room("hall", {box(0.2f, 0, 0.2f, hx, H, 6.2f)});
  m.room("living", {box(hx + w, 0, 0.2f, 11.8f, open ? H2 : H, 6.2f)});
  m.room("kitchen", {box(0.2f, 0, 6.2f + w, 5.0f, H, 9.8f)});
  m.room("bathroom", {box(5.0f + w, 0, 6.2f + w, 7.6f, H, 9.8f)});
  m.room("bedroom", {box(7.6f + w, 0, 6.2f + w, 11.8f, H, 9.8f)});
  m.room("landing", {box(0.2f, y2, 0.2f, hx, H2, 6.2f)});
  if (!open) {
    m.room("room1", {box(hx + w, y2, 0.2f, 7.6f, H2, 6.2f)});
    m.room("room2", {box(7.6f + w, y2, 0.2f, 11.8f, H2, 6.2f)});
  }
  m.room("bath2", {box(0.2f, y2, 6.2f + w, 5.0f, H2, 9.8f)});
  m.room("room3", {box(5.0f + w, y2, 6.2f + w, 11.8f, H2, 9.8f)});
  auto interior = [&](const std::string& name, int axis, float at, float from, float to, float level,
                      const std::string& a, const std::string& b) {
    const Box3 h = axis == 0 ? box(at, level, from, at + w, level + kDoorTop, to)
                             : box(from, level, at, to, level + kDoorTop, at + w);
    m.opening(name, h, axis, a, b);
  };
  m.opening("front-door", hole(2, 0.0f, 2.2f, 3.2f, 0, kDoorTop), 2, "outside", "hall");
  m.opening("terrace-door", hole(0, 11.8f, 2.0f, 3.6f, 0, 2.2f), 0, "living", "outside");
  interior("door-hall-living", 0, hx, 1.0f, 1.9f, 0, "hall", "living");
  interior("door-hall-kitchen", 2, 6.2f, 1.6f, 2.5f, 0, "hall", "kitchen");
  interior("door-living-bathroom", 2, 6.2f, 5.6f, 6.4f, 0, "living", "bathroom");
  interior("door-living-bedroom", 2, 6.2f, 9.0f, 9.9f, 0, "living", "bedroom");
  interior("door-landing-bath2", 2, 6.2f, 2.4f, 3.3f, y2, "landing", "bath2");
  if (open) {
    interior("door-bath2-room3", 0, 5.0f, 7.0f, 7.9f, y2, "bath2", "room3");
    // The wall between them stops at the parapet's top, or at the landing's floor (a 15 cm edge that
    // carries the balustrade).
    const float sill = gallery == IfcGallery::Parapet ? y2 + 1.0f : y2;
    m.opening("gallery", box(hx, sill, 0.2f, hx + w, H2, 6.2f), 0, "landing", "living");
  } else {
    interior("door-landing-room1", 0, hx, 1.0f, 1.9f, y2, "landing", "room1");
    interior("door-room1-room2", 0, 7.6f, 4.6f, 5.5f, y2, "room1", "room2");
    interior("door-room1-room3", 2, 6.2f, 6.2f, 7.1f, y2, "room1", "room3");
  }
  for (float level : {0.0f, y2}) {
    glazedWindow(m, 2, 0.0f, 5.0f, 7.0f, level + kSill, level + kHead);
    glazedWindow(m, 2, 0.0f, 8.5f, 10.5f, level + kSill, level + kHead);
    glazedWindow(m, 2, 9.8f, 1.5f, 3.0f, level + kSill, level + kHead);
    glazedWindow(m, 2, 9.8f, 8.5f, 10.5f, level + kSill, level + kHead);
    glazedWindow(m, 0, 11.8f, 7.0f, 8.5f, level + kSill, level + kHead);
  }
  glazedWindow(m, 2, 9.8f, 5.6f, 6.8f, 1.4f, kHead);             // the bathroom's high window
  glazedWindow(m, 0, 0.0f, 3.0f, 4.2f, y2 + kSill, y2 + kHead);  // the landing's

  const Box3 hl = ifcStair(m, stair);
  m.opening("stair", hl, 1, "hall", "landing");
  ifcFurniture(m, stair, hl, gallery);
  if (gallery == IfcGallery::Balustrade) {
    SceneBuilder b(m.scene());
    Furniture(b).balustrade({{hx + 0.5f * w, y2, 0.25f}, {hx + 0.5f * w, y2, 6.15f}}, 0.9f, 0.12f,
                            b.node("landing/furniture"));
  }
}

}  // namespace

Building makeIfcLikeHouse(const std::string& stair) {
  IfcStair kind = IfcStair::Straight;
  if (stair == "open-riser")
    kind = IfcStair::OpenRiser;
  else if (stair == "l")
    kind = IfcStair::LShaped;
  else if (stair == "spiral")
    kind = IfcStair::Spiral;
  else if (stair != "straight")
    throw std::invalid_argument("unknown stair '" + stair + "'");
  BuildingMaker m;
  ifcHouse(m, kind, IfcGallery::None);
  return m.finish();
}

Building makeIfcGalleryHouse(bool balustrade) {
  BuildingMaker m;
  ifcHouse(m, IfcStair::Straight, balustrade ? IfcGallery::Balustrade : IfcGallery::Parapet);
  return m.finish();
}

const std::vector<std::string>& buildingNames() {
  static const std::vector<std::string> names = {
      "house-open",           "house-stair",         "house-spiral",     "open-plan",        "porch",
      "house-stair-closed",   "house-spiral-closed", "house-gallery",    "house-furnished",  "ifc-house",
      "ifc-house-open-riser", "ifc-house-l-stair",   "ifc-house-spiral", "ifc-house-gallery",
      "ifc-house-gallery-balustrade"};
  return names;
}

Building makeBuilding(const std::string& name) {
  if (name == "house-open") return makeOpenHouse();
  if (name == "house-stair") return makeTwoStoreyHouse(false);
  if (name == "house-spiral") return makeTwoStoreyHouse(true);
  if (name == "house-stair-closed") return makeTwoStoreyHouse(false, true);
  if (name == "house-spiral-closed") return makeTwoStoreyHouse(true, true);
  if (name == "open-plan") return makeOpenPlanHouse();
  if (name == "house-gallery") return makeGalleryHouse();
  if (name == "porch") return makePorchHouse();
  if (name == "house-furnished") return makeFurnishedHouse();
  if (name == "ifc-house") return makeIfcLikeHouse("straight");
  if (name == "ifc-house-open-riser") return makeIfcLikeHouse("open-riser");
  if (name == "ifc-house-l-stair") return makeIfcLikeHouse("l");
  if (name == "ifc-house-spiral") return makeIfcLikeHouse("spiral");
  if (name == "ifc-house-gallery") return makeIfcGalleryHouse();
  if (name == "ifc-house-gallery-balustrade") return makeIfcGalleryHouse(true);
  throw std::invalid_argument("unknown building '" + name + "'");
}

}  // namespace cpgi
