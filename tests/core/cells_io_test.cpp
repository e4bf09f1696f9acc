// Manual cells in a glTF (design.md §3): `cell:`, `portal:A:B`, `cellvolume:` nodes and their checks.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

// A unit floor square from x0 to x0 + 1 (normal +y), two triangles.
std::vector<float> floorAt(float x0) {
  return {x0, 0, 0, x0, 0, 1, x0 + 1, 0, 1, x0, 0, 0, x0 + 1, 0, 1, x0 + 1, 0, 0};
}

// The opening at x = 1 (y, z in [0, 1]) as 4 vertices and 2 triangles, wound either way.
int portalMesh(test::GlbBuilder& g, bool windPlusX, float bulge = 0.0f) {
  const std::vector<float> p = {1, 0, 0, 1, 1, 0, 1 + bulge, 1, 1, 1, 0, 1};
  return windPlusX ? g.addMesh(p, {0, 1, 2, 0, 2, 3}) : g.addMesh(p, {0, 2, 1, 0, 3, 2});
}

std::string errorOf(const test::GlbBuilder& g) {
  test::TempDir dir;
  g.writeGlb(dir / "cells.glb");
  try {
    loadScene(dir / "cells.glb");
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir / "cells.glb");
    return e.problem();
  }
  return "no error";
}

LoadedScene loadBuilt(const test::GlbBuilder& g) {
  test::TempDir dir;
  g.writeGlb(dir / "cells.glb");
  return loadScene(dir / "cells.glb");
}

TEST(CellsIo, CellsPortalsAndOrientationFromGeometry) {
  for (bool windPlusX : {true, false}) {
    test::GlbBuilder g;
    const int floorA = g.addNode({{"name", "floor"}, {"mesh", g.addMesh(floorAt(0))}}, false);
    g.addNode({{"name", "cell:A"}, {"children", {floorA}}});
    g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh(floorAt(1))}});
    g.addNode({{"name", "portal:A:B"}, {"mesh", portalMesh(g, windPlusX)}});
    const LoadedScene s = loadBuilt(g);
    EXPECT_EQ(s.scene.triangles.size(), 4u);  // the portal is not a scene triangle
    ASSERT_EQ(s.cells.cells.size(), 2u);
    EXPECT_EQ(s.cells.cells[0].name, "A");
    EXPECT_EQ(s.cells.cells[0].triangles.size(), 2u);
    EXPECT_EQ(s.cells.cells[1].triangles.size(), 2u);
    for (uint32_t t : s.cells.cells[0].triangles) EXPECT_LT(s.scene.triangles[t].centroid().x, 1.0f);
    EXPECT_EQ(s.scene.nodePaths[s.scene.triangles[s.cells.cells[0].triangles[0]].node], "cell:A/floor");
    ASSERT_EQ(s.cells.portals.size(), 1u);
    const PortalQuad& p = s.cells.portals[0];
    EXPECT_EQ(p.cellA, 0);
    EXPECT_EQ(p.cellB, 1);
    // From A (x < 1) into B (x > 1), whichever way the file winds it.
    EXPECT_NEAR(p.normal.x, 1.0f, 1e-6f) << "windPlusX " << windPlusX;
    EXPECT_NEAR(p.area, 1.0f, 1e-6f);
    // Corners go around the boundary: consecutive corners are unit edges apart.
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(glm::length(p.corners[(i + 1) % 4] - p.corners[i]), 1.0f, 1e-6f);
    EXPECT_TRUE(s.warnings.empty());
  }
}

TEST(CellsIo, PortalNamingAnUnknownCell) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "portal:A:X"}, {"mesh", portalMesh(g, true)}});
  EXPECT_EQ(errorOf(g), "portal:A:X: names a cell that does not exist");
}

TEST(CellsIo, NonPlanarPortal) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh(floorAt(1))}});
  g.addNode({{"name", "portal:A:B"}, {"mesh", portalMesh(g, true, 0.2f)}});
  const std::string problem = errorOf(g);
  EXPECT_EQ(problem.rfind("portal:A:B: not planar", 0), 0u) << problem;
}

TEST(CellsIo, PortalThatIsNotAQuad) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh(floorAt(1))}});
  g.addNode({{"name", "portal:A:B"}, {"mesh", g.addMesh({1, 0, 0, 1, 1, 0, 1, 0, 1})}});
  EXPECT_EQ(
      errorOf(g),
      "portal:A:B: a portal must be one quad (2 triangles, 4 vertices), found 1 triangles and 3 vertices");
  test::GlbBuilder two;  // two triangles that do not share an edge
  two.addNode({{"name", "cell:A"}, {"mesh", two.addMesh(floorAt(0))}});
  two.addNode({{"name", "cell:B"}, {"mesh", two.addMesh(floorAt(1))}});
  two.addNode({{"name", "portal:A:B"},
               {"mesh", two.addMesh({1, 0, 0, 1, 1, 0, 1, 0, 1, 1, 5, 5, 1, 6, 5, 1, 5, 6})}});
  EXPECT_NE(errorOf(two).find("portal:A:B: a portal must be one quad"), std::string::npos) << errorOf(two);
}

TEST(CellsIo, MalformedPortalName) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "portal:A"}, {"mesh", portalMesh(g, true)}});
  EXPECT_EQ(errorOf(g), "portal:A: a portal is named portal:CELL_A:CELL_B");
}

TEST(CellsIo, NestedCellIsAnErrorNamingTheNode) {
  test::GlbBuilder g;
  const int inner = g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh(floorAt(1))}}, false);
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}, {"children", {inner}}});
  EXPECT_EQ(errorOf(g), "cell:B: is inside cell:A (cells cannot nest)");
}

// A triangle cannot be in two cells: a cell owns its subtree and cells cannot nest, and a mesh used
// under two cells becomes two triangles, one in each.
TEST(CellsIo, InstancedMeshUnderTwoCellsGivesOneTriangleSetPerCell) {
  test::GlbBuilder g;
  const int mesh = g.addMesh(floorAt(0));
  const int inA = g.addNode({{"name", "shared"}, {"mesh", mesh}}, false);
  const int inB = g.addNode({{"name", "shared"}, {"mesh", mesh}, {"translation", {1, 0, 0}}}, false);
  g.addNode({{"name", "cell:A"}, {"children", {inA}}});
  g.addNode({{"name", "cell:B"}, {"children", {inB}}});
  g.addNode({{"name", "portal:A:B"}, {"mesh", portalMesh(g, true)}});
  const LoadedScene s = loadBuilt(g);
  ASSERT_EQ(s.scene.triangles.size(), 4u);
  const std::vector<int> owner = s.cells.cellOfTriangle(s.scene.triangles.size());
  EXPECT_EQ(std::count(owner.begin(), owner.end(), 0), 2);
  EXPECT_EQ(std::count(owner.begin(), owner.end(), 1), 2);
  EXPECT_TRUE(validateCells(s.scene, s.cells).errors.empty());
}

TEST(CellsIo, DisconnectedGraphAndUncelledTrianglesAreWarnings) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh(floorAt(1))}});
  g.addNode({{"name", "cell:C"}, {"mesh", g.addMesh(floorAt(5))}});
  g.addNode({{"name", "outside"}, {"mesh", g.addMesh(floorAt(9))}});
  g.addNode({{"name", "portal:A:B"}, {"mesh", portalMesh(g, true)}});
  const LoadedScene s = loadBuilt(g);
  EXPECT_EQ(s.cells.cells.size(), 3u);
  const auto has = [&](const std::string& w) {
    return std::find(s.warnings.begin(), s.warnings.end(), w) != s.warnings.end();
  };
  EXPECT_TRUE(has("the cell graph is not connected"));
  EXPECT_TRUE(has("cell:C: has no portal"));
  EXPECT_TRUE(has("2 triangles are in no cell"));
}

TEST(CellsIo, CellVolumesAndBlenderDuplicateSuffix) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh(floorAt(1))}});
  g.addNode({{"name", "portal:A:B"}, {"mesh", portalMesh(g, true)}});
  g.addNode({{"name", "portal:A:B.001"}, {"mesh", portalMesh(g, false)}, {"translation", {0, 2, 0}}});
  g.addNode({{"name", "cellvolume:B"}, {"mesh", g.addMesh(floorAt(1))}, {"translation", {0, 1, 0}}});
  const LoadedScene s = loadBuilt(g);
  EXPECT_EQ(s.scene.triangles.size(), 4u);
  ASSERT_EQ(s.cells.portals.size(), 2u);
  EXPECT_EQ(s.cells.portals[1].name, "portal:A:B.001");
  EXPECT_EQ(s.cells.portals[1].cellB, 1);
  EXPECT_NEAR(s.cells.portals[1].normal.x, 1.0f, 1e-6f);
  EXPECT_TRUE(s.cells.cells[0].volume.empty());
  ASSERT_EQ(s.cells.cells[1].volume.size(), 2u);
  EXPECT_NEAR(s.cells.cells[1].volume[0].p[0].y, 1.0f, 1e-6f);

  test::GlbBuilder bad;
  bad.addNode({{"name", "cell:A"}, {"mesh", bad.addMesh(floorAt(0))}});
  bad.addNode({{"name", "cellvolume:Z"}, {"mesh", bad.addMesh(floorAt(1))}});
  EXPECT_EQ(errorOf(bad),
            "cellvolume:Z: names a cell that does not exist (volumes define cells only in a "
            "scene without cell: and portal: nodes)");
}

TEST(CellsIo, VolumesAloneDefineTheCells) {
  // An IFC export's rooms: cellvolume: meshes, no cell: or portal: node. Each volume is a cell, with no
  // triangles yet (decomp::decomposeFromVolumes gives them), and no "in no cell" warning at load.
  test::GlbBuilder g;
  g.addNode({{"name", "walls"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "cellvolume:Hall"}, {"mesh", g.addMesh(floorAt(1))}});
  g.addNode({{"name", "cellvolume:Kitchen"}, {"mesh", g.addMesh(floorAt(2))}});
  g.addNode({{"name", "cellvolume:Hall.001"}, {"mesh", g.addMesh(floorAt(3))}});
  const LoadedScene s = loadBuilt(g);
  ASSERT_EQ(s.cells.cells.size(), 2u);
  EXPECT_EQ(s.cells.cells[0].name, "Hall");
  EXPECT_EQ(s.cells.cells[1].name, "Kitchen");
  EXPECT_EQ(s.cells.cells[0].volume.size(), 4u);  // Hall.001 is more of Hall (Blender's duplicate suffix)
  EXPECT_TRUE(s.cells.definedByVolumes());
  EXPECT_EQ(s.scene.triangles.size(), 2u);  // the volumes are not part of the scene
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("in no cell"), std::string::npos) << w;
  // A flat square is no closed volume: said once per volume.
  size_t open = 0;
  for (const std::string& w : s.warnings) open += w.find("is not a closed mesh") != std::string::npos;
  EXPECT_EQ(open, 2u);
}

TEST(CellsIo, PortalJoiningACellToItself) {
  test::GlbBuilder g;
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh(floorAt(0))}});
  g.addNode({{"name", "portal:A:A"}, {"mesh", portalMesh(g, true)}});
  EXPECT_EQ(errorOf(g), "portal:A:A: joins cell A to itself");
}

}  // namespace
}  // namespace cpgi
