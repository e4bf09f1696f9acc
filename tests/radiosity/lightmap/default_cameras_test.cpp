// Default cameras on the generated buildings (their own cameras removed): every eye stands in its room's
// empty space, at eye height above a floor of its cell, away from the walls; with the hand-made cells,
// with the automatic decomposition's and with no cells at all.
#include <cmath>

#include <gtest/gtest.h>

#include "decomposition/decompose.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/views.h"
#include "scenes/buildings.h"
#include "scenes/seed_scenes.h"

namespace cpgi {
namespace {

/// The room (by index in b.rooms) whose boxes hold `p`, -1 for none.
int roomHolding(const Building& b, glm::vec3 p) {
  for (size_t r = 0; r < b.rooms.size(); ++r)
    for (const Box3& box : b.rooms[r].boxes)
      if (box.contains(p)) return int(r);
  return -1;
}

/// Checks what every default camera must satisfy whatever its cells: a floor facing up straight below the
/// eye, between 0.5 and 1.6 m down (1.6 unless the ceiling is low), owned by `cell` (unless -1); no surface
/// within 0.25 m around the eye; a unit view direction close to horizontal.
void expectStandsOnFloor(const RayScene& rays, const Scene& scene, const std::vector<int>& triangleCell,
                         const Camera& cam, int cell) {
  SCOPED_TRACE(cam.name);
  const RayScene::Hit below = rays.intersect(cam.position, {0, -1, 0});
  ASSERT_TRUE(below);
  EXPECT_GT(scene.triangles[size_t(below.triangle)].geometricNormal().y, 0.7f);
  EXPECT_GE(below.t, 0.5f);
  EXPECT_LE(below.t, 1.6f + 1e-3f);
  if (cell >= 0) {
    EXPECT_EQ(triangleCell[size_t(below.triangle)], cell);
  }
  for (int k = 0; k < 16; ++k) {
    const float a = float(k) * 3.14159265f / 8.0f;
    const RayScene::Hit h = rays.intersect(cam.position, {std::cos(a), 0.0f, std::sin(a)});
    if (h) {
      EXPECT_GT(h.t, 0.25f) << "direction " << k;
    }
  }
  EXPECT_NEAR(glm::length(cam.forward), 1.0f, 1e-5f);
  EXPECT_LT(std::abs(cam.forward.y), 0.2f);
}

TEST(DefaultCameras, OnePerRoomOfEveryBuildingInsideItsRoomAboveItsFloor) {
  for (const std::string& name : buildingNames()) {
    SCOPED_TRACE(name);
    Building b = makeBuilding(name);
    Scene& scene = b.seed.scene;
    scene.cameras.clear();
    const RayScene rays(scene);
    const CellGraph& cells = b.seed.cells;
    const std::vector<int> triangleCell = cells.cellOfTriangle(scene.triangles.size());
    const std::vector<Camera> cameras = defaultCameras(rays, scene, cells);
    ASSERT_EQ(cameras.size(), b.rooms.size());  // every cell but "outside"
    for (size_t r = 0; r < b.rooms.size(); ++r) {
      const Camera& cam = cameras[r];
      EXPECT_EQ(cam.name, b.rooms[r].name);
      EXPECT_EQ(roomHolding(b, cam.position), int(r))
          << cam.name << " at " << cam.position.x << "," << cam.position.y << "," << cam.position.z;
      expectStandsOnFloor(rays, scene, triangleCell, cam, cells.findCell(cam.name));
    }
  }
}

// The cameras a bake of a generated building renders (it brings none of its own, so the defaults) stand in
// empty space: the furnished house's kitchen once had its camera inside the fridge, and rendered black.
TEST(DefaultCameras, GeneratedBuildingsViewFromEmptySpace) {
  for (const std::string& name : buildingNames()) {
    SCOPED_TRACE(name);
    const Building b = makeBuilding(name);
    EXPECT_TRUE(b.seed.scene.cameras.empty());
    const RayScene rays(b.seed.scene);
    for (const Camera& cam : defaultCameras(rays, b.seed.scene, b.seed.cells)) {
      int backFaces = 0;
      for (int k = 0; k < 27; ++k) {  // the directions to a cube's faces, edges and corners
        const glm::vec3 d(float(k % 3) - 1.0f, float(k / 3 % 3) - 1.0f, float(k / 9) - 1.0f);
        if (d == glm::vec3(0.0f)) continue;
        const RayScene::Hit hit = rays.intersect(cam.position, glm::normalize(d));
        backFaces +=
            hit && glm::dot(b.seed.scene.triangles[size_t(hit.triangle)].geometricNormal(), d) > 0.0f;
      }
      EXPECT_LE(backFaces, 2) << cam.name << " sees the inside of something in " << backFaces
                              << " of 26 directions";
    }
  }
}

/// The share of a grid of rays across the camera's field of view whose first surface is one of `cell`'s.
float shareSeeingCell(const RayScene& rays, const std::vector<int>& triangleCell, const Camera& cam,
                      int cell) {
  const glm::vec3 side = glm::normalize(glm::cross(cam.forward, cam.up));
  const float h = std::tan(0.5f * cam.yfov), w = h * cam.aspect;
  int own = 0, n = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 7; ++j) {
      const float x = (float(i) / 8.0f * 2.0f - 1.0f) * w * 0.9f,
                  y = (float(j) / 6.0f * 2.0f - 1.0f) * h * 0.9f;
      const RayScene::Hit hit =
          rays.intersect(cam.position, glm::normalize(cam.forward + x * side + y * cam.up));
      own += hit && triangleCell[size_t(hit.triangle)] == cell;
      ++n;
    }
  return float(own) / float(n);
}

// A camera named after a room shows that room: standing just inside a door and looking through it (each
// seed room's camera once looked into the next room) is what a user choosing "in A" does not want.
TEST(DefaultCameras, EachLooksAtItsOwnRoomNotThroughADoor) {
  std::vector<std::pair<std::string, SeedScene>> scenes;
  for (int level : {1, 2, 3}) scenes.emplace_back("seed" + std::to_string(level), makeSeedScene(level));
  for (const std::string& name : buildingNames()) scenes.emplace_back(name, makeBuilding(name).seed);
  for (auto& [name, seed] : scenes) {
    SCOPED_TRACE(name);
    seed.scene.cameras.clear();
    const RayScene rays(seed.scene);
    const std::vector<int> triangleCell = seed.cells.cellOfTriangle(seed.scene.triangles.size());
    for (const Camera& cam : defaultCameras(rays, seed.scene, seed.cells)) {
      const float share = shareSeeingCell(rays, triangleCell, cam, seed.cells.findCell(cam.name));
      EXPECT_GE(share, 0.6f) << cam.name << " sees its own cell in " << share << " of its view";
    }
  }
}

TEST(DefaultCameras, WithoutCellsOneOverviewInsideARoomOfTheHouse) {
  // Terrain or a roof must not decide: the eye stands in a room, under a roof.
  for (const char* name : {"house-open", "house-stair", "house-gallery", "porch"}) {
    SCOPED_TRACE(name);
    Building b = makeBuilding(name);
    Scene& scene = b.seed.scene;
    scene.cameras.clear();
    const RayScene rays(scene);
    const std::vector<Camera> cameras = defaultCameras(rays, scene, CellGraph{});
    ASSERT_EQ(cameras.size(), 1u);
    EXPECT_EQ(cameras[0].name, "overview");
    EXPECT_GE(roomHolding(b, cameras[0].position), 0);
    EXPECT_TRUE(rays.intersect(cameras[0].position, {0, 1, 0}));
    expectStandsOnFloor(rays, scene, {}, cameras[0], -1);
  }
}

TEST(DefaultCameras, OnePerCellOfTheAutomaticDecompositionInsideThatCell) {
  const Building b = makeBuilding("house-stair");
  decomp::DecomposeParams params;
  params.voxelSize = 0.1;
  Context ctx;
  decomp::Decomposition d = decomp::decompose(b.seed.scene, params, ctx);
  d.scene.cameras.clear();
  const RayScene rays(d.scene);
  const std::vector<int> triangleCell = d.graph.cellOfTriangle(d.scene.triangles.size());
  const std::vector<Camera> cameras = defaultCameras(rays, d.scene, d.graph);
  const size_t rooms = d.graph.cells.size() - (d.outsideCell >= 0 ? 1 : 0);
  ASSERT_EQ(cameras.size(), rooms);
  ASSERT_GE(rooms, b.rooms.size() - 1);
  for (const Camera& cam : cameras) {
    const int cell = d.graph.findCell(cam.name);
    ASSERT_GE(cell, 0) << cam.name;
    // In the cell's own empty voxels, and in a room of the house.
    EXPECT_EQ(d.voxelCell[d.frame.index(d.frame.voxelOf(cam.position))], cell) << cam.name;
    EXPECT_GE(roomHolding(b, cam.position), 0) << cam.name;
    expectStandsOnFloor(rays, d.scene, triangleCell, cam, cell);
  }
}

}  // namespace
}  // namespace cpgi
