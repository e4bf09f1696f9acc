#include "scenes/stability_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/quads.h"
#include "scenes/buildings.h"

namespace cpgi {
namespace {

TEST(StabilityScenes, SpotThroughDoorHasTwoCellsOnePortalAndA50WattLamp) {
  const SeedScene s = makeSpotThroughDoor();
  ASSERT_EQ(s.cells.cells.size(), 2u);
  ASSERT_EQ(s.cells.portals.size(), 1u);
  const CellValidation v = validateCells(s.scene, s.cells);
  EXPECT_TRUE(v.errors.empty());
  EXPECT_TRUE(v.warnings.empty());
  EXPECT_NEAR(s.scene.emittedPower().r, 50.0f, 1e-3f);
  EXPECT_NEAR(s.cells.portals[0].normal.x, 1.0f, 1e-6f);
  // The emitter faces the door.
  for (const Triangle& t : s.scene.triangles)
    if (s.scene.materials[t.material].isEmitter()) {
      EXPECT_NEAR(t.geometricNormal().x, 1.0f, 1e-6f);
    }
  EXPECT_EQ(findQuads(s.scene).looseTriangles(), 0u);
}

TEST(StabilityScenes, ThinWallRoomsShareAWallAndHaveNoPortal) {
  for (float thickness : {0.0f, 0.05f}) {
    const SeedScene s = makeThinWall(thickness);
    ASSERT_EQ(s.cells.cells.size(), 2u);
    EXPECT_TRUE(s.cells.portals.empty());
    // B's west wall sits `thickness` behind A's east wall, facing the other way.
    int aEast = 0, bWest = 0;
    for (const Triangle& t : s.scene.triangles) {
      const glm::vec3 n = t.geometricNormal();
      const bool atA = std::abs(t.p[0].x - 4.0f) < 1e-6f && std::abs(t.p[2].x - 4.0f) < 1e-6f;
      const bool atB =
          std::abs(t.p[0].x - (4.0f + thickness)) < 1e-6f && std::abs(t.p[2].x - (4.0f + thickness)) < 1e-6f;
      aEast += atA && n.x < -0.999f;
      bWest += atB && n.x > 0.999f;
    }
    EXPECT_EQ(aEast, 2);
    EXPECT_EQ(bWest, 2);
  }
  EXPECT_THROW(makeThinWall(-1.0f), std::invalid_argument);
}

TEST(StabilityScenes, PunctualLightRoomsAreLitByTheirLampAlone) {
  for (const SeedScene& s : {makePointLightRooms(), makeSpotLightThroughDoor()}) {
    EXPECT_EQ(s.scene.emittedPower(), glm::vec3(0.0f));
    ASSERT_EQ(s.scene.lights.size(), 1u);
    EXPECT_TRUE(s.scene.hasLight());
    const PunctualLight& l = s.scene.lights[0];
    EXPECT_LT(l.position.x, 4.0f);  // in room A
    EXPECT_EQ(s.cells.cells.size(), 2u);
    EXPECT_EQ(s.cells.portals.size(), 1u);
  }
  // The spot aims through the door (z in [1.5, 2.5], y below 2.1) along +x.
  const PunctualLight spot = makeSpotLightThroughDoor().scene.lights[0];
  EXPECT_EQ(spot.kind, PunctualLight::Kind::Spot);
  EXPECT_EQ(spot.direction, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_GT(spot.position.z, 1.5f);
  EXPECT_LT(spot.position.z, 2.5f);
  EXPECT_LT(spot.position.y, 2.1f);
}

TEST(StabilityScenes, EveryBuiltinNameBuilds) {
  for (const std::string& name : builtinSceneNames())
    EXPECT_FALSE(makeBuiltinScene(name).scene.triangles.empty());
  EXPECT_THROW(makeBuiltinScene("nope"), std::invalid_argument);
  // `generate --help` lists these names: every building must be among them.
  for (const std::string& building : buildingNames())
    EXPECT_NE(std::find(builtinSceneNames().begin(), builtinSceneNames().end(), building),
              builtinSceneNames().end())
        << building;
}

}  // namespace
}  // namespace cpgi
