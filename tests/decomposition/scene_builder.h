// Small scenes built in code for the decomposition tests: boxes with outward faces, rooms made of wall
// boxes, doors cut as gaps. Y is up (glTF), metres.
#pragma once

#include <vector>

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

/// Builds the three rooms; `wall` overrides the inner walls' thickness (thin-wall tests).
inline Scene makeThreeRooms(float doorWidth = 1.0f, float innerWall = ThreeRooms::kWall) {
  using R = ThreeRooms;
  SceneBuilder b;
  const float w = R::kWall, len = 3 * R::kRoom + 4 * w, depth = R::kRoom + 2 * w, H = R::kHeight;
  b.box({0, -w, 0}, {len, 0, depth});
  b.box({0, H, 0}, {len, H + w, depth});
  b.box({0, 0, 0}, {len, H, w});
  b.box({0, 0, depth - w}, {len, H, depth});
  for (int k = 0; k < 4; ++k) {
    const float x0 = R::wallX(k) + (k == 1 || k == 2 ? 0.5f * (w - innerWall) : 0.0f);
    const float x1 = x0 + (k == 1 || k == 2 ? innerWall : w);
    if (k == 0 || k == 3) {
      b.box({x0, 0, w}, {x1, H, depth - w});
      continue;
    }
    const float zc = w + 0.5f * R::kRoom, z0 = zc - 0.5f * doorWidth, z1 = zc + 0.5f * doorWidth;
    b.box({x0, 0, w}, {x1, H, z0});
    b.box({x0, 0, z1}, {x1, H, depth - w});
    b.box({x0, R::kDoorHeight, z0}, {x1, H, z1});
  }
  return b.scene();
}

}  // namespace cpgi::testing
