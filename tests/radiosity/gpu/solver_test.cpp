// The GPU solver against closed forms: Lambert's point-to-polygon form factor, the parallel and
// perpendicular unit squares, the white furnace, energy bookkeeping and determinism.
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/solve/progressive_loop.h"

#include <algorithm>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "core/error.h"
#include "core/quads.h"
#include "scenes/seed_scenes.h"
#include "tests/radiosity/furnace_check.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;

struct Solved {
  LightmapAtlas atlas;
  SolveResult result;
};

Solved solve(const Scene& scene, const AtlasParams& atlasParams, const SolverParams& params,
             const SolveControls& controls = {}) {
  Context ctx;
  EglContext context(ctx);
  Solved s;
  s.atlas = buildAtlas(scene, findQuads(scene), atlasParams, ctx);
  s.result = solveProgressive(scene, s.atlas, params, context, ctx, controls);
  return s;
}

// Area-weighted mean radiosity (red channel) over the patch containing triangle `tri`.
double patchMean(const Solved& s, int tri) {
  double sum = 0.0, area = 0.0;
  for (size_t t = 0; t < s.atlas.texelCount(); ++t) {
    const int p = s.atlas.patch[t];
    if (p < 0) continue;
    const std::vector<int32_t>& own = s.atlas.patches[p].triangles;
    if (std::find(own.begin(), own.end(), tri) == own.end()) continue;
    sum += double(s.result.radiosity[t].r) * s.atlas.area[t];
    area += s.atlas.area[t];
  }
  return sum / area;
}

// Lambert's contour integral: the form factor from a differential area at x (normal n) to a polygon.
double lambert(glm::dvec3 x, glm::dvec3 n, const std::vector<glm::dvec3>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3 a = glm::normalize(polygon[i] - x),
                     b = glm::normalize(polygon[(i + 1) % polygon.size()] - x);
    const glm::dvec3 c = glm::cross(a, b);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, c) / glm::length(c);
  }
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

SolverParams oneShot(Visibility v) {
  SolverParams p;
  p.visibility = v;
  p.maxShots = 1;
  return p;
}

class SolverVisibility : public ::testing::TestWithParam<Visibility> {};

// Unit squares one metre apart, face to face: F = 0.19982 (Siegel & Howell). The receiver has
// albedo 1, so after the emitter's shot its mean radiosity is E · F. The hemisphere item buffer draws
// the receiver's edges as chords of their curved images, so its outer texels miss their own pixel
// (thesis fig. 6.2); the plane test finds them unshadowed, so both modes are held to 1 %.
TEST_P(SolverVisibility, ParallelUnitSquares) {
  Scene s;
  const uint32_t lamp = addMaterial(s, glm::vec3(0.0f), glm::vec3(1.0f));
  const uint32_t white = addMaterial(s, glm::vec3(1.0f));
  addRect(s, glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), lamp);   // normal −z
  addRect(s, glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), white);  // normal +z
  const Solved r = solve(s, AtlasParams{.texelsPerQuad = 16}, oneShot(GetParam()));
  EXPECT_EQ(r.result.shots, 1);
  const double f = patchMean(r, 2);
  // Both modes: the hemisphere's rim texels, which its chords miss, see behind them only what lies
  // beyond their own plane, and the plane test of visibility.glsl keeps them (on main: 0.8–0.99).
  EXPECT_NEAR(f, 0.19982, 0.01 * 0.19982);
}

// Perpendicular unit squares sharing an edge: F = 0.20004. The hemisphere item buffer loses the
// receiver texels near the shared edge (the thesis's curved-edge error, fig. 6.2) in their own pixel;
// the plane test keeps them, and both modes are held to 1 %.
TEST_P(SolverVisibility, PerpendicularUnitSquares) {
  Scene s;
  const uint32_t lamp = addMaterial(s, glm::vec3(0.0f), glm::vec3(1.0f));
  const uint32_t white = addMaterial(s, glm::vec3(1.0f));
  addRect(s, glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), lamp);   // floor, normal +z
  addRect(s, glm::vec3(0, 0, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), white);  // wall y = 0, normal +y
  const Solved r = solve(s, AtlasParams{.texelsPerQuad = 16}, oneShot(GetParam()));
  const double f = patchMean(r, 2);
  EXPECT_NEAR(f, 0.20004, 0.01 * 0.20004);  // both modes, as above (hemisphere on main: 0.25–0.99)
}

INSTANTIATE_TEST_SUITE_P(Modes, SolverVisibility,
                         ::testing::Values(Visibility::Hemisphere, Visibility::Hemicube),
                         [](const auto& info) { return std::string(visibilityName(info.param)); });

// One texel against Lambert's formula, far from the emitter (one disk) and close to it (blocks, texels).
TEST(Solver, SingleTexelMatchesLambert) {
  Scene s;
  const uint32_t lamp = addMaterial(s, glm::vec3(0.0f), glm::vec3(1.0f));
  const uint32_t white = addMaterial(s, glm::vec3(1.0f));
  const std::vector<glm::dvec3> emitter = {{-0.1, -0.1, 1}, {-0.1, 0.1, 1}, {0.1, 0.1, 1}, {0.1, -0.1, 1}};
  addRect(s, glm::vec3(-0.1f, -0.1f, 1.0f), glm::vec3(0, 0.2f, 0), glm::vec3(0.2f, 0, 0), lamp);
  struct Probe {
    glm::vec3 centre, normal;
  };
  const Probe probes[] = {{{0.3f, 0.1f, 0.2f}, glm::normalize(glm::vec3(-0.3f, -0.2f, 1.0f))},
                          {{0.05f, 0.12f, 0.93f}, glm::normalize(glm::vec3(0.1f, -0.4f, 1.0f))}};
  for (const Probe& p : probes) {
    const glm::vec3 u = glm::normalize(glm::cross(p.normal, glm::vec3(1, 0, 0))) * 0.02f;
    const glm::vec3 v = glm::cross(p.normal, u);
    addRect(s, p.centre - 0.5f * (u + v), u, v, white);
  }
  AtlasParams atlas{.density = 40.0f, .minTexels = 1};
  const Solved r = solve(s, atlas, oneShot(Visibility::Hemicube));
  for (int i = 0; i < 2; ++i) {
    const double exact = lambert(glm::dvec3(probes[i].centre), glm::dvec3(probes[i].normal), emitter);
    EXPECT_NEAR(patchMean(r, 2 + 2 * i), exact, 0.01 * exact) << "probe " << i;
  }
}

// A closed box with albedo ρ and emission E everywhere converges to B = E / (1 − ρ).
TEST(Solver, WhiteFurnace) {
  Scene s;
  const float rho = 0.5f, e = 1.0f;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(1.0f, 1.2f, 0.8f), addMaterial(s, glm::vec3(rho), glm::vec3(e)));
  SolverParams params;
  params.unshotFraction = 1e-3;
  const Solved r = solve(s, AtlasParams{.texelsPerQuad = 8}, params);
  const double expect = e / (1.0 - rho);
  testing::expectFurnace(r.atlas, r.result.radiosity, expect, 0.03, 0.01);
  EXPECT_LE(r.result.unshotFraction, 1e-3);
}

// emitted = absorbed + unshot + escaped after every shot; in a closed room almost nothing escapes and
// the unshot power only falls.
TEST(Solver, EnergyBookkeepingAtEveryShot) {
  Scene s;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f, 1.5f, 1.0f), addMaterial(s, glm::vec3(0.6f, 0.4f, 0.2f)));
  addRect(s, glm::vec3(0.8f, 0.5f, 0.99f), glm::vec3(0, 0.4f, 0), glm::vec3(0.4f, 0, 0),
          addMaterial(s, glm::vec3(0.0f), glm::vec3(10.0f)));
  SolverParams params;
  params.maxShots = 12;
  params.unshotFraction = 1e-4;
  const Solved r = solve(s, AtlasParams{.texelsPerQuad = 8}, params);
  ASSERT_EQ(r.result.history.size(), size_t(r.result.shots) + 1);
  EXPECT_EQ(r.result.shots, 12);
  const double emitted = r.result.history[0].emitted;
  EXPECT_NEAR(emitted, 10.0 * 0.16 * 3, 1e-4 * emitted);
  double previous = emitted * 1.0001;
  for (const EnergyTotals& e : r.result.history) {
    EXPECT_NEAR(e.absorbed + e.unshot + e.escaped(), emitted, 1e-4 * emitted);
    EXPECT_GE(e.escaped(), -0.01 * e.shot);
    EXPECT_LE(e.escaped(), 0.02 * e.shot);
    EXPECT_LT(e.unshot, previous);
    previous = e.unshot;
  }
  // The lamp hangs 1 cm under the ceiling's centre: the ceiling shoots from its visibility regions'
  // centres, not from behind the lamp, so its light is not lost either.
  EXPECT_GT(r.result.history.back().absorbed, 0.5 * emitted);
}

// SolveControls::acceptStop is asked at the unshot stop with the radiosity and residual so far; refused,
// the solve shoots on and asks again once the unshot share has fallen to kStopRecheck of it.
TEST(Solver, ARefusedStopShootsOnAndAsksAgain) {
  Scene s;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f, 1.5f, 1.0f), addMaterial(s, glm::vec3(0.6f)));
  addRect(s, glm::vec3(0.8f, 0.5f, 0.99f), glm::vec3(0, 0.4f, 0), glm::vec3(0.4f, 0, 0),
          addMaterial(s, glm::vec3(0.0f), glm::vec3(10.0f)));
  SolverParams params;
  params.unshotFraction = 0.05;
  const Solved plain = solve(s, AtlasParams{.texelsPerQuad = 8}, params);
  const LightmapAtlas& atlas = plain.atlas;  // the second solve builds the same one
  std::vector<double> asked;  // the unshot power (W, the residual summed over the atlas) at each ask
  SolveControls controls;
  controls.acceptStop = [&](const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual) {
    EXPECT_EQ(radiosity.size(), atlas.texelCount());
    double unshot = 0.0;
    for (size_t i = 0; i < residual.size(); ++i)
      if (atlas.patch[i] >= 0)
        unshot += double(residual[i].r + residual[i].g + residual[i].b) * atlas.area[i];
    asked.push_back(unshot);
    return asked.size() == 3;
  };
  const SolveResult refused = solve(s, AtlasParams{.texelsPerQuad = 8}, params, controls).result;
  EXPECT_EQ(plain.result.stopChecks, 0);
  ASSERT_EQ(refused.stopChecks, 3);
  ASSERT_EQ(asked.size(), 3u);
  const double plainUnshot = plain.result.energy.unshot;
  EXPECT_NEAR(asked[0], plainUnshot, 1e-3 * plainUnshot);  // first asked where plain stopped
  EXPECT_LE(asked[1], kStopRecheck * asked[0] * 1.001);
  EXPECT_LE(asked[2], kStopRecheck * asked[1] * 1.001);
  EXPECT_GT(refused.shots, plain.result.shots);
  EXPECT_NEAR(refused.energy.unshot, asked[2], 1e-3 * asked[2]);
}

TEST(Solver, Deterministic) {
  Scene s;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f, 1.5f, 1.0f), addMaterial(s, glm::vec3(0.7f)));
  addRect(s, glm::vec3(0.5f, 0.5f, 0.5f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.4f),
          addMaterial(s, glm::vec3(0.3f)));
  addRect(s, glm::vec3(0.8f, 0.5f, 0.99f), glm::vec3(0, 0.4f, 0), glm::vec3(0.4f, 0, 0),
          addMaterial(s, glm::vec3(0.0f), glm::vec3(5.0f)));
  SolverParams params;
  params.maxShots = 25;
  const Solved a = solve(s, AtlasParams{.density = 12.0f}, params);
  const Solved b = solve(s, AtlasParams{.density = 12.0f}, params);
  EXPECT_EQ(a.result.shots, b.result.shots);
  ASSERT_EQ(a.result.radiosity.size(), b.result.radiosity.size());
  EXPECT_EQ(0, std::memcmp(a.result.radiosity.data(), b.result.radiosity.data(),
                           a.result.radiosity.size() * sizeof(glm::vec3)));
}

// Culling the item buffers per hemicube face only leaves out triangles the rasterizer clips and keeps the
// rest in their order: the solve is bit-identical to drawing every triangle into every face. seed3 (columns,
// furniture, lamps; triangles across every face's edges) for its first 60 shots, strong ones with 16 eyes
// among them. Item buffers of 128²: the faces' edges clip the same triangles at any resolution, and the
// default 512² draws 16 times the pixels for the same check.
TEST(Solver, CulledItemBuffersAreBitIdentical) {
  const SeedScene seed = makeSeedScene(3);
  SolverParams params;
  params.maxShots = 60;
  params.itemBuffer = 128;
  const Solved culled = solve(seed.scene, AtlasParams{.density = 10.0f}, params);
  params.cullItemBuffers = false;
  const Solved drawn = solve(seed.scene, AtlasParams{.density = 10.0f}, params);
  EXPECT_EQ(culled.result.shots, drawn.result.shots);
  ASSERT_EQ(culled.result.radiosity.size(), drawn.result.radiosity.size());
  EXPECT_EQ(0, std::memcmp(culled.result.radiosity.data(), drawn.result.radiosity.data(),
                           culled.result.radiosity.size() * sizeof(glm::vec3)));
  EXPECT_EQ(culled.result.energy.unshot, drawn.result.energy.unshot);
}

TEST(Solver, RejectsBadParameters) {
  Scene s;
  addRect(s, glm::vec3(0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
          addMaterial(s, glm::vec3(0.5f), glm::vec3(1.0f)));
  SolverParams p;
  p.itemBuffer = 7;
  EXPECT_THROW(solve(s, AtlasParams{.texelsPerQuad = 4}, p), InputError);
  p = SolverParams{};
  p.unshotFraction = 0.0;
  EXPECT_THROW(solve(s, AtlasParams{.texelsPerQuad = 4}, p), InputError);
}

// An atlas whose per-texel buffers pass the driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE (llvmpipe: 128 MiB,
// 8.4 M RGBA32F texels) is refused before any buffer is made, naming the option that set its size
// (issue 15: --texels-per-quad 1024 ended in GL_OUT_OF_MEMORY after minutes). Only its size is set: the
// check comes before the per-texel arrays are read.
TEST(Solver, RefusesAnAtlasBeyondTheStorageBlockLimit) {
  Context ctx;
  EglContext context(ctx);
  ASSERT_GE(context.maxStorageBlockSize(), int64_t(1) << 27);  // the GL 4.3 minimum
  LightmapAtlas atlas;
  atlas.sizeParameter = "texels per quad";
  const int64_t texels = context.maxStorageBlockSize() / 16 + 1;
  atlas.width = 8192;
  atlas.height = int((texels + atlas.width - 1) / atlas.width);
  if (atlas.height > context.maxTextureSize()) GTEST_SKIP() << "the texture limit comes first on this driver";
  try {
    solveProgressive(Scene{}, atlas, SolverParams{}, context, ctx);
    ADD_FAILURE() << "an atlas of " << atlas.texelCount() << " texels was solved";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "texels per quad");
    EXPECT_NE(e.problem().find("the lightmap atlas of 8192x"), std::string::npos) << e.problem();
    EXPECT_NE(e.problem().find("more than this driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos)
        << e.problem();
  }
}

}  // namespace
}  // namespace cpgi
