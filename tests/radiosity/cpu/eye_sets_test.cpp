// The light a room gets through a door from one shot of the next room's floor, eye draw by eye draw
// (radiosity/cpu/ray_shot.h, RayShotParams::eyeSetsPerEdge). A room lit through doors takes most of its light
// from shots like this one, and its mean is only as steady as the sum over its texels of each shot.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "tests/radiosity/cpu/exact_transfer.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

// Room A (x, y in [0, 4]) and room B (y in [4, 8]), 2.6 m high, z up, a zero-thickness wall between them at
// y = 4 with a door 0.8 m wide and 2 m high near one end. A's floor comes first: it is the shooter.
Scene twoRoomsThroughADoor() {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  const float h = 2.6f, door0 = 2.6f, door1 = 3.4f, doorTop = 2.0f;
  addRect(s, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}, m);  // A's floor, normal +z
  for (float y0 : {0.0f, 4.0f}) {
    const float y1 = y0 + 4.0f;
    if (y0 > 0.0f) addRect(s, {0, y0, 0}, {4, 0, 0}, {0, 4, 0}, m);  // B's floor
    addRect(s, {0, y0, h}, {0, 4, 0}, {4, 0, 0}, m);                 // ceiling, normal −z
    addRect(s, {0, y0, 0}, {0, 4, 0}, {0, 0, h}, m);                 // x = 0, normal +x
    addRect(s, {4, y0, 0}, {0, 0, h}, {0, 4, 0}, m);                 // x = 4, normal −x
    if (y0 == 0.0f) addRect(s, {0, 0, 0}, {0, 0, h}, {4, 0, 0}, m);  // y = 0, normal +y
    if (y0 > 0.0f) addRect(s, {0, y1, 0}, {4, 0, 0}, {0, 0, h}, m);  // y = 8, normal −y
  }
  // The partition, A's side (normal −y) and B's (normal +y), around the door.
  for (int side = 0; side < 2; ++side) {
    auto wall = [&](glm::vec3 o, float w, float t) {
      if (side == 0)
        addRect(s, o, {w, 0, 0}, {0, 0, t}, m);
      else
        addRect(s, o, {0, 0, t}, {w, 0, 0}, m);
    };
    wall({0, 4, 0}, door0, h);
    wall({door1, 4, 0}, 4.0f - door1, h);
    wall({door0, 4, doorTop}, door1 - door0, h - doorTop);
  }
  return s;
}

struct DoorShot {
  Scene scene;
  Context ctx;
  LightmapAtlas atlas;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<RayShotScene> shots;
  std::vector<ShooterLayout> layouts;
  std::vector<glm::vec3> residual;
  int shooter = 0;

  DoorShot() : scene(twoRoomsThroughADoor()) {
    atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.density = 4.0f}, ctx);
    rays = std::make_unique<RayScene>(scene);
    shots = std::make_unique<RayShotScene>(scene, atlas, *rays);
    layouts = layoutShooters(scene, atlas, {});
    shooter = atlas.patch[size_t(atlas.patches[0].y) * atlas.width + size_t(atlas.patches[0].x)];
    residual.assign(atlas.texelCount(), glm::vec3(0.0f));
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (atlas.patch[t] == shooter) residual[t] = glm::vec3(1.0f);
  }
  bool inB(size_t t) const { return atlas.patch[t] >= 0 && atlas.position[t].y > 4.01f; }
  // B's power from the shot with eye draw `shotNumber` (W, R).
  double roomB(uint32_t shotNumber, const RayShotParams& params) const {
    const RayShotGain g =
        shootByRays(*shots, shooter, layouts[size_t(shooter)], residual, shotNumber, params);
    double sum = 0.0;
    for (size_t k = 0; k < shots->texels.size(); ++k)
      if (inB(shots->texels[k])) sum += double(g.irradiance[k].r) * atlas.area[shots->texels[k]];
    return sum;
  }
  // The same from 4 × 4 points per shooter texel, each seen by its own ray: nothing shared with the shot
  // but the ray scene.
  double roomBExact() const {
    double sum = 0.0;
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (inB(t)) sum += testing::exactIrradiance(atlas, *rays, shooter, t, 4) * atlas.area[t];
    return sum;
  }
};

// Each of A's floor's regions (2 m across) sends its light into B from its eyes: with every receiver on the
// same two eyes a region, B's whole power from one shot swung with where those two landed (the door is
// 0.8 m wide), 30 % from draw to draw (RMS, eyeSetsPerEdge 1). With the receivers' eyes interleaved over
// four sets, B's texels together look from eight points a region, and B's power keeps near the exact one
// on every draw.
TEST(EyeSets, ARoomBehindADoorGetsEachShotsLightOnEveryEyeDraw) {
  const DoorShot shot;
  ASSERT_NEAR(shot.atlas.patches[size_t(shot.shooter)].normal.z, 1.0f, 1e-6f);
  ASSERT_LT(shot.atlas.position[shot.shots->patchTexels[size_t(shot.shooter)][0]].y, 4.0f);
  const double exact = shot.roomBExact();
  ASSERT_GT(exact, 0.0);
  auto rms = [&](const RayShotParams& params) {
    double squares = 0.0, mean = 0.0;
    constexpr int kDraws = 64;
    for (int d = 1; d <= kDraws; ++d) {
      const double got = shot.roomB(uint32_t(d), params) / exact;
      squares += (got - 1.0) * (got - 1.0), mean += got / kDraws;
    }
    std::printf("eye sets per edge %d: B's power over the exact, mean %.4f, RMS error %.4f\n",
                params.eyeSetsPerEdge, mean, std::sqrt(squares / kDraws));
    return std::sqrt(squares / kDraws);
  };
  const double shared = rms(RayShotParams{.eyeSetsPerEdge = 1}), interleaved = rms(RayShotParams{});
  EXPECT_LT(interleaved, 0.6 * shared);
  EXPECT_LT(interleaved, 0.07);
}

}  // namespace
}  // namespace cpgi
