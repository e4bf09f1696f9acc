// OBJ + MTL: Kd albedo, Ke emission, object names as node paths and as cell tags.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

void write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

TEST(ObjIo, MaterialsObjectsAndCells) {
  test::TempDir dir;
  write(dir / "rooms.mtl",
        "newmtl wall\nKd 0.7 0.6 0.5\n"
        "newmtl lamp\nKd 0.8 0.8 0.8\nKe 100 90 80\n");
  write(dir / "rooms.obj",
        "mtllib rooms.mtl\n"
        "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\n"  // 1-4: floor of A
        "v 1 0 0\nv 1 0 1\nv 2 0 1\nv 2 0 0\n"  // 5-8: floor of B
        "v 1 0 0\nv 1 1 0\nv 1 1 1\nv 1 0 1\n"  // 9-12: the opening at x = 1
        "vn 0 1 0\n"
        "o loose\nf 1 3 2\n"  // before any usemtl: the default grey
        "o cell:A\nusemtl wall\nf 1//1 2//1 3//1 4//1\n"
        "o cell:B\nusemtl lamp\nf 5 6 7 8\n"
        "o portal:A:B\nf 9 10 11 12\n");
  const LoadedScene s = loadScene(dir / "rooms.obj");
  ASSERT_EQ(s.scene.triangles.size(), 5u);  // two quads triangulated, the loose triangle; not the portal
  ASSERT_EQ(s.cells.cells.size(), 2u);
  EXPECT_EQ(s.cells.cells[0].triangles.size(), 2u);
  EXPECT_EQ(s.cells.cells[1].triangles.size(), 2u);
  const Triangle& a = s.scene.triangles[s.cells.cells[0].triangles[0]];
  const Triangle& b = s.scene.triangles[s.cells.cells[1].triangles[0]];
  EXPECT_EQ(s.scene.materials[a.material].name, "wall");
  EXPECT_LE(glm::length(s.scene.materials[a.material].albedo - glm::vec3(0.7f, 0.6f, 0.5f)), 1e-6f);
  EXPECT_LE(glm::length(s.scene.materials[b.material].emission - glm::vec3(100, 90, 80)), 1e-4f);
  EXPECT_EQ(s.scene.nodePaths[a.node], "cell:A");
  EXPECT_LE(glm::length(a.n[0] - glm::vec3(0, 1, 0)), 1e-6f);
  EXPECT_LE(glm::length(b.n[0] - glm::vec3(0, 1, 0)), 1e-6f);  // no vn: the geometric normal
  ASSERT_EQ(s.cells.portals.size(), 1u);
  EXPECT_NEAR(s.cells.portals[0].normal.x, 1.0f, 1e-6f);
  EXPECT_NEAR(s.cells.portals[0].area, 1.0f, 1e-6f);
  // The loose triangle is in no cell.
  const Triangle& loose = s.scene.triangles.front();
  EXPECT_EQ(s.scene.nodePaths[loose.node], "loose");
  EXPECT_LE(glm::length(s.scene.materials[loose.material].albedo - glm::vec3(0.5f)), 1e-6f);
  EXPECT_EQ(s.warnings, std::vector<std::string>{"1 triangles are in no cell"});
}

// The seal (design.md §3): solids the decomposition voxelizes and the bake never draws, read apart from the
// faces and scaled with them; a decomposition's cells.glb keeps it, a bake's glb does not.
TEST(ObjIo, ASealIsReadApartFromTheFacesAndWrittenOnlyWhenAsked) {
  test::TempDir dir;
  write(dir / "level.obj",
        "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\n"  // a floor facing up
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"  // a tetrahedron under it
        "o world\nf 1 2 3 4\n"
        "o seal:brushes\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n");
  LoadOptions options;
  options.scale = 2.0;
  const LoadedScene s = loadScene(dir / "level.obj", options);
  ASSERT_EQ(s.scene.triangles.size(), 2u);
  ASSERT_EQ(s.scene.seal.size(), 4u);
  float highest = 0.0f;
  for (const Triangle& t : s.scene.seal)
    for (const glm::vec3& p : t.p) highest = std::max(highest, p.y);
  EXPECT_FLOAT_EQ(highest, 2.0f);  // scaled as the faces are

  GltfWriteOptions bake;  // a bake's glb: no seal
  writeGltf(dir / "baked.glb", s.scene, bake);
  EXPECT_TRUE(loadScene(dir / "baked.glb").scene.seal.empty());
  GltfWriteOptions cells;
  cells.keepSeal = true;
  writeGltf(dir / "cells.glb", s.scene, cells);
  const LoadedScene back = loadScene(dir / "cells.glb");
  EXPECT_EQ(back.scene.triangles.size(), 2u);
  EXPECT_EQ(back.scene.seal.size(), 4u);
}

TEST(ObjIo, MissingFileAndEmptyObj) {
  test::TempDir dir;
  try {
    loadScene(dir / "nothing.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "no such file");
  }
  write(dir / "empty.obj", "# nothing\nv 0 0 0\n");
  try {
    loadScene(dir / "empty.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "the scene has no triangles");
  }
}

// Issue 15, defect 8: a 100,000-vertex polygon took 27 CPU-s to triangulate (the cost grows with its
// square). Refused before tinyobjloader sees it, naming its line; a circle of 64 still loads.
TEST(ObjIo, HugePolygonIsRefusedBeforeTriangulation) {
  test::TempDir dir;
  auto polygon = [](int n) {
    std::string text;
    for (int i = 0; i < n; ++i)
      text += "v " + std::to_string(std::cos(6.2831853 * i / n)) + " " +
              std::to_string(std::sin(6.2831853 * i / n)) + " 0\n";
    text += "f";
    for (int i = 1; i <= n; ++i) text += " " + std::to_string(i);
    return text + "\n";
  };
  write(dir / "circle.obj", polygon(64));
  EXPECT_EQ(loadScene(dir / "circle.obj").scene.triangles.size(), 62u);
  write(dir / "huge.obj", "# a disc\n" + polygon(100000));
  try {
    loadScene(dir / "huge.obj");
    FAIL() << "a 100,000-vertex face was triangulated";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem().rfind("line 100002: a face of 100000 vertices; faces this large", 0), 0u)
        << e.problem();
  }
}

// Finite corners too far apart for float products: refused by name, not as "the scene emits -nan W".
TEST(ObjIo, TriangleWhoseAreaOverflowsIsRefused) {
  test::TempDir dir;
  write(dir / "vast.obj", "v 3e38 0 0\nv -3e38 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    loadScene(dir / "vast.obj");
    FAIL() << "a triangle of infinite area was loaded";
  } catch (const InputError& e) {
    // Positions past 1e6 m are refused first (issue 49, item 5), long before the area overflows.
    EXPECT_NE(e.problem().find(": a vertex lies 3e+38 m from the origin, beyond the 1e6 m cpgi handles"),
              std::string::npos)
        << e.problem();
  }
}

}  // namespace
}  // namespace cpgi
