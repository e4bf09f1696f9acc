// Small scenes built in code for the decomposition tests: boxes with outward faces, rooms made of wall
// boxes, doors cut as gaps. Y is up (glTF), metres.
#pragma once

#include <string>
#include <vector>

#include "core/cell_graph.h"
#include "core/scene.h"

namespace cpgi::testing {

class SceneBuilder {
 public:
  SceneBuilder() {
    scene_.materials.push_back({"grey", glm::vec3(0.6f), glm::vec3(0.0f)});
    scene_.nodePaths.push_back("root");
  }

  /// A planar quad a-b-c-d, counter-clockwise seen from the side its normal points to.
  void quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    tri(a, b, c);
    tri(a, c, d);
  }
  void tri(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    Triangle t;
    t.p = {a, b, c};
    const glm::vec3 n = t.geometricNormal();
    t.n = {n, n, n};
    scene_.triangles.push_back(t);
  }
  /// An axis-aligned box with outward-facing faces.
  void box(glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    quad(p[0], p[3], p[2], p[1]);  // -z
    quad(p[4], p[5], p[6], p[7]);  // +z
    quad(p[0], p[4], p[7], p[3]);  // -x
    quad(p[1], p[2], p[6], p[5]);  // +x
    quad(p[0], p[1], p[5], p[4]);  // -y
    quad(p[3], p[7], p[6], p[2]);  // +y
  }
  Scene& scene() { return scene_; }

 private:
  Scene scene_;
};

/// Geometry of the seed-like three-room building (design.md §4): rooms 4 × 4 × 3 m along +x, walls 0.2 m,
/// doors doorWidth × 2.1 m centred in the two inner walls. Floor and ceiling are single slabs through
/// all rooms, so their faces cross the door planes.
struct ThreeRooms {
  static constexpr float kWall = 0.2f, kRoom = 4.0f, kHeight = 3.0f, kDoorHeight = 2.1f;
  static float wallX(int k) { return k * (kRoom + kWall); }  // wall k spans [wallX, wallX + kWall]
  static glm::vec3 doorCentre(int k) { return {wallX(k) + 0.5f * kWall, 0.5f * kDoorHeight, kWall + 0.5f * kRoom}; }
  /// The room index a point in the interior belongs to (by the wall mid-planes).
  static int roomOf(const glm::vec3& p) { return p.x < doorCentre(1).x ? 0 : p.x < doorCentre(2).x ? 1 : 2; }
};

struct ThreeRoomsOptions {
  float doorWidth = 1.0f;
  float innerWall = ThreeRooms::kWall;  ///< thickness of the two inner walls (thin-wall tests)
  bool slabsPerRoom = false;            ///< floor, ceiling and outer walls cut at the inner walls' mid-planes
  float crackWidth = 0.0f;              ///< > 0: a floor-to-ceiling slit this wide in inner wall 1, 1 m from a corner
};

/// Builds the three rooms.
inline Scene makeThreeRooms(const ThreeRoomsOptions& o = {}) {
  using R = ThreeRooms;
  SceneBuilder b;
  const float w = R::kWall, len = 3 * R::kRoom + 4 * w, depth = R::kRoom + 2 * w, H = R::kHeight;
  const int segments = o.slabsPerRoom ? 3 : 1;
  for (int s = 0; s < segments; ++s) {
    const float x0 = s == 0 ? 0.0f : R::doorCentre(s).x, x1 = s == segments - 1 ? len : R::doorCentre(s + 1).x;
    b.box({x0, -w, 0}, {x1, 0, depth});
    b.box({x0, H, 0}, {x1, H + w, depth});
    b.box({x0, 0, 0}, {x1, H, w});
    b.box({x0, 0, depth - w}, {x1, H, depth});
  }
  for (int k = 0; k < 4; ++k) {
    if (k == 0 || k == 3) {
      b.box({R::wallX(k), 0, w}, {R::wallX(k) + w, H, depth - w});
      continue;
    }
    const float x0 = R::wallX(k) + 0.5f * (w - o.innerWall), x1 = x0 + o.innerWall;
    const float zc = w + 0.5f * R::kRoom, z0 = zc - 0.5f * o.doorWidth, z1 = zc + 0.5f * o.doorWidth;
    if (k == 1 && o.crackWidth > 0.0f) {
      const float c0 = w + 1.0f, c1 = c0 + o.crackWidth;
      b.box({x0, 0, w}, {x1, H, c0});
      b.box({x0, 0, c1}, {x1, H, z0});
    } else {
      b.box({x0, 0, w}, {x1, H, z0});
    }
    b.box({x0, 0, z1}, {x1, H, depth - w});
    b.box({x0, R::kDoorHeight, z0}, {x1, H, z1});
  }
  return b.scene();
}

/// The hand-made cells of makeThreeRooms({.slabsPerRoom = true}): triangles by the room their centroid
/// lies in, portals exactly the door openings at the inner walls' mid-planes.
inline CellGraph manualThreeRooms(const Scene& scene, float doorWidth = 1.0f) {
  using R = ThreeRooms;
  CellGraph g;
  for (const char* name : {"A", "B", "C"}) g.cells.push_back({name, {}, {}});
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    g.cells[size_t(R::roomOf(scene.triangles[t].centroid()))].triangles.push_back(uint32_t(t));
  for (int k = 1; k <= 2; ++k) {
    PortalQuad q;
    const glm::vec3 c = R::doorCentre(k);
    const float hw = 0.5f * doorWidth, hh = 0.5f * R::kDoorHeight;
    q.corners = {c + glm::vec3(0, -hh, hw), c + glm::vec3(0, -hh, -hw), c + glm::vec3(0, hh, -hw), c + glm::vec3(0, hh, hw)};
    q.cellA = k - 1, q.cellB = k;
    q.name = std::string("portal:") + g.cells[size_t(k - 1)].name + ":" + g.cells[size_t(k)].name;
    computePortalFrame(q);
    g.portals.push_back(q);
  }
  return g;
}

}  // namespace cpgi::testing
