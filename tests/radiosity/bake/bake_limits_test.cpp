// A bake inside its limits in every stage: --time-limit reached before the views (the lightmap, glb and
// report still written, the views skipped and said), during the decompositions, and --max-memory counting
// the sky gather and the views. The deadline is put in the past by the run's start, so what the report
// says does not hang on how fast the machine is.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "core/scene_io.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_limits.h"
#include "radiosity/bake/bake_steps.h"
#include "scenes/seed_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

BakeSettings quick() {
  return test::quickSeed1();
}

// A run whose time limit of one second passed ten seconds before the bake starts.
BakeRun pastTheLimit(BakeSettings& s) {
  s.limits.timeLimit = 1.0;
  BakeRun run;
  run.gl = &test::sharedGl();
  run.start = std::chrono::steady_clock::now() - std::chrono::seconds(10);
  return run;
}

// `seed`'s bake input with its atlas laid out by `s`.
bake_steps::BakeInput laidOut(SeedScene& seed, const BakeSettings& s, Context& ctx) {
  bake_steps::BakeInput in;
  in.scene = &seed.scene;
  in.cells = &seed.cells;
  bake_steps::buildBakeAtlas(s, in, nullptr, ctx);
  return in;
}

bool anyWarning(const Context& ctx, const std::string& start) {
  for (const std::string& w : ctx.warnings())
    if (w.rfind(start, 0) == 0) return true;
  return false;
}

TEST(BakeLimits, PastTheTimeLimitTheViewsAreSkippedAndTheRestIsWritten) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = quick();
  s.output.folder = dir / "out";
  const BakeRun run = pastTheLimit(s);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  for (const char* f : {"lightmap.exr", "lightmap.png", "baked.glb", "report.json", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  for (const auto& e : std::filesystem::directory_iterator(dir / "out"))
    EXPECT_NE(e.path().filename().string().rfind("view-", 0), 0u) << e.path();
  EXPECT_TRUE(r.partial);
  EXPECT_TRUE(r.report["views"].empty());
  EXPECT_EQ(r.report["views_skipped"], (std::vector<std::string>{"A", "B", "C"}));
  EXPECT_TRUE(r.report["partial"].get<bool>());
  EXPECT_NE(r.report["partial_reason"].get<std::string>().find("before 3 of 3 views"), std::string::npos)
      << r.report["partial_reason"];
  int viewWarnings = 0;
  for (const std::string& w : ctx.warnings()) viewWarnings += w.rfind("views: the time limit", 0) == 0;
  EXPECT_EQ(viewWarnings, 1);
  // The outputs' share was estimated and kept back from the solve.
  EXPECT_GT(r.report["output_estimate_s"]["views"].get<double>(), 0.0);
  EXPECT_GT(r.report["output_estimate_s"]["files"].get<double>(), 0.0);
  std::ifstream in(dir / "out/report.json");
  EXPECT_EQ(nlohmann::json::parse(in)["views_skipped"], r.report["views_skipped"]);
}

TEST(BakeLimits, WithinTheTimeLimitEveryViewIsRendered) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = quick();
  s.output.folder = dir / "out";
  s.limits.timeLimit = 3600.0;
  const BakeResult r = test::bakeHere(seed.scene, seed.cells, s);
  EXPECT_EQ(r.report["views"].size(), 3u);
  EXPECT_TRUE(r.report["views_skipped"].empty());
  EXPECT_FALSE(r.partial);
}

// A large atlas still being laid out at the limit stops part-way and is laid out again coarse: at a
// quarter of the texels per metre, then by halves while its files and report would not be written by the
// limit (here never: the limit is past), down to 1/32; and the sky gather stops after its first pass: each
// said in one warning, the result set written whole (its lightmap the coarse atlas's) and marked partial.
// Seed1 at 64 × 64 texels a quad is 172 032 texels, past the atlas's first deadline check
// (kAtlasDeadlineTexels).
TEST(BakeLimits, TheAtlasLayoutAndTheFirstSkyPassStopAtTheTimeLimit) {
  SeedScene seed = makeSeedScene(1);
  seed.scene.sky.kind = Sky::Kind::Uniform;
  seed.scene.sky.zenithRadiance = 10.0f;
  test::TempDir dir;
  BakeSettings s = quick();
  s.atlas.params.texelsPerQuad = 64;
  s.output.folder = dir / "out";
  const BakeRun run = pastTheLimit(s);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  EXPECT_TRUE(anyWarning(ctx, "atlas: the time limit came while laying out the lightmap"));
  EXPECT_TRUE(anyWarning(ctx, "atlas: the time limit came while laying out the lightmap (131072 of"));
  int coarsened = 0;
  for (const std::string& w : ctx.warnings())
    coarsened += w.find("laid out again at 1/32 of the texels") != w.npos;
  EXPECT_EQ(coarsened, 1);
  // The coarsest atlas's texels are one chunk of the sky's first pass, which runs whole.
  EXPECT_TRUE(anyWarning(ctx, "sky light: the deadline came after 8 of"));
  // The coarse layout: 2 × 2 texels a quad (64 / 32).
  Context whole;
  bake_steps::BakeInput in;
  in.scene = &seed.scene;
  in.cells = &seed.cells;
  BakeSettings coarse = quick();
  coarse.atlas.params.texelsPerQuad = 2;
  bake_steps::buildBakeAtlas(coarse, in, nullptr, whole);
  EXPECT_EQ(r.report["texels"].get<size_t>(), in.atlas.validTexels());
  EXPECT_LT(r.report["texels"].get<size_t>(), kAtlasDeadlineTexels);
  EXPECT_TRUE(r.partial);
  std::ifstream written(dir / "out/report.json");
  const nlohmann::json report = nlohmann::json::parse(written);
  EXPECT_EQ(report["texels"], r.report["texels"]);
  EXPECT_TRUE(report["partial"].get<bool>());
  const ImageRGB lightmap = readExr(dir / "out/lightmap.exr");
  EXPECT_EQ(size_t(lightmap.width) * size_t(lightmap.height), in.atlas.texelCount());
  for (const char* f : {"lightmap.png", "baked.glb", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
}

// A scene without cells is labelled by its automatic rooms; past the limit the decomposition stops at its
// first stage and the scene is one room, said once.
TEST(BakeLimits, TheRoomsDecompositionStopsAtTheTimeLimit) {
  const SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  Context ctx;
  const BakeResult limited = bake(seed.scene, CellGraph{}, s, ctx, pastTheLimit(s));
  EXPECT_TRUE(anyWarning(ctx, "rooms: the time limit came during the decomposition"));
  EXPECT_TRUE(limited.cellNames.empty());
  BakeSettings unlimited = quick();
  const BakeResult r = test::bakeHere(seed.scene, CellGraph{}, unlimited);
  EXPECT_EQ(r.cellNames.size(), 3u);  // the three rooms, when there is time
}

// The rooms' decomposition takes what the bake's own buffers leave of --max-memory (a room 1e5 m wide
// peaked at 3.8 GB under --max-memory 2G): left too little, it is not made, said in one warning, and the
// bake goes on with the scene as one room.
TEST(BakeLimits, TheRoomsDecompositionTakesWhatTheBakeLeavesOfTheMemoryLimit) {
  SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  Context layout;
  const BakeSettings resolved = bake_steps::resolved(s);
  const bake_steps::BakeInput in = laidOut(seed, resolved, layout);
  const double own = bake_steps::bakeMemory(resolved, seed.scene, in.atlas, 0.0).total();
  s.limits.maxMemory = uint64_t(own) + (uint64_t(1) << 20);  // a megabyte left: no decomposition's grid
  BakeRun run;
  run.gl = &test::sharedGl();
  Context ctx;
  const BakeResult r = bake(seed.scene, CellGraph{}, s, ctx, run);
  EXPECT_TRUE(anyWarning(ctx, "rooms: the decomposition's grid")) << "no warning of the rooms' memory";
  EXPECT_TRUE(r.cellNames.empty());
  EXPECT_FALSE(r.partial);
}

// A cells bake of `--cells auto` cannot go on without its cells: one line naming the time limit.
TEST(BakeLimits, TheCellsDecompositionPastTheTimeLimitIsRefusedInOneLine) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  writeGltf(scene, seed.scene);
  BakeSettings s = quick();
  s.input.scene = scene;
  s.cells.method = BakeMethod::Cells;
  s.cells.source = "auto";
  Context ctx;
  try {
    bake(s, ctx, pastTheLimit(s));
    ADD_FAILURE() << "a cells bake past its time limit in the decomposition";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "time limit");
    EXPECT_NE(e.problem().find("decomposition of " + scene), std::string::npos) << e.problem();
  }
  EXPECT_TRUE(anyWarning(ctx, "load: the time limit came while"));
}

// The memory model counts the sky gather and the largest view besides the atlas and the item buffers.
TEST(BakeLimits, MemoryCountsTheSkyGatherAndTheViews) {
  SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  Context ctx;
  bake_steps::BakeInput in = laidOut(seed, s, ctx);
  const double view = viewBytes(ViewSize{640, 480});
  const bake_steps::BakeMemory dark = bake_steps::bakeMemory(s, seed.scene, in.atlas, view);
  EXPECT_EQ(dark.skyGather, 0.0);
  EXPECT_EQ(dark.views, view);
  EXPECT_GT(dark.rayScene, 0.0);
  EXPECT_DOUBLE_EQ(dark.total(), dark.atlas + dark.itemBuffers + dark.rayScene + dark.views);
  seed.scene.sky.zenithRadiance = 10.0f;
  ASSERT_TRUE(seed.scene.sky.lights());
  const bake_steps::BakeMemory daylit = bake_steps::bakeMemory(s, seed.scene, in.atlas, view);
  EXPECT_GE(daylit.skyGather, 24.0 * double(in.atlas.validTexels()));
}

// --directional and --probes count too: the gather's floats a texel with its own ray scene, the probes'
// voxels over the scene's bounds; the larger of the two (one runs after the other), and a limit they pass
// is refused naming the one asked for.
TEST(BakeLimits, MemoryCountsTheDirectionalGatherAndTheProbes) {
  SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  Context ctx;
  bake_steps::BakeInput in = laidOut(seed, s, ctx);
  const bake_steps::BakeMemory none = bake_steps::bakeMemory(s, seed.scene, in.atlas, 0.0);
  EXPECT_EQ(none.gathers, 0.0);
  s.output.engine.directional = true;
  const bake_steps::BakeMemory directional = bake_steps::bakeMemory(s, seed.scene, in.atlas, 0.0);
  EXPECT_GE(directional.gathers, 60.0 * double(in.atlas.texelCount()));
  s.output.engine.directional = false;
  s.output.engine.probes = true;
  const bake_steps::BakeMemory probes = bake_steps::bakeMemory(s, seed.scene, in.atlas, 0.0);
  // seed1's bounds, 12.4 × 3 × 4 m, at 0.1 m voxels: 150 000 voxels or more.
  EXPECT_GE(probes.gathers, 150000.0);
  s.output.engine.directional = true;
  const bake_steps::BakeMemory both = bake_steps::bakeMemory(s, seed.scene, in.atlas, 0.0);
  EXPECT_DOUBLE_EQ(both.gathers, std::max(directional.gathers, probes.gathers));
  EXPECT_DOUBLE_EQ(both.total() - none.total(), both.gathers);
  s.atlas.params.memoryLimit = uint64_t(none.total() + 0.5 * both.gathers);
  try {
    bake_steps::requireBakeMemory(s, seed.scene, bake_steps::expectedCameras(seed.scene, seed.cells),
                                  in.atlas, ctx);
    ADD_FAILURE() << "a limit the gathers pass";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--probes");
    EXPECT_NE(e.problem().find("leave out --probes"), std::string::npos) << e.problem();
  }
}

// Views larger than what --max-memory leaves after the solve shrink to fit, said in one warning; a limit
// the solve alone passes is refused naming what to lower.
TEST(BakeLimits, ViewsShrinkToTheMemoryLeftAndTheRestIsRefused) {
  SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  s.output.views.width = 8192;
  s.output.views.height = 8192;  // 2 GiB a view
  Context ctx;
  bake_steps::BakeInput in = laidOut(seed, s, ctx);
  const bake_steps::BakeMemory m = bake_steps::bakeMemory(s, seed.scene, in.atlas, 0.0);
  const double rest = m.total();
  s.atlas.params.memoryLimit = uint64_t(rest + 8.0 * (1 << 20));  // 8 MiB for the views
  const std::vector<Camera> cameras = bake_steps::expectedCameras(seed.scene, seed.cells);
  const ViewParams fitted = bake_steps::requireBakeMemory(s, seed.scene, cameras, in.atlas, ctx);
  EXPECT_LT(fitted.width, 8192);
  EXPECT_EQ(fitted.width, fitted.height);  // the shape asked for kept
  EXPECT_LE(viewBytes(viewSize(cameras.front(), fitted)), 8.0 * (1 << 20));
  EXPECT_TRUE(anyWarning(ctx, "views: pictures"));
  s.atlas.params.memoryLimit = uint64_t(rest / 2.0);
  try {
    bake_steps::requireBakeMemory(s, seed.scene, cameras, in.atlas, ctx);
    ADD_FAILURE() << "a limit of half the solve's memory";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "item buffer");  // seed1's coarse atlas takes less than its item buffers
    EXPECT_NE(e.problem().find("lower `item buffer` or raise `maximum memory`"), std::string::npos)
        << e.problem();
  }
}

// The optional outputs are dropped before the required ones, in the order views, probes, directional:
// with time for the files and the page alone nothing optional is started; each more second keeps one
// more, the directional gather first. No time asked for the views (no cameras) drops nothing for them.
TEST(BakeLimits, TheOptionalOutputsAreDroppedFirstViewsThenProbesThenDirectional) {
  bake_steps::OutputEstimate e;
  e.views = 3;
  e.filesSeconds = 2.0, e.pageSeconds = 1.0;
  e.directionalSeconds = 4.0, e.probesSeconds = 2.0, e.viewSeconds = 5.0;
  EngineOutputParams both;
  both.directional = true, both.probes = true;
  using Skipped = std::vector<std::string>;
  const auto plan = [&](double left) { return bake_steps::planOutputs(left, e, true, both); };
  EXPECT_EQ(plan(3.0).skipped, (Skipped{"views", "probes", "directional"}));  // the files and page alone
  EXPECT_EQ(plan(2.0).skipped, (Skipped{"views", "probes", "directional"}));  // not even those: still planned
  EXPECT_EQ(plan(7.0).skipped, (Skipped{"views", "probes"}));
  EXPECT_TRUE(plan(7.0).directional);
  EXPECT_EQ(plan(9.0).skipped, (Skipped{"views"}));
  EXPECT_TRUE(plan(9.0).probes && plan(9.0).directional && !plan(9.0).views);
  EXPECT_TRUE(plan(14.0).skipped.empty());
  EXPECT_TRUE(plan(14.0).views && plan(14.0).probes && plan(14.0).directional);
  // Not asked, not planned and not said.
  const bake_steps::OutputPlan none = bake_steps::planOutputs(0.0, e, false, EngineOutputParams{});
  EXPECT_TRUE(none.skipped.empty());
  EXPECT_FALSE(none.views || none.probes || none.directional);
}

// A limit under the least a bake writes (its files and page at the coarsest atlas, at this machine's
// costs) is refused in one line before anything runs; one over it is not.
TEST(BakeLimits, ALimitUnderTheLeastABakeWritesIsRefusedAtOnce) {
  EXPECT_NO_THROW(bake_steps::requireTimeForMinimum(0.0, 5.0, 1000));  // no limit
  EXPECT_NO_THROW(bake_steps::requireTimeForMinimum(6.0, 5.0, 1000));
  try {
    bake_steps::requireTimeForMinimum(4.0, 5.0, 1000);
    ADD_FAILURE() << "4 s for 5 s of files";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--time-limit");
    EXPECT_NE(e.problem().find("about 5 s for its lightmap's files and report at 1000 texels; raise it"),
              std::string::npos)
        << e.problem();
  }
  const SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  s.limits.timeLimit = 1e-6;
  test::TempDir dir;
  s.output.folder = dir / "out";
  Context ctx;
  BakeRun run;
  run.gl = &test::sharedGl();
  EXPECT_THROW(bake(seed.scene, seed.cells, s, ctx, run), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json"));
}

// The load ratio: 1 with no CPU spent yet or on a machine that gave the bake its cores; more when the
// wall ran on while this process got no CPU (a sleep stands for the other processes' share).
TEST(BakeLimits, TheLoadMeterSeesWallTimeWithoutCpu) {
  const bake_steps::LoadMeter idle;
  EXPECT_EQ(idle.ratio(), 1.0);  // under a tenth of a CPU second: nothing to say
  const bake_steps::LoadMeter meter;
  const double cpu0 = bake_steps::processCpuSeconds();
  volatile double sink = 0.0;
  while (bake_steps::processCpuSeconds() - cpu0 < 0.15) sink = sink + 1.0;
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  EXPECT_GT(meter.ratio(), 2.0);  // 0.15 s of CPU over at least 0.75 s of wall, on at least one core
  EXPECT_LE(meter.ratio(), bake_steps::kMostLoadRatio);
}

}  // namespace
}  // namespace cpgi
