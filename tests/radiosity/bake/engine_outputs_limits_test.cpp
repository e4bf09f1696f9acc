// --time-limit over the engine outputs' gathers (issue 48): the directional lightmap's and the probes'
// gathers stop at the deadline, and since a part of either would light some surfaces (or rooms) one way
// and the rest another, their files are not written: one warning each, report.json's outputs_skipped and
// partial say so, and every other file is written. The deadline is put in the past by the run's start, so
// nothing hangs on how fast the machine is; the same bake with time to spare writes both.
#include <chrono>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "radiosity/bake/bake.h"
#include "scenes/seed_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

BakeSettings directionalAndProbes(const std::filesystem::path& folder) {
  BakeSettings s = test::quickSeed1();
  s.output.engine.directional = true;
  s.output.engine.directionalRays = 16;
  s.output.engine.probes = true;
  s.output.engine.perObject = true;
  s.output.folder = folder;
  return s;
}

int warningsStarting(const Context& ctx, const std::string& start) {
  int n = 0;
  for (const std::string& w : ctx.warnings()) n += w.rfind(start, 0) == 0;
  return n;
}

TEST(EngineOutputLimits, PastTheTimeLimitTheDirectionalLightmapAndProbesAreLeftOutAndSaidSo) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = directionalAndProbes(dir / "out");
  s.limits.timeLimit = 1.0;
  BakeRun run;
  run.gl = &test::sharedGl();
  run.start = std::chrono::steady_clock::now() - std::chrono::seconds(10);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx, run);
  // No time for them: left out before their gathers start (planOutputs), said in one warning; the views
  // are made smaller instead.
  EXPECT_EQ(warningsStarting(ctx, "write: the time limit is too near for probes, directional"), 1);
  for (const char* f : {"lightmap_sh_l0.exr", "lightmap_sh_l1x.exr", "probes.json"})
    EXPECT_FALSE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  for (const char* f : {"lightmap_irradiance.exr", "baked.glb", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  EXPECT_TRUE(r.partial);
  std::ifstream in(dir / "out/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["outputs_skipped"], (std::vector<std::string>{"probes", "directional"}));
  EXPECT_TRUE(report["partial"].get<bool>());
  EXPECT_NE(report["partial_reason"].get<std::string>().find("no time for the directional"),
            std::string::npos)
      << report["partial_reason"];
  EXPECT_TRUE(report["engine_lightmap"]["directional"].contains("skipped"));
  EXPECT_FALSE(report["engine_lightmap"]["directional"].contains("object_files"));
  EXPECT_TRUE(report["engine_lightmap"]["probes"].contains("skipped"));
  // The per-object lightmaps are no gather: written whatever the time.
  for (const auto& o : report["engine_lightmap"]["objects"])
    EXPECT_TRUE(std::filesystem::exists(dir / ("out/" + o["exr"].get<std::string>()))) << o.dump();
}

TEST(EngineOutputLimits, WithinTheTimeLimitBothAreWritten) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = directionalAndProbes(dir / "out");
  s.limits.timeLimit = 3600.0;
  const BakeResult r = test::bakeHere(seed.scene, seed.cells, s);
  EXPECT_FALSE(r.partial);
  for (const char* f : {"lightmap_sh_l0.exr", "lightmap_sh_l1x.exr", "probes.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  EXPECT_TRUE(r.report["outputs_skipped"].empty());
}

}  // namespace
}  // namespace cpgi
