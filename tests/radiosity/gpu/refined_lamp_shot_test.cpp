// The lamps' shot at the output's texels only where its light varies (issue 13): against the same shot
// at every output texel, the rooms get the same direct light, sharp where a table's shadow and the
// door's edge fall, for a fraction of the texels.
#include "radiosity/solve/refined_lamp_shot.h"
#include "radiosity/gpu/gl_shot_engine.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addRect;

// testing::twoRoomsThroughADoor with a 0.8 m table top (both faces) 0.8 m above the first room's floor.
Scene roomsWithTable() {
  Scene s = testing::twoRoomsThroughADoor();
  const uint32_t grey = 0;                                           // twoRoomsThroughADoor's first material
  addRect(s, {1.0f, 1.1f, 0.8f}, {0.8f, 0, 0}, {0, 0.8f, 0}, grey);  // top, faces +z
  addRect(s, {1.0f, 1.1f, 0.8f}, {0, 0.8f, 0}, {0.8f, 0, 0}, grey);  // underside, faces −z
  return s;
}

struct RoomError {
  double ratio = 0.0;  ///< mean of `b` ÷ mean of `a`
  double rmse = 0.0;   ///< RMS of b − a ÷ mean of a
};

// Per room (x < 3, x > 3 by the texel's side of the partition), R + G + B of the non-emitting texels.
std::array<RoomError, 2> compareRooms(const LightmapAtlas& atlas, const std::vector<glm::vec3>& a,
                                      const std::vector<glm::vec3>& b) {
  std::array<double, 2> sa{}, sb{}, sd{}, area{};
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0 || atlas.emission[t] != glm::vec3(0.0f)) continue;
    const int room = (atlas.position[t] + 0.01f * atlas.normal[t]).x < 3.0f ? 0 : 1;
    const double va = a[t].r + a[t].g + a[t].b, vb = b[t].r + b[t].g + b[t].b;
    sa[room] += va * atlas.area[t], sb[room] += vb * atlas.area[t];
    sd[room] += (vb - va) * (vb - va) * atlas.area[t], area[room] += atlas.area[t];
  }
  std::array<RoomError, 2> e;
  for (int r = 0; r < 2; ++r) e[r] = {sb[r] / sa[r], std::sqrt(sd[r] / area[r]) / (sa[r] / area[r])};
  return e;
}

TEST(RefinedLampShot, GivesEveryOutputTexelTheLightOfAShotAtItsOwnResolution) {
  const Scene scene = roomsWithTable();
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  const QuadSet quads = findQuads(scene);
  const AtlasParams output{.density = 24.0f};
  const LightmapAtlas atlas = buildAtlas(scene, quads, output, ctx);
  SolverParams params;
  SolverParams lampOnly = params;
  lampOnly.maxShots = 1;
  lampOnly.unshotFraction = 1e-12;
  const SolveResult whole =
      solveProgressive(scene, atlas, lampOnly, gl, ctx, SolveControls{.readTransfer = true});

  RefinedLampData data;
  const SolveResult refined =
      shootLampsRefined(scene, quads, atlas, output, RefinedLampParams{.minDensity = 6.0f}, params, gl, ctx,
                        SolveControls{}, &data);
  ASSERT_EQ(refined.incident.size(), atlas.texelCount());
  const auto e = compareRooms(atlas, whole.incident, refined.incident);
  std::printf(
      "lamp room %.4f (rmse %.4f), next room %.4f (rmse %.4f); %zu of %zu texels refined, coarse %zu\n",
      e[0].ratio, e[0].rmse, e[1].ratio, e[1].rmse, data.refinedTexels, atlas.validTexels(),
      data.coarseTexels);
  EXPECT_NEAR(e[0].ratio, 1.0, 0.01);
  EXPECT_NEAR(e[1].ratio, 1.0, 0.02);
  EXPECT_LT(e[0].rmse, 0.015);
  EXPECT_LT(e[1].rmse, 0.03);  // 0.33 with the flags alone: the beam through the door bends
  // The coarse shot at 24 / 4 = 6 texels a metre; most output texels take its light interpolated.
  EXPECT_GT(data.coarseTexels, 0u);
  EXPECT_LT(data.coarseTexels * 8, atlas.validTexels());
  EXPECT_LT(data.refinedTexels * 2, atlas.validTexels());
  EXPECT_GT(data.refinedTexels, 0u);

  // The books: the lamp's power shot, no more received, what is kept to reflect is the unshot.
  const EnergyTotals& b = refined.energy;
  EXPECT_NEAR(b.emitted, whole.energy.emitted, 0.01 * b.emitted);
  EXPECT_LE(b.received, b.shot * (1.0 + 1e-6));
  EXPECT_NEAR(b.received, whole.energy.received, 0.01 * b.received);
  EXPECT_NEAR(b.absorbed + b.unshot, b.received, 1e-6 * b.received);
}

}  // namespace
}  // namespace cpgi
