// A bake inside its limits in every stage: --time-limit reached before the views (the lightmap, glb and
// report still written, the views skipped and said), during the decompositions, and --max-memory counting
// the sky gather and the views. The deadline is put in the past by the run's start, so what the report
// says does not hang on how fast the machine is.
#include <algorithm>
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
#include "radiosity/bake/cell_source.h"
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

// Past the limit before the outputs, the first view is still rendered, at kLimitedViewWidth and one ray a
// pixel (the user sees what was baked); the others are skipped and said once. Without the first view
// whatever the deadline, no view-*.png was written at all.
TEST(BakeLimits, PastTheTimeLimitTheFirstViewIsWrittenSmallAndTheRestSkipped) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = quick();
  s.output.folder = dir / "out";
  s.output.views.width = 640;
  const BakeRun run = pastTheLimit(s);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  for (const char* f : {"lightmap.exr", "lightmap.png", "baked.glb", "report.json", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  std::vector<std::string> views;
  for (const auto& e : std::filesystem::directory_iterator(dir / "out"))
    if (e.path().filename().string().rfind("view-", 0) == 0) views.push_back(e.path().filename().string());
  std::sort(views.begin(), views.end());
  EXPECT_EQ(views, (std::vector<std::string>{"view-A.exr", "view-A.png"}));
  EXPECT_EQ(readExr(dir / "out/view-A.exr").width, bake_steps::kLimitedViewWidth);
  EXPECT_EQ(r.report["view_width"].get<int>(), bake_steps::kLimitedViewWidth);
  EXPECT_TRUE(r.partial);
  EXPECT_EQ(r.report["views"], (std::vector<std::string>{"A"}));
  EXPECT_EQ(r.report["views_skipped"], (std::vector<std::string>{"B", "C"}));
  EXPECT_TRUE(r.report["partial"].get<bool>());
  EXPECT_NE(r.report["partial_reason"].get<std::string>().find("before 2 of 3 views"), std::string::npos)
      << r.report["partial_reason"];
  int viewWarnings = 0;
  for (const std::string& w : ctx.warnings()) viewWarnings += w.rfind("views: the time limit came", 0) == 0;
  EXPECT_EQ(viewWarnings, 1);
  EXPECT_TRUE(anyWarning(ctx, "views: the time limit leaves too little"));
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

// An atlas still being laid out at the limit stops part-way, at its first chart (the clock is looked at
// after every chart, not after a count of texels), and is laid out again at the least layout, 1/32 of the
// texels per metre, since a layout that filled nothing measured no rate to price a finer one: said in one
// warning, the sky gather stopping after its first pass, the result set written whole (its lightmap the
// least atlas's) and marked partial. Seed1 at 64 × 64 texels a quad is 172 032 texels; on main the layout
// filled 131 072 of them before it looked at the clock.
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
  EXPECT_TRUE(anyWarning(ctx, "atlas: the time limit came while laying out the lightmap (0 of"));
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

// The rooms' decomposition stops only between its stages, and a stage took 20-45 s at 2 % of a core: one
// whose estimate at the CPU share would end past its deadline is not started, said in one warning (here
// twice the hour it has); at an idle core's pace it runs and finds seed1's rooms.
TEST(BakeLimits, TheRoomsDecompositionEstimatedPastTheLimitIsNotStarted) {
  SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  Context layout;
  const bake_steps::BakeInput in = laidOut(seed, s, layout);
  const auto hour = std::chrono::steady_clock::now() + std::chrono::hours(1);
  const double idleSeconds = roomsCpuSeconds(seed.scene);
  ASSERT_GT(idleSeconds, 0.0);
  ASSERT_LT(roomsExtentCpuSeconds(seed.scene), 0.25 * idleSeconds);
  Context slow;
  const RoomLabels none =
      labelTexelsByRoom(seed.scene, "seed1", in.atlas, slow, {}, hour, 0, 7200.0 / idleSeconds);
  EXPECT_TRUE(none.graph.empty());
  EXPECT_TRUE(anyWarning(slow, "rooms: the decomposition into rooms, estimated at"));
  Context idle;
  const RoomLabels rooms = labelTexelsByRoom(seed.scene, "seed1", in.atlas, idle, {}, hour, 0, 1.0);
  EXPECT_EQ(rooms.graph.cells.size(), 3u);
}

// The estimate's own coarse pass ran 20 s past a map's limit at 0.09 of a core before it said the
// decomposition had no time: when that pass alone would end past the deadline (here a million times slower
// than idle against a minute), neither is made, said in one warning.
TEST(BakeLimits, TheRoomsEstimatePastTheLimitIsNotMade) {
  SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  Context layout;
  const bake_steps::BakeInput in = laidOut(seed, s, layout);
  const auto minute = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  Context slow;
  const RoomLabels none = labelTexelsByRoom(seed.scene, "seed1", in.atlas, slow, {}, minute, 0, 1e6);
  EXPECT_TRUE(none.graph.empty());
  EXPECT_TRUE(
      anyWarning(slow, "rooms: the decomposition into rooms would end past the time limit (its first"));
  EXPECT_FALSE(anyWarning(slow, "rooms: the decomposition into rooms, estimated at"));
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
  LoadedScene loaded = loadScene(scene);
  Context ctx;
  try {
    resolveCells("auto", scene, loaded, s.cells.decompose, s.input.load, ctx,
                 std::chrono::steady_clock::now());
    ADD_FAILURE() << "a cells bake past its time limit in the decomposition";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "time limit");
    EXPECT_NE(e.problem().find("decomposition of " + scene), std::string::npos) << e.problem();
  }
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
  EXPECT_GT(dark.base, 0.0);
  EXPECT_DOUBLE_EQ(dark.total(), dark.base + dark.atlas + dark.itemBuffers + dark.rayScene + dark.views);
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
  EXPECT_NEAR(both.total() - none.total(), both.gathers, 1.0);
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

// A limit whose time left (after the loading, when the bake read its scene) is under the least a bake
// writes (its least layout, its files and page, at the share of a core measured) is refused in one line
// with the least limit that would do; one over it is not.
TEST(BakeLimits, ALimitUnderTheLeastABakeWritesIsRefusedAtOnce) {
  bake_steps::LeastBake least{.seconds = 5.0, .layoutSeconds = 1.0, .texels = 1000, .share = 0.02};
  EXPECT_NO_THROW(bake_steps::requireTimeForMinimum(0.0, least));  // no limit
  EXPECT_NO_THROW(bake_steps::requireTimeForMinimum(6.0, least));
  try {
    bake_steps::requireTimeForMinimum(4.0, least);
    ADD_FAILURE() << "4 s for 5 s of the least bake";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--time-limit");
    EXPECT_NE(
        e.problem().find("at 2 % of a core: about 5 s for its least layout and its lightmap's files and "
                         "report at 1000 texels; at this load it needs at least 5 s; raise it"),
        std::string::npos)
        << e.problem();
  }
  least.spentSeconds = 3.0;  // 3 s of the limit went to the loading: 6 s no longer holds 5 s more
  try {
    bake_steps::requireTimeForMinimum(6.0, least);
    ADD_FAILURE() << "6 s, 3 s of them spent loading, for 5 s of the least bake";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("after 3 s of loading; at this load it needs at least 8 s"), std::string::npos)
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

// Clocks that say this process got `share` of a core over the `wall` seconds before the bake's first
// reading (a starved machine, without waiting for one), and no more CPU after.
struct StarvedClocks {
  CpuClocks clocks;
  CpuReading start;
};
StarvedClocks starvedClocks(double share, double wall) {
  const auto now = std::chrono::steady_clock::now();
  const auto before = now - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(wall));
  const double cpu = share * wall;
  return {[cpu] {
            return CpuReading{std::chrono::steady_clock::now(), cpu, cpu};
          },
          CpuReading{before, 0.0, 0.0}};
}

// The share of a core this bake gets is measured from the clocks, not capped: a bake read at a thousandth
// of a core (fake clocks) is told at once, after its loading, that its limit of 10 s cannot hold its least
// result there, naming the share, and writes nothing; read at a whole core the same limit holds it. The
// cap of 40 the load ratio had (2.5 % of a core) took the files of a bake at 1.5-2 % for a third of their
// time.
TEST(BakeLimits, ABakeReadAtAThousandthOfACoreIsRefusedAfterItsLoading) {
  const SeedScene seed =
      makeSeedScene(3);  // its thousands of triangles: a least bake of tens of seconds there
  test::TempDir dir;
  const std::string scene = dir / "seed3.glb";
  GltfWriteOptions withCells;
  withCells.cells = &seed.cells;
  writeGltf(scene, seed.scene, withCells);
  for (const double share : {1e-3, 1.0}) {
    SCOPED_TRACE(share);
    BakeSettings s = quick();
    s.input.scene = scene;
    s.limits.timeLimit = 10.0;
    s.output.folder = dir / (share < 1.0 ? "starved" : "whole");
    BakeRun run;
    run.gl = &test::sharedGl();
    const StarvedClocks clocks = starvedClocks(share, 1000.0);
    run.clocks = clocks.clocks;
    run.cpuAtStart = clocks.start;
    Context ctx;
    const std::filesystem::path report = std::filesystem::path(s.output.folder) / "report.json";
    if (share < 1.0) {
      try {
        bake(s, ctx, run);
        ADD_FAILURE() << "a 10 s limit at a thousandth of a core";
      } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--time-limit");
        EXPECT_NE(e.problem().find("at 0.1 % of a core"), std::string::npos) << e.problem();
        EXPECT_NE(e.problem().find("at this load it needs at least"), std::string::npos) << e.problem();
      }
      EXPECT_FALSE(std::filesystem::exists(report));
    } else {
      const BakeResult r = bake(s, ctx, run);
      EXPECT_GT(r.report["output_estimate_s"]["cpu_share"].get<double>(), 0.99);
      EXPECT_TRUE(std::filesystem::exists(report));
    }
  }
}

// A cells bake's two-level solve gets the bake's CPU share: at a thousandth of a core (fake clocks) its
// interreflection's set-up (about 0.05 CPU s on seed1: 50 s there) is estimated past the solve's deadline
// and not started, said in report.json. Its CellSolveParams carried no load before, and the set-up was
// estimated as on an idle machine.
TEST(BakeLimits, ACellsBakesTwoLevelSolveIsEstimatedAtTheBakesCpuShare) {
  const SeedScene seed = makeSeedScene(1);
  BakeSettings s = quick();
  s.cells.method = BakeMethod::Cells;
  s.solver.solveDensity = 2.0f;
  s.limits.timeLimit = 30.0;
  BakeRun run;
  run.gl = &test::sharedGl();
  const StarvedClocks starved = starvedClocks(1e-3, 1000.0);
  run.clocks = starved.clocks;
  run.cpuAtStart = starved.start;
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  EXPECT_EQ(r.report["indirect_setup"]["stopped"], "not started") << r.report["indirect_setup"];
  EXPECT_GT(r.report["indirect_setup"]["estimate_s"].get<double>(), 30.0);
}

// CpuShare from fake clocks: nothing said under kLeastCpuSeconds; the larger of the bake's own thread's
// share and the process's over every core; past a cap of 40 (a share of 0.45 % is a ratio of 222); and a
// load that rises seen within the window, whatever the bake's mean.
TEST(BakeLimits, TheCpuShareIsTheClocksOwnUncapped) {
  using namespace std::chrono;
  const auto t0 = steady_clock::now() - hours(1);
  CpuReading now{t0, 0.0, 0.0};
  const CpuClocks clocks = [&now] { return now; };
  const bake_steps::CpuShare meter(clocks, CpuReading{t0, 0.0, 0.0}, 2);
  now = {t0 + seconds(1), 0.01, 0.01};
  EXPECT_EQ(meter.share(), 0.0);  // a hundredth of a CPU second says nothing yet
  EXPECT_EQ(meter.ratio(), 1.0);
  EXPECT_EQ(meter.observed(), 0.0);
  now = {t0 + seconds(100), 0.5, 0.45};  // the process's 0.5 s over 2 cores; its own thread's 0.45 s
  EXPECT_NEAR(meter.share(), 0.0045, 1e-9);
  EXPECT_NEAR(meter.ratio(), 1.0 / 0.0045, 1e-6);
  now.thread = -1.0;  // no thread clock: the process's over every core
  EXPECT_NEAR(meter.share(), 0.0025, 1e-9);
  // A whole core for 100 s, then a hundredth of one for 20 s: the last window's share, not the mean.
  const bake_steps::CpuShare rising(clocks, CpuReading{t0, 0.0, 0.0}, 2);
  now = {t0 + seconds(100), 100.0, 100.0};
  EXPECT_NEAR(rising.share(), 1.0, 1e-9);
  now = {t0 + seconds(120), 100.2, 100.2};
  EXPECT_NEAR(rising.share(), 0.01, 1e-9);
}

// After a layout stopped, the finest scale whose layout (at the first attempt's measured rate, with room
// to spare) and files fit in half the time left, else the least layout; with no rate measured, the least.
TEST(BakeLimits, AStoppedLayoutGoesStraightToTheScaleItsRateFits) {
  const bake_steps::LayoutCost cost{
      .chartSeconds = 1.0, .texelSeconds = 1e-5, .texels = 1000000, .charts = 1000};
  const AtlasParams params;  // 2 texels a chart's edge at least, 1 of gutter: 16 texels a chart
  EXPECT_EQ(bake_steps::coarseTexels(cost, params, 2), 250000u + 16000u);
  EXPECT_NEAR(bake_steps::coarseLayoutSeconds(cost, params, 2), 2.0 * (1.0 + 2.66), 1e-9);
  const auto files = [](size_t texels) { return 1e-5 * double(texels); };
  // Planned in half the time left: the stages before the files cannot stop either.
  EXPECT_EQ(bake_steps::coarseningThatFits(cost, params, 20.0, files), 2);  // 7.32 + 2.66 s
  EXPECT_EQ(bake_steps::coarseningThatFits(cost, params, 10.0, files), 4);  // 3.57 + 0.785 s
  EXPECT_EQ(bake_steps::coarseningThatFits(cost, params, 6.0, files), 8);
  EXPECT_EQ(bake_steps::coarseningThatFits(cost, params, 5.4, files), 16);
  EXPECT_EQ(bake_steps::coarseningThatFits(cost, params, 2.0, files), bake_steps::kMostCoarsening);
  bake_steps::LayoutCost unmeasured = cost;
  unmeasured.texelSeconds = 0.0;  // stopped before its first chart was filled
  EXPECT_EQ(bake_steps::coarseningThatFits(unmeasured, params, 1e6, files), bake_steps::kMostCoarsening);
  // From the stop itself: its fill's rate, its charts' seconds.
  const bake_steps::LayoutCost measured =
      bake_steps::stoppedLayoutCost(AtlasLayoutStopped(2000, 10000, 50, 0.5, 0.1));
  EXPECT_DOUBLE_EQ(measured.texelSeconds, 0.1 / 2000.0);
  EXPECT_DOUBLE_EQ(measured.chartSeconds, 0.5);
  EXPECT_EQ(measured.charts, 50u);
}

// The layout looks at the clock after every chart: past its deadline even a small atlas stops at once, with
// what it took so far (on main it filled 131 072 texels before its first look, so seed1 was laid out whole).
TEST(BakeLimits, PastItsDeadlineALayoutStopsAtItsFirstChart) {
  const SeedScene seed = makeSeedScene(1);
  Context ctx;
  const QuadSet quads = findQuads(seed.scene);
  try {
    buildAtlas(seed.scene, quads, AtlasParams{}, ctx, {}, std::chrono::steady_clock::now());
    ADD_FAILURE() << "laid out past its deadline";
  } catch (const AtlasLayoutStopped& stopped) {
    EXPECT_EQ(stopped.filledTexels, 0u);
    EXPECT_GT(stopped.texels, 0u);
    EXPECT_GT(stopped.charts, 0u);
    EXPECT_GE(stopped.chartSeconds, 0.0);
  }
  EXPECT_NO_THROW(buildAtlas(seed.scene, quads, AtlasParams{}, ctx));  // no deadline: whole
}

// A limit that passes while the scene is read ends the bake there, in one line naming the file and how far
// the reading came, before anything is written.
TEST(BakeLimits, ALimitPassingWhileTheSceneIsReadEndsTheBakeThere) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  writeGltf(scene, seed.scene);
  LoadOptions past;
  past.deadline = std::chrono::steady_clock::now();
  try {
    loadScene(scene, past);
    ADD_FAILURE() << "read past its deadline";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "time limit");
    EXPECT_NE(e.problem().find("came while " + scene + " was read (parsed, no mesh read yet)"),
              std::string::npos)
        << e.problem();
  }
  BakeSettings s = quick();
  s.input.scene = scene;
  s.output.folder = dir / "out";
  Context ctx;
  EXPECT_THROW(bake(s, ctx, pastTheLimit(s)), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json"));
  EXPECT_NO_THROW(loadScene(scene));  // no deadline
}

}  // namespace
}  // namespace cpgi
