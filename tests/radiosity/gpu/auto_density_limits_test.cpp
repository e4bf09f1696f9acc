// The density pilot within its limits (issue 46): a deadline stops its sky gather after a whole pass (the
// densities still chosen, from the noisier light), its atlas keeps to its share of the texel budget, and
// fitTexelBudget lays the output out within --max-texels by one factor on every density.
#include <chrono>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/cpu/ray_shot_engine.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/solve/auto_density.h"
#include "tests/radiosity/test_sky_scenes.h"

namespace cpgi {
namespace {

Scene daylitBox() {
  Scene s = testing::boxOpenToTheSky(0.5f, 0.5f);
  s.sky.kind = Sky::Kind::Uniform, s.sky.zenithRadiance = 3.0f;
  s.sky.gatherRays = 256;
  return s;
}

bool saidOnce(const Context& ctx, const std::string& text) {
  int n = 0;
  for (const std::string& w : ctx.warnings()) n += w.find(text) != std::string::npos;
  return n == 1;
}

TEST(AutoDensityLimits, ADeadlineStopsThePilotsSkyGather) {
  const Scene s = daylitBox();
  const QuadSet quads = findQuads(s);
  RayShotEngine rays;
  AutoDensityData onTime, late;
  Context a, b;
  const std::vector<float> full =
      chooseAutoDensity(s, quads, AtlasParams{}, AutoDensityParams{}, SolverParams{}, rays, a, {}, &onTime);
  EXPECT_FALSE(saidOnce(a, "sky light: the deadline came"));
  const std::vector<float> cut =
      chooseAutoDensity(s, quads, AtlasParams{}, AutoDensityParams{}, SolverParams{}, rays, b,
                        SolveControls{.deadline = std::chrono::steady_clock::now()}, &late);
  EXPECT_TRUE(saidOnce(b, "sky light: the deadline came after 8 of 256 rays a texel")) << b.warnings().size();
  ASSERT_EQ(cut.size(), full.size());
  const AutoDensityParams p;
  for (size_t t = 0; t < cut.size(); ++t) {
    if (full[t] == 0.0f) continue;
    EXPECT_GE(cut[t], p.light.minDensity) << t;
    EXPECT_LE(cut[t], std::max(p.light.maxDensity, p.maxContactDensity)) << t;
  }
  EXPECT_EQ(late.pilotTexels, onTime.pilotTexels);
}

TEST(AutoDensityLimits, ThePilotAndTheOutputKeepToTheTexelBudget) {
  const Scene s = daylitBox();
  const QuadSet quads = findQuads(s);
  double area = 0.0;  // about 23 m²: 2 300 texels at the pilot's 10 a metre
  for (const Triangle& t : s.triangles) area += t.area();
  AutoDensityParams p;
  EXPECT_FLOAT_EQ(pilotDensity(s, p), p.pilotDensity);
  p.maxTexels = 2000;  // the pilot's share: 500 texels
  EXPECT_NEAR(pilotDensity(s, p), std::sqrt(kPilotTexelShare * 2000.0 / area), 1e-4);
  RayShotEngine rays;
  Context ctx;
  AutoDensityData data;
  const std::vector<float> density =
      chooseAutoDensity(s, quads, AtlasParams{}, p, SolverParams{}, rays, ctx, {}, &data);
  EXPECT_LE(data.pilotDensity, std::sqrt(kPilotTexelShare * 2000.0 / area) + 1e-4);
  EXPECT_LE(data.pilotTexels, size_t(kPilotTexelShare * 2000.0));  // fitted to its share, borders and all

  // The output at 40 a metre everywhere asks 1 600 texels a m²: scaled by one factor to within 2 000.
  AtlasParams out;
  out.triangleDensity.assign(s.triangles.size(), 40.0f);
  Context fit;
  TexelBudget budget;
  const LightmapAtlas atlas = fitTexelBudget(s, quads, out, 2000, fit, &budget);
  EXPECT_LE(atlas.validTexels(), 2000u);
  EXPECT_GT(atlas.validTexels(), 1000u);
  EXPECT_LT(budget.scale, 0.3f);
  EXPECT_NEAR(double(budget.asked), 1600.0 * area, 0.01 * 1600.0 * area);
  for (float d : out.triangleDensity) EXPECT_NEAR(d, 40.0f * budget.scale, 1e-3f);
  EXPECT_NE(budget.note.find("--max-texels"), std::string::npos);
  // Within the budget: the atlas as asked, no note.
  AtlasParams small;
  small.triangleDensity.assign(s.triangles.size(), 4.0f);
  TexelBudget none;
  const LightmapAtlas same = fitTexelBudget(s, quads, small, 2000, fit, &none);
  EXPECT_EQ(none.scale, 1.0f);
  EXPECT_EQ(none.note, "");
  EXPECT_EQ(
      same.validTexels(),
      buildAtlas(s, quads, AtlasParams{.triangleDensity = std::vector<float>(s.triangles.size(), 4.0f)}, fit)
          .validTexels());
}

// Faces cut where other geometry runs through them can leave a triangle of zero area (oa_dm2: two, each with
// two corners at one point), which no atlas charts: the pilot gives it no light and so no density, and the
// output's atlas refused the bake ("a chart's density must be positive").
TEST(AutoDensityLimits, AZeroAreaTriangleGetsADensityTheOutputAccepts) {
  Scene s = daylitBox();
  testing::addZeroAreaTriangle(s);
  const QuadSet quads = findQuads(s);
  RayShotEngine rays;
  Context ctx;
  const std::vector<float> density =
      chooseAutoDensity(s, quads, AtlasParams{}, AutoDensityParams{}, SolverParams{}, rays, ctx);
  ASSERT_EQ(density.size(), s.triangles.size());
  for (float d : density) EXPECT_GT(d, 0.0f);
  AtlasParams out;
  out.triangleDensity = density;
  Context layout;
  const LightmapAtlas atlas = buildAtlas(s, quads, out, layout);
  EXPECT_TRUE(saidOnce(layout, "1 zero-area triangle(s) left out"));
  EXPECT_GT(atlas.validTexels(), 0u);
}

// The same triangle in a room lit by a lamp, on GL: the lamps' refined shot lays a coarse atlas out from the
// pilot's, where the triangle left out had density 0, and the pilot refused the bake ("a chart's density
// must be positive": ctf_gate1 baked by its lamp shaders).
TEST(AutoDensityLimits, AZeroAreaTriangleBesideALampLetsThePilotShootIt) {
  Scene s;
  const uint32_t grey = testing::addMaterial(s, glm::vec3(0.6f));
  const uint32_t lamp = testing::addMaterial(s, glm::vec3(0.0f), glm::vec3(50.0f));
  testing::addClosedBox(s, glm::vec3(0.0f), glm::vec3(3.0f, 3.0f, 2.5f), grey);
  testing::addRect(s, glm::vec3(1.2f, 1.8f, 2.49f), glm::vec3(0.6f, 0, 0), glm::vec3(0, -0.6f, 0), lamp);
  testing::addZeroAreaTriangle(s);
  const QuadSet quads = findQuads(s);
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);  // the refined lamp shot is the lamp-shooting engine's
  std::vector<float> density;
  ASSERT_NO_THROW(
      density = chooseAutoDensity(s, quads, AtlasParams{}, AutoDensityParams{}, SolverParams{}, gl, ctx));
  ASSERT_EQ(density.size(), s.triangles.size());
  for (float d : density) EXPECT_GT(d, 0.0f);
}

// A bake lays its atlas out more than once on its context (the density pilot, the budget's fit, the output):
// the zero-area triangles left out are said once, whichever layout said it first (ctf_gate1's daylit bake
// printed "14 zero-area triangle(s) left out" twice).
TEST(AutoDensityLimits, AZeroAreaTriangleLeftOutIsSaidOnceAcrossTheBudgetsLayouts) {
  Scene s = daylitBox();
  testing::addZeroAreaTriangle(s);
  const QuadSet quads = findQuads(s);
  Context ctx;
  AtlasParams asked;
  asked.triangleDensity.assign(s.triangles.size(), 4.0f);
  buildAtlas(s, quads, asked, ctx);
  TexelBudget budget;
  fitTexelBudget(s, quads, asked, 2000, ctx, &budget);
  EXPECT_TRUE(saidOnce(ctx, "1 zero-area triangle(s) left out")) << ctx.warnings().size();
}

}  // namespace
}  // namespace cpgi
