#include "bench/house.h"

#include <algorithm>
#include <cmath>

namespace cpgi::bench {
namespace {

class Builder {
 public:
  Builder(Scene& s, float cell) : s_(s), cell_(cell) {}
  // A rectangle spanned by u and v from o, cut into a grid of squares no larger than cell_; faces u × v.
  void rect(glm::vec3 o, glm::vec3 u, glm::vec3 v) {
    const int nu = std::max(1, int(std::ceil(glm::length(u) / cell_))), nv = std::max(1, int(std::ceil(glm::length(v) / cell_)));
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        const glm::vec3 a = o + (float(i) / nu) * u + (float(j) / nv) * v;
        const glm::vec3 du = u / float(nu), dv = v / float(nv);
        tri(a, a + du, a + du + dv);
        tri(a, a + du + dv, a + dv);
      }
  }
  void box(glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 d = hi - lo;
    const glm::vec3 X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
    rect(lo, Y, X);               // -z
    rect(lo + Z, X, Y);           // +z
    rect(lo, Z, Y);               // -x
    rect(lo + X, Y, Z);           // +x
    rect(lo, X, Z);               // -y
    rect(lo + Y, Z, X);           // +y
  }

 private:
  void tri(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    Triangle t;
    t.p = {a, b, c};
    const glm::vec3 n = t.geometricNormal();
    t.n = {n, n, n};
    s_.triangles.push_back(t);
  }
  Scene& s_;
  float cell_;
};

}  // namespace

Scene makeHouse(const HouseParams& p, int* expectedCells, int* doors) {
  Scene s;
  s.materials.push_back({"default", glm::vec3(0.6f), glm::vec3(0.0f)});
  s.nodePaths.push_back("house");
  Builder wallB(s, p.wallCell), furnB(s, 1e9f);
  std::mt19937 rng(p.seed);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const float w = p.wall, H = p.height;
  const float lenX = p.roomsPerSide * p.roomX + (p.roomsPerSide + 1) * w;
  const float lenZ = 2 * p.roomZ + p.hallZ + 4 * w;
  wallB.box({0, -w, 0}, {lenX, 0, lenZ});
  wallB.box({0, H, 0}, {lenX, H + w, lenZ});
  // Outer walls.
  wallB.box({0, 0, 0}, {lenX, H, w});
  wallB.box({0, 0, lenZ - w}, {lenX, H, lenZ});
  wallB.box({0, 0, w}, {w, H, lenZ - w});
  wallB.box({lenX - w, 0, w}, {lenX, H, lenZ - w});
  int doorCount = 0;
  // The two long walls between the rooms and the hallway, one door per room.
  const float zHall0 = w + p.roomZ + w, zHall1 = zHall0 + p.hallZ;  // hallway interior z range
  for (float zw : {w + p.roomZ, zHall1}) {
    float x = w;
    for (int r = 0; r < p.roomsPerSide; ++r) {
      const float x0 = w + r * (p.roomX + w), dx = x0 + 0.5f * p.roomX - 0.5f * p.doorWidth + (U(rng) - 0.5f) * 2.0f;
      wallB.box({x, 0, zw}, {dx, H, zw + w});
      wallB.box({dx, p.doorHeight, zw}, {dx + p.doorWidth, H, zw + w});
      x = dx + p.doorWidth;
      ++doorCount;
    }
    wallB.box({x, 0, zw}, {lenX - w, H, zw + w});
  }
  // Cross walls between neighbouring rooms, every other one with a door.
  for (int side = 0; side < 2; ++side) {
    const float z0 = side == 0 ? w : zHall1 + w, z1 = z0 + p.roomZ;
    for (int r = 1; r < p.roomsPerSide; ++r) {
      const float xw = r * (p.roomX + w);
      if ((r + side) % 2 == 0) {
        const float dz = z0 + 0.5f * p.roomZ - 0.5f * p.doorWidth;
        wallB.box({xw, 0, z0}, {xw + w, H, dz});
        wallB.box({xw, 0, dz + p.doorWidth}, {xw + w, H, z1});
        wallB.box({xw, p.doorHeight, dz}, {xw + w, H, dz + p.doorWidth});
        ++doorCount;
      } else {
        wallB.box({xw, 0, z0}, {xw + w, H, z1});
      }
    }
  }
  // Furniture: boxes against the walls and tables with legs in the middle, clear of the doors.
  for (int side = 0; side < 2; ++side)
    for (int r = 0; r < p.roomsPerSide; ++r) {
      const glm::vec3 lo(w + r * (p.roomX + w), 0, side == 0 ? w : zHall1 + w);
      const glm::vec3 hi = lo + glm::vec3(p.roomX, H, p.roomZ);
      for (int k = 0; k < p.furniturePerRoom; ++k) {
        const int kind = k % 3;
        if (kind == 0) {  // a table: top and four legs
          const glm::vec2 size(0.6f + U(rng), 0.5f + 0.6f * U(rng));
          const glm::vec3 a(lo.x + 1.0f + U(rng) * (p.roomX - 2.0f - size.x), 0, lo.z + 1.0f + U(rng) * (p.roomZ - 2.0f - size.y));
          const float top = 0.45f + 0.3f * U(rng);
          furnB.box(a + glm::vec3(0, top, 0), a + glm::vec3(size.x, top + 0.04f, size.y));
          for (float fx : {0.0f, size.x - 0.05f})
            for (float fz : {0.0f, size.y - 0.05f}) furnB.box(a + glm::vec3(fx, 0, fz), a + glm::vec3(fx + 0.05f, top, fz + 0.05f));
        } else {  // a cabinet, bed or shelf against the north or south wall
          const glm::vec3 size(0.4f + 1.2f * U(rng), 0.3f + 1.7f * U(rng), 0.3f + 0.5f * U(rng));
          const float x = lo.x + 0.05f + U(rng) * (p.roomX - size.x - 0.1f);
          // Against the outer wall only, so the hallway doors stay clear.
          const float z = (side == 0) ? lo.z + 0.02f : hi.z - size.z - 0.02f;
          furnB.box({x, 0, z}, {x + size.x, size.y, z + size.z});
        }
      }
    }
  if (expectedCells) *expectedCells = 2 * p.roomsPerSide + 1;
  if (doors) *doors = doorCount;
  return s;
}

}  // namespace cpgi::bench
