// A scene not in metres (issue 46): its storey height says so in one warning naming the likely unit and
// the --scale that fixes it, and LoadOptions::scale (--scale) makes it metres as it loads.
#include "core/units.h"

#include <string>

#include <gtest/gtest.h>

#include "core/scene_io.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

void addQuad(Scene& s, glm::vec3 o, glm::vec3 u, glm::vec3 v) {
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  Triangle a, b;
  a.p = {o, o + u, o + u + v};
  b.p = {o, o + u + v, o + v};
  a.n = b.n = {n, n, n};
  s.triangles.push_back(a);
  s.triangles.push_back(b);
}

// Two rooms of w × d, `height` tall (y up), side by side, each a floor (normal +y) and a ceiling (−y), a
// lamp light at head height and a camera: a house in whatever unit `height` is given in.
// A hall `w` × `d` with its sky `sky` up, in units of `unit` metres: a game level's open arena.
Scene hallUnderASky(float unit, float w, float d, float sky) {
  Scene s;
  s.materials = {Material{"grey", glm::vec3(0.5f), glm::vec3(0.0f)}};
  addQuad(s, {0, 0, 0}, {0, 0, d * unit}, {w * unit, 0, 0});           // the floor
  addQuad(s, {0, sky * unit, 0}, {w * unit, 0, 0}, {0, 0, d * unit});  // the sky
  return s;
}

Scene twoRooms(float w, float d, float height) {
  Scene s;
  s.materials = {Material{"grey", glm::vec3(0.5f), glm::vec3(0.0f)}};
  s.nodePaths = {"house"};
  for (int r = 0; r < 2; ++r) {
    const glm::vec3 o(float(r) * w, 0.0f, 0.0f);
    addQuad(s, o, {0, 0, d}, {w, 0, 0});
    addQuad(s, o + glm::vec3(0, height, 0), {w, 0, 0}, {0, 0, d});
  }
  PunctualLight l;
  l.position = glm::vec3(0.5f * w, 0.6f * height, 0.5f * d), l.intensity = glm::vec3(1.0f),
  l.range = 2.0f * w;
  s.lights.push_back(l);
  s.cameras.push_back(Camera{"view", glm::vec3(w, 0.5f * height, 2.0f * d), glm::vec3(0, 0, -1),
                             glm::vec3(0, 1, 0), 0.9f, 1.5f});
  return s;
}

TEST(Units, MetresPassFeetInchesCentimetresAndMillimetresAreNamed) {
  EXPECT_EQ(checkUnits(twoRooms(4.0f, 5.0f, 2.6f)).warning, "");
  EXPECT_NEAR(checkUnits(twoRooms(4.0f, 5.0f, 2.6f)).storeyHeight, 2.6, 1e-3);
  // Storeys of 4 m in feet (13 ft), 2.8 m in inches, centimetres and millimetres, a game's tall arena.
  const struct {
    float metres, metresPerUnit;
    const char* flag;
  } cases[] = {{4.0f, 0.3048f, "--scale 0.3048"},
               {2.8f, 0.0254f, "--scale 0.0254"},
               {2.8f, 0.01f, "--scale 0.01"},
               {2.8f, 0.001f, "--scale 0.001"},
               {22.0f, 0.0254f, "--scale 0.0254"}};  // an arena 22 m tall in inches: 866 units, not mm
  for (const auto& c : cases) {
    const float k = 1.0f / c.metresPerUnit;
    const UnitsCheck u = checkUnits(twoRooms(4.0f * k, 5.0f * k, c.metres * k));
    EXPECT_NEAR(u.storeyHeight, c.metres * k, 1e-3 * k);
    EXPECT_FLOAT_EQ(float(u.scale), c.metresPerUnit) << u.warning;
    EXPECT_NE(u.warning.find(c.flag), std::string::npos) << u.warning;
    EXPECT_EQ(u.warning.find('\n'), std::string::npos);
  }
  // An open landscape (no ceiling over its floors) cannot say.
  Scene open;
  open.materials = {Material{"grey", glm::vec3(0.5f), glm::vec3(0.0f)}};
  addQuad(open, {0, 0, 0}, {0, 0, 500}, {500, 0, 0});
  EXPECT_EQ(checkUnits(open).storeyHeight, 0.0);
  EXPECT_EQ(checkUnits(open).warning, "");
}

// A game level in metres under its sealed sky box: a hall 40 m tall over 90 % of the floors, a corridor 3 m
// tall beside it. Its median says feet; its corridor, a person's height in metres, says metres. The same
// level in inches is still told.
TEST(Units, ALevelInMetresUnderATallSkyIsNotTakenForFeet) {
  auto level = [](float unit) {
    Scene s = hallUnderASky(unit, 9.0f, 10.0f, 40.0f);
    addQuad(s, {9 * unit, 0, 0}, {0, 0, 10 * unit}, {1 * unit, 0, 0});         // the corridor's floor
    addQuad(s, {9 * unit, 3 * unit, 0}, {1 * unit, 0, 0}, {0, 0, 10 * unit});  // its ceiling
    return s;
  };
  const UnitsCheck metres = checkUnits(level(1.0f));
  EXPECT_NEAR(metres.storeyHeight, 40.0, 1e-3);
  EXPECT_EQ(metres.warning, "");
  const UnitsCheck inches = checkUnits(level(1.0f / 0.0254f));
  EXPECT_NE(inches.warning.find("--scale 0.0254"), std::string::npos) << inches.warning;
}

// An open arena in metres under its sky box 35 m up with no corridor at all (OpenArena's islanddm, oa_shouse,
// czest1tourney): storeys of 35 would be 11 m in feet, no building's storey, so no line; the same arena in
// Quake units is still told, and so is a house of 13 ft storeys in feet.
TEST(Units, AnArenaUnderASkyTensOfMetresUpIsNotTakenForFeet) {
  auto arena = [](float unit) { return hallUnderASky(unit, 60.0f, 60.0f, 35.0f); };
  const UnitsCheck metres = checkUnits(arena(1.0f));
  EXPECT_NEAR(metres.storeyHeight, 35.0, 1e-3);
  EXPECT_EQ(metres.warning, "");
  const UnitsCheck quake = checkUnits(arena(1.0f / 0.03f));
  EXPECT_NE(quake.warning.find("--scale 0.0254"), std::string::npos) << quake.warning;
  const UnitsCheck feet = checkUnits(twoRooms(4.0f / 0.3048f, 5.0f / 0.3048f, 13.0f));
  EXPECT_NE(feet.warning.find("feet: --scale 0.3048"), std::string::npos) << feet.warning;
  // A storey of 19 ft (5.8 m) is still a storey: the feet band's top.
  EXPECT_NE(checkUnits(twoRooms(13.0f, 16.0f, 19.0f)).warning.find("--scale 0.3048"), std::string::npos);
}

// A stair of `count` steps rising `rise` each over treads `tread` deep and `width` wide, its foot at `at`
// (treads face up, risers face −z, towards the foot), in the scene's units.
void addStair(Scene& s, glm::vec3 at, int count, float rise, float tread, float width) {
  for (int k = 0; k < count; ++k) {
    const glm::vec3 o = at + glm::vec3(0.0f, float(k) * rise, float(k) * tread);
    addQuad(s, o, {0, rise, 0}, {width, 0, 0});                           // the riser
    addQuad(s, o + glm::vec3(0, rise, 0), {0, 0, tread}, {width, 0, 0});  // the tread
  }
}

// A game level sealed under its sky box, in units of `unit` metres: an arena of 60 × 60 m under a sky
// `sky` m up (the floor round the stair), with a stair of 0.48 m steps (Quake's 16 units) up to a
// gallery 7.7 m under the sky along one side.
Scene sealedArena(float unit, float sky) {
  Scene s = hallUnderASky(unit, 60.0f, 60.0f, sky);
  addQuad(s, {0, (sky - 7.7f) * unit, 50 * unit}, {0, 0, 10 * unit}, {60 * unit, 0, 0});  // the gallery
  addStair(s, {20 * unit, 0, 10 * unit}, 12, 0.48f * unit, 0.64f * unit, 4.0f * unit);
  return s;
}

// OpenArena's cbctf1 and am_spacecont are sealed under a sky 104–111 m up, pxlfan under one 15 m up with
// nothing lower than 7.7 m: by their median they read as inches and feet. Their steps (0.48 m) and their
// storeys of many heights say metres; the same levels in Quake units are told, with the --scale that fixes
// them, and a house in feet (one storey height, no step) still is.
TEST(Units, ASealedLevelInMetresIsToldByItsStepsAndStoreysNotItsSky) {
  for (const float sky : {15.0f, 104.0f}) {
    const UnitsCheck metres = checkUnits(sealedArena(1.0f, sky));
    EXPECT_NEAR(metres.storeyHeight, sky, 1e-3 * sky);
    EXPECT_EQ(metres.warning, "") << "sky " << sky << " m";
    const UnitsCheck quake = checkUnits(sealedArena(1.0f / 0.03f, sky));
    EXPECT_NE(quake.warning.find("--scale 0.0254"), std::string::npos)
        << "sky " << sky << ": " << quake.warning;
  }
  EXPECT_NEAR(checkUnits(sealedArena(1.0f, 104.0f)).stepHeight, 0.48, 1e-3);
  EXPECT_NEAR(checkUnits(sealedArena(1.0f, 15.0f)).lowStoreyHeight, 7.7, 1e-3);
  const UnitsCheck feet = checkUnits(twoRooms(4.0f / 0.3048f, 5.0f / 0.3048f, 13.0f));
  EXPECT_NE(feet.warning.find("feet: --scale 0.3048"), std::string::npos) << feet.warning;
}

// A daylit level open to the sky has no storey to measure; its steps alone tell Quake units from metres.
TEST(Units, AnOpenLevelInQuakeUnitsIsToldByItsSteps) {
  auto open = [](float unit) {
    Scene s;
    s.materials = {Material{"grey", glm::vec3(0.5f), glm::vec3(0.0f)}};
    addQuad(s, {0, 0, 0}, {0, 0, 60 * unit}, {60 * unit, 0, 0});
    addStair(s, {20 * unit, 0, 10 * unit}, 12, 0.48f * unit, 0.64f * unit, 4.0f * unit);
    return s;
  };
  EXPECT_EQ(checkUnits(open(1.0f)).warning, "");
  const UnitsCheck quake = checkUnits(open(1.0f / 0.03f));
  EXPECT_NEAR(quake.stepHeight, 16.0, 1e-2);
  EXPECT_NE(quake.warning.find("the steps are 16 units tall"), std::string::npos) << quake.warning;
  EXPECT_NE(quake.warning.find("--scale 0.0254"), std::string::npos) << quake.warning;
  // A town of 4 m blocks in metres on 300 × 300 m of ground rises 4 m a "step" too: not told.
  Scene town;
  town.materials = {Material{"grey", glm::vec3(0.5f), glm::vec3(0.0f)}};
  addQuad(town, {0, 0, 0}, {0, 0, 300}, {300, 0, 0});
  for (int k = 0; k < 20; ++k) {
    const glm::vec3 o(float(k % 5) * 60.0f + 10.0f, 0.0f, float(k / 5) * 60.0f + 10.0f);
    addQuad(town, o + glm::vec3(0, 4, 0), {0, 0, 10}, {10, 0, 0});  // the roof, facing up
    addQuad(town, o, {10, 0, 0}, {0, 4, 0});                        // four walls
    addQuad(town, o + glm::vec3(0, 0, 10), {0, 4, 0}, {10, 0, 0});
    addQuad(town, o, {0, 4, 0}, {0, 0, 10});
    addQuad(town, o + glm::vec3(10, 0, 0), {0, 0, 10}, {0, 4, 0});
  }
  EXPECT_EQ(checkUnits(town).warning, "");
}

TEST(Units, AHouseInCentimetresIsToldAndScaleMakesItMetres) {
  test::TempDir dir;
  const std::string file = dir / "house_cm.glb";
  writeGltf(file, twoRooms(400.0f, 500.0f, 270.0f));
  const LoadedScene asIs = loadScene(file);
  int told = 0;
  for (const std::string& w : asIs.warnings)
    if (w.find("units:") == 0) {
      ++told;
      EXPECT_NE(w.find("270 units tall"), std::string::npos) << w;
      EXPECT_NE(w.find("centimetres: --scale 0.01"), std::string::npos) << w;
      EXPECT_NE(w.find("--scale 0.0254"), std::string::npos) << w;  // or a Quake map's inches
    }
  EXPECT_EQ(told, 1);

  LoadOptions metres;
  metres.scale = 0.01;
  const LoadedScene scaled = loadScene(file, metres);
  for (const std::string& w : scaled.warnings) EXPECT_EQ(w.find("units:"), std::string::npos) << w;
  const glm::vec3 size = scaled.scene.bounds().size();
  EXPECT_NEAR(size.x, 8.0f, 1e-4f);
  EXPECT_NEAR(size.y, 2.7f, 1e-4f);
  EXPECT_NEAR(size.z, 5.0f, 1e-4f);
  ASSERT_EQ(scaled.scene.lights.size(), 1u);
  EXPECT_NEAR(scaled.scene.lights[0].position.y, 0.6f * 2.7f, 1e-4f);
  EXPECT_NEAR(scaled.scene.lights[0].range, 8.0f, 1e-4f);
  EXPECT_EQ(scaled.scene.lights[0].intensity, asIs.scene.lights[0].intensity);  // W/sr: no length in it
  ASSERT_EQ(scaled.scene.cameras.size(), 1u);
  EXPECT_NEAR(scaled.scene.cameras[0].position.z, 10.0f, 1e-4f);
  EXPECT_NEAR(scaled.scene.triangles[0].area(), asIs.scene.triangles[0].area() * 1e-4f,
              1e-6f * asIs.scene.triangles[0].area());
}

}  // namespace
}  // namespace cpgi
