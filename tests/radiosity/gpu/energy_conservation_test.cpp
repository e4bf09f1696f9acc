// No shot may deliver more power than it carries, nor less than its eyes see covered (design.md §5,
// "Energy"): the solver's bookkeeping (EnergyTotals::created, ::worstShotGain) checks it on every shot.
// These scenes are where the solver used to make light up (a lamp near the surface it faces, light
// through a door at a coarse item buffer) or lose it in a closed room (columns beside the drawn eyes, a
// zero-thickness partition) (issue 11).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "scenes/stability_scenes.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;

SolveResult solve(const Scene& scene, float density, const SolverParams& params,
                  LightmapAtlas* atlasOut = nullptr) {
  Context ctx;
  EglContext context(ctx);
  AtlasParams atlasParams;
  atlasParams.density = density;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), atlasParams, ctx);
  SolveResult r = solveProgressive(scene, atlas, params, context, ctx);
  if (atlasOut) *atlasOut = atlas;
  return r;
}

void expectNoEnergyCreated(const SolveResult& r) {
  const EnergyTotals& e = r.energy;
  // worstShotGain may exceed 1 (a drawn eye sees more than its region): such a shot is scaled back.
  EXPECT_LE(e.created, 2e-3 * e.emitted);
  EXPECT_LE(e.absorbed + e.unshot, e.emitted * (1.0 + 2e-3));
  EXPECT_GE(e.escaped(), -2e-3 * e.emitted);
  // Per shot the solver allows 2e-3 for float sums and emission lobes; on main these scenes reached -5 %.
  for (size_t i = 1; i < r.history.size(); ++i)
    EXPECT_GE(r.history[i].escaped(), -2e-3 * e.emitted) << "shot " << i;
}

// A 1 m² lamp facing a ceiling `gap` metres above it, in a closed 2 m box: the shots between the lamp
// and the ceiling are where the near-field form factor and the item buffer's grazing views act.
Scene lampUnderCeiling(float gap) {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.5f));
  const uint32_t lamp = addMaterial(s, glm::vec3(0.5f), glm::vec3(30.0f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f), grey);
  const float y = 2.0f - gap;
  addRect(s, {0.5f, y, 0.5f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, lamp);  // normal +y
  return s;
}

TEST(EnergyConservation, LampNearTheCeilingCreatesNoLight) {
  for (float gap : {0.3f, 0.1f}) {
    SCOPED_TRACE(gap);
    SolverParams p;
    p.unshotFraction = 1e-3;
    expectNoEnergyCreated(solve(lampUnderCeiling(gap), 10.0f, p));
  }
}

// Two rooms joined by a door, the lamp in one: at a coarse item buffer the thesis's 3×3 test counted
// every texel within a pixel of the door's silhouette as lit, and the far room received more than was shot.
Scene twoRoomsAndADoor() {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.6f));
  const uint32_t lamp = addMaterial(s, glm::vec3(0.6f), glm::vec3(100.0f));
  // Room A: x in [0, 3], room B: x in [3, 6], both 3 m deep and 2.5 m high, a 1 m × 2 m door at x = 3.
  const float h = 2.5f, d = 3.0f;
  for (float x0 : {0.0f, 3.0f}) {
    const float x1 = x0 + 3.0f;
    addRect(s, {x0, 0, 0}, {0, 0, d}, {3.0f, 0, 0}, grey);  // floor, +y
    addRect(s, {x0, h, 0}, {3.0f, 0, 0}, {0, 0, d}, grey);  // ceiling, -y
    addRect(s, {x0, 0, 0}, {3.0f, 0, 0}, {0, h, 0}, grey);  // z = 0, +z
    addRect(s, {x0, 0, d}, {0, h, 0}, {3.0f, 0, 0}, grey);  // z = d, -z
    if (x0 == 0.0f)
      addRect(s, {0, 0, 0}, {0, h, 0}, {0, 0, d}, grey);  // x = 0, +x
    else
      addRect(s, {x1, 0, 0}, {0, 0, d}, {0, h, 0}, grey);  // x = 6, -x
  }
  // The door wall at x = 3, both faces (zero thickness), the door z in [1, 2], y in [0, 2].
  for (float sign : {-1.0f, 1.0f}) {
    auto wall = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v) {
      if (sign > 0)
        addRect(s, o, u, v, grey);  // facing +x
      else
        addRect(s, o, v, u, grey);
    };
    wall({3, 0, 0}, {0, h, 0}, {0, 0, 1});
    wall({3, 0, 2}, {0, h, 0}, {0, 0, 1});
    wall({3, 2, 1}, {0, h - 2, 0}, {0, 0, 1});
  }
  addRect(s, {1.0f, h - 0.01f, 1.0f}, {1.0f, 0, 0}, {0, 0, 1.0f}, lamp);  // facing down
  return s;
}

TEST(EnergyConservation, LightThroughADoorAtACoarseItemBufferCreatesNoLight) {
  SolverParams p;
  p.itemBuffer = 128;
  p.unshotFraction = 1e-3;
  expectNoEnergyCreated(solve(twoRoomsAndADoor(), 5.0f, p));
}

// In a closed scene every shot's power lands somewhere: escaped (emitted − absorbed − unshot) stays at
// float rounding, whatever the eyes drawn.
void expectNothingEscapes(const SolveResult& r) {
  const EnergyTotals& e = r.energy;
  EXPECT_LE(std::abs(e.escaped()), 2e-3 * e.emitted) << "escaped " << e.escaped() << " W of " << e.emitted;
  EXPECT_LE(e.created, 2e-3 * e.emitted);
}

// A closed 4 m room with a 3 × 3 grid of floor-to-ceiling columns (seed3's room C, smaller): an eye drawn
// beside a column sees it fill half its view, but the column's faces get only the form factor of the
// shooter's whole region; on 531185c the floor's and ceiling's shots delivered 80–85 % of their power
// and 6 % of seed3's light vanished. Each shot now delivers what its eyes' item buffers see covered.
TEST(EnergyConservation, ShotsBesideColumnsDeliverTheirPower) {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.7f));
  const uint32_t lamp = addMaterial(s, glm::vec3(0.7f), glm::vec3(20.0f));
  // The box, its x = 0 wall the lamp: a lamp hung under the ceiling would hide a ceiling patch behind
  // its back face, and an emitting ceiling would emit inside the columns; in both, light rightly ends
  // (as in the reference), which is not what this test is after.
  const glm::vec3 X(4, 0, 0), Y(0, 3, 0), Z(0, 0, 4), o(0.0f);
  addRect(s, o, X, Y, grey);
  addRect(s, o + Z, Y, X, grey);
  addRect(s, o, Y, Z, lamp);
  addRect(s, o + X, Z, Y, grey);
  addRect(s, o, Z, X, grey);
  addRect(s, o + Y, X, Z, grey);
  for (float cx : {0.9f, 2.0f, 3.1f})
    for (float cz : {0.9f, 2.0f, 3.1f}) {
      const float a = 0.15f;
      addRect(s, {cx - a, 0, cz - a}, {0, 0, 2 * a}, {0, 3, 0}, grey);  // -x
      addRect(s, {cx + a, 0, cz - a}, {0, 3, 0}, {0, 0, 2 * a}, grey);  // +x
      addRect(s, {cx - a, 0, cz - a}, {0, 3, 0}, {2 * a, 0, 0}, grey);  // -z
      addRect(s, {cx - a, 0, cz + a}, {2 * a, 0, 0}, {0, 3, 0}, grey);  // +z
    }
  SolverParams p;
  p.unshotFraction = 1e-3;
  expectNothingEscapes(solve(s, 5.0f, p));
}

// A closed room's wall as a ceiling lamp lights it (bright in a band, dark at the top), shot once with
// nothing emitting: every receiver sees all of the wall, so what the receive pass gathers must be the
// wall's power, before the solver scales the shot to what its eyes see covered. With each far piece of
// the wall at its node's mean radiosity, at Gauss points over its area, it gathered 0.947–0.953 of it at
// 1, 2 and 4 regions per edge (now within 2e-3), and the scaling gave the rest to every receiver alike,
// rooms behind doors included (openings' room C +3 %; bench/shot_probe.cpp).
TEST(EnergyConservation, ALampLitWallsShotGathersItsPower) {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.5f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(3.0f, 2.6f, 3.0f), grey);
  Context ctx;
  EglContext context(ctx);
  AtlasParams atlasParams;
  atlasParams.density = 10.0f;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), atlasParams, ctx);
  // The x = 0 wall's texels, lit by a point 1 cm under the ceiling's centre that faces down.
  const glm::vec3 lamp(1.5f, 2.59f, 1.5f);
  std::vector<glm::vec3> irradiance(atlas.texelCount(), glm::vec3(0.0f));
  double power = 0.0;
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0 || atlas.normal[t].x < 0.5f) continue;
    const glm::vec3 d = lamp - atlas.position[t];
    const float r2 = glm::dot(d, d), r = std::sqrt(r2);
    const float e = 10.0f * std::max(0.0f, d.x / r) * std::max(0.0f, d.y / r) / r2;
    irradiance[t] = glm::vec3(e);
    power += 3.0 * 0.5 * e * atlas.area[t];
  }
  for (int regions : {1, 2, 4}) {
    SCOPED_TRACE(regions);
    SolverParams p;
    p.maxShots = 1;
    p.unshotFraction = 1e-6;
    p.maxRegions = p.strongShotRegions = regions;
    SolveControls controls;
    PriorShot prior;
    prior.irradiance = irradiance;
    prior.emitted = power;
    controls.priorShot = &prior;
    const SolveResult r = solveProgressive(s, atlas, p, context, ctx, controls);
    ASSERT_EQ(r.shots, 1);
    ASSERT_EQ(r.shotScales.size(), 1u);
    // Gathered ÷ shot (the scale is shot ÷ gathered; 1 when within the solver's 2e-3 of it).
    EXPECT_NEAR(1.0 / r.shotScales[0], 1.0, 0.004);
  }
}

// Two closed rooms sharing a zero-thickness wall with a door: the wall's two faces coincide, and a
// shooter on one side used to see the other side's back face over part of the wall (depth rounding),
// light that no receiver took.
TEST(EnergyConservation, ZeroThicknessPartitionLosesNoLight) {
  SolverParams p;
  p.unshotFraction = 1e-3;
  expectNothingEscapes(solve(twoRoomsAndADoor(), 5.0f, p));
}

// A closed 3 m room lit by a 0.8 m lamp 1 cm under its ceiling, facing down, its edges through the
// centres of the ceiling's 0.2 m texels (the openings scene's room A). The ceiling's strong shots draw
// small regions (gl_shot_regions.cpp: strongReflectorLayout), some of them mostly over the lamp, whose
// power is in the texels along its edges: their eyes, at those texels' centres, see the lamp's back over
// half their view, and the shot delivered only what they saw covered (2.2 % of the ceiling's shots lost
// where the room's light lands on no back face). A back face within a texel of the eye is left out of its
// coverage (shot_coverage.comp), as the texel's light came from, and leaves by, its open side.
Scene roomWithALampUnderItsCeiling() {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.7f));
  const uint32_t lamp = addMaterial(s, glm::vec3(0.8f), glm::vec3(100.0f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(3.0f, 2.6f, 3.0f), grey);
  addRect(s, {1.1f, 2.59f, 1.1f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.8f}, lamp);  // facing down
  return s;
}

TEST(EnergyConservation, CeilingShotsBesideALampLoseNoLight) {
  const Scene scene = roomWithALampUnderItsCeiling();
  for (Visibility v : {Visibility::Hemisphere, Visibility::Hemicube}) {
    SCOPED_TRACE(v == Visibility::Hemisphere ? "hemisphere" : "hemicube");
    SolverParams p;
    p.visibility = v;
    p.unshotFraction = 1e-3;
    expectNothingEscapes(solve(scene, 5.0f, p));
  }
}

// The thesis's one-pass hemisphere buffer draws each triangle with straight edges where its image is
// curved: walls next to the eye lost wedges of the view (seed1's room B read 1.48× the reference on
// 11706cc). Tessellated by the angle its edges subtend (item_hemisphere.tesc), here: escaped 10.4 → 5.9
// W of 300 and the rooms 0.96 → 0.97 of the hemicube's. Issue 11 asks for 2 points; edges passing within
// centimetres of an eye are still cut evenly along their length, not their angle.
TEST(EnergyConservation, HemisphereBufferAgreesWithTheHemicube) {
  const Scene scene = twoRoomsAndADoor();
  SolverParams p;
  p.unshotFraction = 1e-3;
  LightmapAtlas atlas;
  const SolveResult cube = solve(scene, 5.0f, p, &atlas);
  p.visibility = Visibility::Hemisphere;
  const SolveResult sphere = solve(scene, 5.0f, p);
  EXPECT_LE(std::abs(sphere.energy.escaped()), 0.03 * sphere.energy.emitted);
  // Mean radiosity of each room (x < 3, x > 3), area-weighted.
  for (int room = 0; room < 2; ++room) {
    double a = 0.0, c = 0.0, h = 0.0;
    for (size_t i = 0; i < atlas.texelCount(); ++i) {
      if (atlas.patch[i] < 0 || (atlas.position[i].x < 3.0f) != (room == 0)) continue;
      a += atlas.area[i];
      c += atlas.area[i] * double(cube.radiosity[i].r);
      h += atlas.area[i] * double(sphere.radiosity[i].r);
    }
    EXPECT_NEAR(h / c, 1.0, 0.04) << "room " << room;
  }
}

// Two rooms sharing a wall with no opening, their floors, ceilings and side walls in common planes; a
// coarse buffer makes a pixel's footprint tens of centimetres, as a fine atlas seen through a door does
// at the default buffer. The ways light got into the closed room (issue 11):
//  - pixel centres aligned with the scene's axis-aligned edges: from a floor's eye, a pixel whose centre
//    ray ran along the wall's top edge, where both rooms' ceilings meet it, went to the far room's
//    ceiling by the rasterizer's tie rule, and that ceiling counted as seen through the wall. The item
//    buffer now turns about the shooter's normal from shot to shot (gl_shot_backend.cpp). 16-pixel buffer:
//    6.7e-4 of the lit room's radiosity power in B on ad2b8db, 0 now;
//  - a pixel showing the lit room's floor just in front of the wall's foot also covers the floor behind
//    it, in the same plane, and a face in the receiver's plane counted as no occluder. It now counts only
//    if it covers the receiver (visibility.glsl). 64-pixel buffer: 2.7e-4 without that rule, 7e-6 with;
//  - the wall itself seen a hair under the ceiling's corner, from an eye on a side wall: the far room's
//    ceiling texel half a texel past the wall lies over the wall's rectangle (its point projected on the
//    wall's plane), and a face seen in the receiver's plane counted as covering it. It now does only when
//    it does not lie across the segment from the eye to the receiver (receive.comp, seenPatchBlocks).
//    512-pixel buffer at 10 texels a metre: 4.4e-6 without that test, 3.6e-7 with it (a bake of the same
//    rooms at the defaults: 2.1e-5 → 1.0e-6);
//  - with the rooms slid along the wall, a side wall of B meets A's side of the wall mid-span, and a pixel
//    showing A's part of the wall beyond that side wall's plane read as a view through that plane beside
//    the receiver. It counts now only when the wall it shows does not lie across that segment either.
//    Slid 1.5 m: 64-pixel buffer 1.7e-4 of the lit room's power without that rule, 5.7e-6 with it;
//    512-pixel buffer 9.4e-6 and 9.3e-8.
// The 16- and 64-pixel buffers (pixels of 6° and 1.5°) keep a few 1e-6 from cracks along the wall's foot.
void expectNoLightBehindTheWall(float shiftB) {
  const SeedScene s = makeThinWall(0.0f, shiftB);
  const std::vector<int> cellOf = s.cells.cellOfTriangle(s.scene.triangles.size());
  const int b = s.cells.findCell("B");
  ASSERT_GE(b, 0);
  for (const auto& [itemBuffer, density, bound] :
       {std::tuple{16, 20.0f, 1e-5}, {64, 20.0f, 1e-5}, {512, 10.0f, 1e-6}}) {
    SolverParams p;
    p.itemBuffer = itemBuffer;
    LightmapAtlas atlas;
    const SolveResult r = solve(s.scene, density, p, &atlas);
    double behind = 0.0, lit = 0.0;
    for (size_t i = 0; i < atlas.texelCount(); ++i) {
      if (atlas.patch[i] < 0) continue;
      const double w = atlas.area[i] * double(r.radiosity[i].r);
      (cellOf[atlas.patches[atlas.patch[i]].triangles[0]] == b ? behind : lit) += w;
    }
    std::printf("%d-pixel buffer: the closed room behind the wall gets %.3g of the lit room's power\n",
                itemBuffer, behind / lit);
    EXPECT_GT(lit, 0.0);
    EXPECT_LE(behind, bound * lit) << itemBuffer << "-pixel buffer";
  }
}

TEST(EnergyConservation, NoLightOverAWallIntoTheRoomBehind) {
  expectNoLightBehindTheWall(0.0f);
}

TEST(EnergyConservation, NoLightOverAWallIntoARoomBesideACorner) {
  expectNoLightBehindTheWall(1.5f);
}

}  // namespace
}  // namespace cpgi
