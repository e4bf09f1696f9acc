// Visibility regions (SolverParams::maxRegions, `bake --regions`): a large emitter seen through a small
// hole. Each region decides visibility from one eye point, so with one region the floor under the hole
// sees the whole 4 m panel or none of it; with more, the pool gets the panel's penumbra. The exact
// irradiance is closed form here (parallel planes: what a floor point sees of the panel through the hole
// is a rectangle, integrated by Lambert's contour formula).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/metrics/form_factors.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

constexpr float kPanel = 2.0f;  // emitter half-width, at z = 3, facing down
constexpr float kHole = 0.25f;  // hole half-width, in a black plate at z = 2
constexpr double kPanelZ = 3.0, kPlateZ = 2.0;

Scene holeScene() {
  Scene s;
  const uint32_t lamp = addMaterial(s, glm::vec3(0.0f), glm::vec3(1.0f));
  const uint32_t black = addMaterial(s, glm::vec3(0.0f));
  addRect(s, glm::vec3(-kPanel, -kPanel, 3.0f), glm::vec3(0, 2 * kPanel, 0), glm::vec3(2 * kPanel, 0, 0),
          lamp);
  // The plate: four strips around the hole, its top at z = 2 and its underside 1 cm lower.
  const float w = 3.0f;
  struct Strip {
    float x0, y0, x1, y1;
  };
  const Strip strips[] = {
      {-w, -w, w, -kHole}, {-w, kHole, w, w}, {-w, -kHole, -kHole, kHole}, {kHole, -kHole, w, kHole}};
  for (const Strip& r : strips) {
    addRect(s, glm::vec3(r.x0, r.y0, 2.0f), glm::vec3(r.x1 - r.x0, 0, 0), glm::vec3(0, r.y1 - r.y0, 0),
            black);
    addRect(s, glm::vec3(r.x0, r.y0, 1.99f), glm::vec3(0, r.y1 - r.y0, 0), glm::vec3(r.x1 - r.x0, 0, 0),
            black);
  }
  // The floor, black too: what it receives is the panel's direct light only.
  addRect(s, glm::vec3(-kPanel, -kPanel, 0.0f), glm::vec3(2 * kPanel, 0, 0), glm::vec3(0, 2 * kPanel, 0),
          black);
  return s;
}

// Irradiance at floor point (x, y, 0) from the unit-exitance panel through the hole.
double exactIrradiance(double x, double y) {
  const double k = kPanelZ / kPlateZ;  // the hole projected from the point onto the panel's plane
  const double x0 = std::max(-double(kPanel), x + (-kHole - x) * k),
               x1 = std::min(double(kPanel), x + (kHole - x) * k);
  const double y0 = std::max(-double(kPanel), y + (-kHole - y) * k),
               y1 = std::min(double(kPanel), y + (kHole - y) * k);
  if (x0 >= x1 || y0 >= y1) return 0.0;
  const std::vector<glm::dvec3> seen = {
      {x0, y0, kPanelZ}, {x1, y0, kPanelZ}, {x1, y1, kPanelZ}, {x0, y1, kPanelZ}};
  return pointToPolygonFormFactor(glm::dvec3(x, y, 0.0), glm::dvec3(0, 0, 1), seen);
}

// Area-weighted relative RMSE of the floor's irradiance against the closed form.
double floorError(int regions, int strongRegions, bool jittered) {
  const Scene scene = holeScene();
  Context ctx;
  EglContext gl(ctx);
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.density = 12.0f}, ctx);
  SolverParams params;
  params.maxRegions = regions;
  params.strongShotRegions = strongRegions;
  params.jitteredEyes = jittered;
  const SolveResult r = solveProgressive(scene, atlas, params, gl, ctx, SolveControls{.readTransfer = true});
  const int floorTriangle = int(scene.triangles.size()) - 1;
  double err = 0.0, ref = 0.0;
  size_t texels = 0;
  testing::forEachTexelOf(atlas, floorTriangle, [&](size_t t) {
    const glm::vec3 x = atlas.position[t];
    const double exact = exactIrradiance(x.x, x.y);
    err += atlas.area[t] * std::pow(r.incident[t].r - exact, 2);
    ref += atlas.area[t] * exact * exact;
    ++texels;
  });
  EXPECT_GT(texels, 2000u);
  return std::sqrt(err / ref);
}

TEST(VisibilityRegions, MoreRegionsGiveTheLargeShootersPenumbra) {
  // Fixed eyes at the regions' centres: drawn eyes (the default) make one shot's pool a random sample of
  // the penumbra, right on average over shots but not in this single shot (measured: error 1.0 either way).
  const double one = floorError(1, 1, false), four = floorError(4, 4, false);
  // Measured (hemicube, 12 texels/m): one region 12.8 (the pool under the hole gets the whole panel),
  // two 1.26, three 1.68 (eyes placed differently: not monotonic), four 0.87. A 1 m region is still
  // wider than the 0.75 m of panel seen through the hole, so four regions are not yet accurate either.
  EXPECT_GT(one, 0.5) << "one eye for a 4 m panel should give a hard, far too bright pool";
  EXPECT_LT(four, 0.5 * one);
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// The panel is the only shooter (everything else is black), so its one shot is strong: the strong
// layout alone decides, whatever the ordinary one.
TEST(VisibilityRegions, StrongShotsUseTheirOwnLayout) {
  EXPECT_EQ(floorError(1, 4, true), floorError(4, 4, true));
  EXPECT_EQ(floorError(4, 1, true), floorError(1, 1, true));
}

}  // namespace
}  // namespace cpgi
