// Every baked.glb (and the scenes, cells.glb) passes the Khronos glTF validator with no error: a bake of
// each seed and stability scene, a cells bake whose glb carries portals, a reference and a decomposition.
#include <gtest/gtest.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/core/html_report/node_tools.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

// Validates `files`; every file must have 0 errors. Prints the validator's figures per file.
void expectValid(const test::TempDir& dir, const std::vector<std::filesystem::path>& files) {
  std::string args;
  for (const auto& f : files) args += " " + quote(f.string());
  const test::CommandRun r = test::runNodeScript(dir.path(), "validate_glb.mjs", args);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  std::istringstream lines(r.out);
  size_t seen = 0;
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json j = nlohmann::json::parse(line);
    ++seen;
    std::cout << std::filesystem::path(j["file"].get<std::string>()).lexically_relative(dir.path()).string()
              << ": " << j["errors"] << " errors, " << j["warnings"] << " warnings, " << j["infos"]
              << " infos, " << j["hints"] << " hints\n";
    EXPECT_EQ(j["errors"], 0) << j.dump(1);
  }
  EXPECT_EQ(seen, files.size()) << r.err;
}

class GltfValidator : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string missing = test::missingNodeTools();
    if (!missing.empty()) GTEST_SKIP() << "SKIPPED, NOT TESTED: the glTF validator cannot run: " << missing;
  }
  test::TempDir dir;
};

TEST_F(GltfValidator, BakedSeedAndStabilityScenesHaveNoErrors) {
  std::vector<std::filesystem::path> files;
  for (const char* name : {"seed1", "seed2", "seed3", "spot-door", "thin-wall", "thin-wall-5cm"}) {
    const std::string scene = dir / (std::string(name) + ".glb"), out = dir / name;
    ASSERT_EQ(cpgi(dir, std::string("generate ") + name + " -o " + quote(scene)).status, 0) << name;
    // A coarse atlas and small item buffers: the glb's structure is what is checked, not the light.
    const test::CommandRun r = cpgi(
        dir, "bake " + quote(scene) + " -o " + quote(out) + " --density 2 --unshot 0.2 --item-buffer 64 -q");
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    files.push_back(scene);
    files.push_back(std::filesystem::path(out) / "baked.glb");
  }
  expectValid(dir, files);
}

TEST_F(GltfValidator, CellsBakeReferenceAndDecompositionHaveNoErrors) {
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  test::CommandRun r =
      cpgi(dir, "bake " + quote(scene) + " -o " + quote(dir / "cells") + " --method cells --cells " +
                    quote(scene) + " --density 2 --unshot 0.2 --item-buffer 64 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  r = cpgi(dir, "reference " + quote(scene) + " -o " + quote(dir / "reference") + " --density 2 --spp 2 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  r = cpgi(dir, "decompose " + quote(scene) + " -o " + quote(dir / "decomposition"));
  ASSERT_EQ(r.status, 0) << r.err;
  expectValid(dir, {dir / "cells/baked.glb", dir / "reference/baked.glb", dir / "decomposition/cells.glb"});
}

}  // namespace
}  // namespace cpgi
