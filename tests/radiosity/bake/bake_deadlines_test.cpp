// --time-limit in the stages after the solve and before it (issue 46 item 3): the directional gather and
// the light probes stop at their deadline and write nothing, the density pilot is left out when its
// deadline has passed, and a solve stopped early keeps its books: what the surfaces absorbed, what left the
// scene and what it had not yet carried (unshot), said in report.json and in one warning. Every deadline
// here has passed before the stage starts, so nothing depends on the machine's speed.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/quads.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_limits.h"
#include "radiosity/cpu/ray_shot_engine.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/solve/solve.h"
#include "scenes/seed_scenes.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/radiosity/test_sky_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using Clock = std::chrono::steady_clock;

// A run whose time limit of one second passed ten seconds before the bake starts.
BakeRun pastTheLimit(BakeSettings& s) {
  s.limits.timeLimit = 1.0;
  BakeRun run;
  run.gl = &test::sharedGl();
  run.start = Clock::now() - std::chrono::seconds(10);
  return run;
}

int warningsStarting(const Context& ctx, const std::string& start) {
  int n = 0;
  for (const std::string& w : ctx.warnings()) n += w.rfind(start, 0) == 0;
  return n;
}

// A 4 m × 4 m grey floor under a small lamp, at 16 texels a metre.
struct LampOverFloor {
  Scene scene;
  LightmapAtlas atlas;
  LampOverFloor() {
    const uint32_t floor = testing::addMaterial(scene, glm::vec3(0.5f));
    const uint32_t lamp = testing::addMaterial(scene, glm::vec3(0.0f), glm::vec3(100.0f));
    testing::addRect(scene, {-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, floor);
    testing::addRect(scene, {0.9f, 2.2f, -0.6f}, {0.2f, 0, 0}, {0, 0, 0.2f}, lamp);
    Context ctx;
    AtlasParams p;
    p.density = 16.0f;
    atlas = buildAtlas(scene, findQuads(scene), p, ctx);
  }
};

// A bake past its limit with --directional and --probes: the solve stops, and the optional gathers (the
// probes, the directional gather) are left out before they start, since neither fits in the time left
// (planOutputs), while the views are made smaller and the first rendered: said in one warning, each gather
// named in outputs_skipped and report.json's reason, the gathers' files absent (a part-gathered one would
// light some surfaces one way and the rest another) and the required ones written; the outputs' estimate
// counted the gathers.
TEST(BakeDeadlines, PastTheLimitTheOptionalOutputsAreLeftOutAndTheReportSaysWhy) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = test::quickSeed1();
  s.output.folder = dir / "out";
  s.output.engine.directional = true;
  s.output.engine.probes = true;
  const BakeRun run = pastTheLimit(s);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  EXPECT_TRUE(r.partial);
  EXPECT_EQ(r.report["outputs_skipped"], nlohmann::json::array({"probes", "directional"}));
  const std::string why = r.report["partial_reason"];
  for (const char* part :
       {"shots with", "views were rendered", "no time for the directional", "no time for the probes"})
    EXPECT_NE(why.find(part), std::string::npos) << part << " in " << why;
  EXPECT_EQ(warningsStarting(ctx, "write: the time limit is too near for probes, directional"), 1);
  EXPECT_EQ(why.find("no time for the views"), std::string::npos) << why;
  EXPECT_EQ(warningsStarting(ctx, "directional lightmap: the time limit came after"), 0);  // not started
  EXPECT_EQ(warningsStarting(ctx, "probes: the time limit came"), 0);
  for (const char* f : {"baked.glb", "report.json", "lightmap.exr", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  for (const char* f : {"lightmap_sh_l0.exr", "probes.json"})
    EXPECT_FALSE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  EXPECT_GT(r.report["output_estimate_s"]["directional"].get<double>(), 0.0);
  EXPECT_GT(r.report["output_estimate_s"]["probes"].get<double>(), 0.0);
}

TEST(BakeDeadlines, TheGathersEstimateGrowsWithTheirRaysAndIsNoneWhenNotAsked) {
  const SeedScene seed = makeSeedScene(1);
  const std::vector<Camera> cameras = bake_steps::expectedCameras(seed.scene, seed.cells);
  EngineOutputParams engine;
  const bake_steps::OutputEstimate none =
      bake_steps::estimateOutputs(seed.scene, cameras, ViewParams{}, 10000, 12000, {1e-6, 1e-7}, engine);
  EXPECT_EQ(none.gatherSeconds(), 0.0);
  engine.directional = true;
  engine.probes = true;
  const bake_steps::OutputEstimate both =
      bake_steps::estimateOutputs(seed.scene, cameras, ViewParams{}, 10000, 12000, {1e-6, 1e-7}, engine);
  engine.directionalRays *= 4;
  engine.probeSpacing /= 2.0f;
  const bake_steps::OutputEstimate more =
      bake_steps::estimateOutputs(seed.scene, cameras, ViewParams{}, 10000, 12000, {1e-6, 1e-7}, engine);
  EXPECT_GT(both.directionalSeconds, 0.0);
  EXPECT_GT(both.probesSeconds, 0.0);
  EXPECT_GT(more.directionalSeconds, 3.0 * both.directionalSeconds);
  EXPECT_GT(more.probesSeconds, 4.0 * both.probesSeconds);
  EXPECT_DOUBLE_EQ(both.seconds() - none.seconds(), both.gatherSeconds());
}

// --density auto with its deadline passed: no pilot (its atlas, set-up and shot would all come after the
// limit); the output laid out at one even density, said once.
TEST(BakeDeadlines, PastTheLimitTheDensityPilotIsLeftOut) {
  const SeedScene seed = makeSeedScene(1);
  BakeSettings s = test::quickSeed1();
  s.atlas.densityAuto = true;
  const BakeRun run = pastTheLimit(s);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  EXPECT_EQ(warningsStarting(ctx, "auto density: the time limit came before the density pilot"), 1);
  EXPECT_TRUE(r.report["auto_density"].is_null());
  EXPECT_GT(r.atlas.validTexels(), 0u);
  EXPECT_TRUE(r.partial);
}

// The books of a bake stopped before its first shot, on every path its first step can take: the sky's
// light landed is emitted; what the floor absorbed, what it reflects (not yet carried: unshot) and what
// left the scene add up to it, none of them zero but the escape; report.json and one warning say so.
void expectStoppedBooks(BakeSettings s, const std::string& what) {
  SCOPED_TRACE(what);
  Scene box = testing::boxOpenToTheSky(0.5f, 0.5f);
  box.sky.kind = Sky::Kind::Uniform;
  box.sky.zenithRadiance = 3.0f;
  box.sky.gatherRays = 64;
  const BakeRun run = pastTheLimit(s);
  Context ctx;
  const BakeResult r = bake(box, CellGraph{}, s, ctx, run);
  const nlohmann::json& e = r.report["energy"];
  const double emitted = e["emitted_w"], absorbed = e["absorbed_w"], escaped = e["escaped_w"],
               unshot = e["unshot_w"];
  EXPECT_GT(emitted, 0.0);
  EXPECT_GT(absorbed, 0.1 * emitted);
  EXPECT_GT(unshot, 0.1 * emitted);
  EXPECT_NEAR(absorbed + escaped + unshot, emitted, 1e-3 * emitted);
  EXPECT_TRUE(e["stopped_early"].get<bool>());
  EXPECT_NEAR(e["unshot_share"].get<double>(), unshot / emitted, 1e-9);
  EXPECT_EQ(r.shots, 0);
  EXPECT_TRUE(r.partial);
  EXPECT_EQ(warningsStarting(ctx, "solve: the time limit stopped it after 0 shots"), 1);
}

// A solve whose deadline has passed before its engine's set-up (a minute of GL for a house's pilot on a
// loaded machine) sets nothing up: the first shot's light alone, its lamps unshot, the books whole.
TEST(BakeDeadlines, ASolvePastItsDeadlineSetsUpNoEngine) {
  const LampOverFloor s;
  GlShotEngine gl(test::sharedGl());
  SolverParams settings;
  settings.lampRays = 0;  // the lamps through the engine's item buffers, as the density pilot shoots them
  Context ctx;
  const SolveResult r =
      solveProgressive(s.scene, s.atlas, settings, gl, ctx, SolveControls{.deadline = Clock::now()});
  for (const Context::Timing& t : ctx.timings()) EXPECT_NE(t.stage, "solve: setup");
  EXPECT_TRUE(r.timedOut);
  EXPECT_EQ(r.shots, 0);
  EXPECT_GT(r.energy.emitted, 0.0);
  EXPECT_NEAR(r.energy.unshot, r.energy.emitted, 1e-6 * r.energy.emitted);  // the lamp's power, unshot
  EXPECT_EQ(r.radiosity.size(), s.atlas.texelCount());
}

TEST(BakeDeadlines, StoppedBeforeAnyShotTheEnergyIsAbsorbedEscapedAndUnshot) {
  BakeSettings s = test::quickSeed1();
  s.atlas.params.texelsPerQuad = 0;
  s.atlas.params.density = 8.0f;
  s.solver.solveDensity = 0.0f;
  expectStoppedBooks(s, "one level");
  s.solver.solveDensity = 2.0f;
  expectStoppedBooks(s, "two levels, the sky by the lamps' rays");
  s.solver.params.lampRays = 0;
  expectStoppedBooks(s, "two levels, the sky alone (no emitter: shootPunctualOnly)");
}

// The sky gather takes SolveControls::skyTimeShare of the time to the solve's deadline, the interreflection
// the rest: given all of it, a daylit map's gather of a million texels took a 600 s limit whole and the
// solve shot nothing. With a share of the hour that has passed before the gather's first chunk is traced
// (a few microseconds), the gather keeps its first pass and the solve still shoots, on both ways the first
// shot is made; with the whole hour, every ray. Nothing here waits for the deadline.
TEST(BakeDeadlines, TheSkyGatherLeavesTheSolveItsShareOfTheTime) {
  Scene box = testing::boxOpenToTheSky(0.5f, 0.5f);
  box.sky.kind = Sky::Kind::Uniform;
  box.sky.zenithRadiance = 3.0f;
  box.sky.gatherRays = 64;
  Context atlasCtx;
  AtlasParams p;
  p.density = 12.0f;
  const LightmapAtlas atlas = buildAtlas(box, findQuads(box), p, atlasCtx);
  RayShotEngine rays;
  SolveControls controls;
  controls.deadline = Clock::now() + std::chrono::hours(1);
  EXPECT_EQ(skyDeadline(controls), controls.deadline);  // the whole time unless a share is asked
  for (const double share : {1e-9, 1.0}) {
    SCOPED_TRACE(share);
    controls.skyTimeShare = share;
    const int stops = share < 1.0 ? 1 : 0;
    Context ctx;
    const SolveResult r = solveProgressive(box, atlas, SolverParams{}, rays, ctx, controls);
    EXPECT_EQ(warningsStarting(ctx, "sky light: the deadline came after 8 of 64 rays a texel"), stops);
    EXPECT_FALSE(r.timedOut);
    EXPECT_GT(r.shots, 0);
    EXPECT_NEAR(r.energy.absorbed + r.energy.escaped() + r.energy.unshot, r.energy.emitted,
                1e-3 * r.energy.emitted);
    Context first;
    const SolveResult byRays = shootFirstOnCpu(box, atlas, 4, first, controls);
    EXPECT_EQ(warningsStarting(first, "sky light: the deadline came after 8 of 64 rays a texel"), stops);
    EXPECT_GT(byRays.energy.emitted, 0.0);
  }
}

}  // namespace
}  // namespace cpgi
