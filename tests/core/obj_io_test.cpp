// OBJ + MTL: Kd albedo, Ke emission, object names as node paths and as cell tags.
#include <fstream>

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

}  // namespace
}  // namespace cpgi
