// `cpgi info` on the seed scenes written by writeGltf: the numbers the tool prints are the scene's.
#include <sys/wait.h>

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/quads.h"
#include "core/scene_io.h"
#include "scenes/seed_scenes.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

int runCpgi(const test::TempDir& dir, const std::string& args, std::string& out, std::string& err) {
  const test::CommandRun r = test::cpgi(dir, args);
  out = r.out;
  err = r.err;
  return r.status;
}

TEST(InfoCommand, SeedScenesJsonMatchesTheScene) {
  test::TempDir dir;
  for (int level = 1; level <= 3; ++level) {
    const SeedScene seed = makeSeedScene(level);
    const std::string path = dir / ("seed" + std::to_string(level) + ".glb");
    GltfWriteOptions options;
    options.cells = &seed.cells;
    writeGltf(path, seed.scene, options);
    std::string out, err;
    ASSERT_EQ(runCpgi(dir, "info '" + path + "' --json", out, err), 0) << err;
    EXPECT_TRUE(err.empty()) << err;
    const nlohmann::json info = nlohmann::json::parse(out);
    for (const char* key : {"triangles", "quads", "loose_triangles", "materials", "emitters", "emitted_power",
                            "bounds", "cameras", "cells", "portals", "warnings"})
      EXPECT_TRUE(info.contains(key)) << key;
    const QuadSet quads = findQuads(seed.scene);
    EXPECT_EQ(info["triangles"], seed.scene.triangles.size());
    EXPECT_EQ(info["quads"], quads.quads.size());
    EXPECT_EQ(info["loose_triangles"], quads.looseTriangles());
    EXPECT_EQ(info["cameras"].size(), seed.scene.cameras.size());
    EXPECT_NEAR(info["emitted_power"][0].get<double>(), 200.0, 1e-3);  // two 1 m² lights at 100 W/m²
    ASSERT_EQ(info["emitters"].size(), 1u);
    EXPECT_NEAR(info["emitters"][0]["area_m2"].get<double>(), 2.0, 1e-5);
    ASSERT_EQ(info["cells"].size(), 3u);
    size_t inCells = 0;
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(info["cells"][c]["name"], seed.cells.cells[c].name);
      EXPECT_EQ(info["cells"][c]["triangles"], seed.cells.cells[c].triangles.size());
      inCells += info["cells"][c]["triangles"].get<size_t>();
    }
    EXPECT_EQ(inCells, seed.scene.triangles.size());
    ASSERT_EQ(info["portals"].size(), 2u);
    for (size_t p = 0; p < 2; ++p) {
      EXPECT_NEAR(info["portals"][p]["area_m2"].get<double>(), 2.1, 1e-5);
      EXPECT_NEAR(info["portals"][p]["normal"][0].get<double>(), 1.0, 1e-6);
      EXPECT_EQ(info["portals"][p]["cells"],
                nlohmann::json::array({seed.cells.cells[p].name, seed.cells.cells[p + 1].name}));
    }
    EXPECT_EQ(info["warnings"], nlohmann::json::array());
    EXPECT_NEAR(info["bounds"]["size"][1].get<double>(), 3.0, 1e-5);
  }
}

TEST(InfoCommand, TextModeNamesEveryPart) {
  test::TempDir dir;
  const SeedScene seed = makeSeedScene(1);
  GltfWriteOptions options;
  options.cells = &seed.cells;
  writeGltf(dir / "seed1.gltf", seed.scene, options);
  std::string out, err;
  ASSERT_EQ(runCpgi(dir, "info '" + (dir / "seed1.gltf") + "'", out, err), 0) << err;
  for (const char* part : {"triangles", "quads", "emitted power", "200 200 200 W", "cells          3",
                           "portals        2", "portal:A:B", "portal:B:C", "bounds"})
    EXPECT_NE(out.find(part), std::string::npos) << part << "\n" << out;
}

TEST(InfoCommand, HelpAndMissingArgument) {
  test::TempDir dir;
  std::string out, err;
  EXPECT_EQ(runCpgi(dir, "info --help", out, err), 0);
  EXPECT_NE(out.find("--repair"), std::string::npos);
  EXPECT_EQ(runCpgi(dir, "info", out, err), 1);
  EXPECT_FALSE(err.empty());
}

}  // namespace
}  // namespace cpgi
