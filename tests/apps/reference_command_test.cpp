// End-to-end: `cpgi reference` and `cpgi compare-light` on a small closed box written to a .glb.
#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "tests/support/run_cpgi.h"

#include "core/image_io.h"
#include "core/scene_io.h"
#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;

using RunResult = test::CommandRun;

RunResult runCpgi(const std::string& args, const fs::path& dir) {
  return test::cpgi(dir, args);
}

class ReferenceCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cpgi_reference_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A closed 2 m box, every face with albedo ρ and emission E: the white furnace, B = E / (1 − ρ).
  fs::path writeFurnace(float albedo, float emission) {
    Scene scene;
    SceneBuilder b(scene);
    const uint32_t m = b.material("furnace", glm::vec3(albedo), glm::vec3(emission));
    const uint32_t node = b.node("box");
    const float s = 2.0f;
    const glm::vec3 X(s, 0, 0), Y(0, s, 0), Z(0, 0, s), o(0.0f);
    b.quad(o, X, Y, m, node);
    b.quad(o + Z, Y, X, m, node);
    b.quad(o, Y, Z, m, node);
    b.quad(o + X, Z, Y, m, node);
    b.quad(o, Z, X, m, node);
    b.quad(o + Y, X, Z, m, node);
    const fs::path path = dir_ / "furnace.glb";
    writeGltf(path.string(), scene);
    return path;
  }

  fs::path dir_;
};

TEST_F(ReferenceCommand, FurnaceEndToEnd) {
  const fs::path scene = writeFurnace(0.5f, 1.0f);
  const fs::path out = dir_ / "ref";
  const RunResult r =
      runCpgi("reference " + scene.string() + " -o " + out.string() + " --texels-per-quad 4 --spp 256", dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name :
       {"lightmap.exr", "lightmap.png", "report.json", "baked.glb", "view-overview.png", "view-overview.exr"})
    EXPECT_TRUE(fs::exists(out / name)) << name;

  std::vector<ExrChannel> extra;
  const ImageRGB lightmap = readExr((out / "lightmap.exr").string(), &extra);
  const std::vector<float>* area = nullptr;
  const std::vector<float>* sigma = nullptr;
  for (const ExrChannel& c : extra) {
    if (c.name == "area") area = &c.values;
    if (c.name == "stderr") sigma = &c.values;
  }
  ASSERT_TRUE(area && sigma);
  int valid = 0;
  double totalArea = 0.0;
  for (size_t i = 0; i < lightmap.pixels.size(); ++i) {
    if ((*area)[i] <= 0.0f) continue;
    ++valid;
    totalArea += (*area)[i];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lightmap.pixels[i][c], 2.0f, 6.0f * (*sigma)[i] + 1e-4f) << i;
    EXPECT_LT((*sigma)[i], 0.1f);
  }
  EXPECT_EQ(valid, 6 * 16);
  EXPECT_NEAR(totalArea, 24.0, 1e-3);

  std::ifstream in(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["method"], "reference");
  EXPECT_EQ(report["texels"], 96);
  EXPECT_EQ(report["spp"], 256);
  EXPECT_EQ(report["cells"], 1);
  EXPECT_EQ(report["portals"], 0);
  EXPECT_EQ(report["shots"], 0);
  EXPECT_EQ(report["unshot_fraction"], 0.0);
  EXPECT_GT(report["seconds"].get<double>(), 0.0);
  EXPECT_GE(report["seconds"].get<double>(), report["solve_seconds"].get<double>());
  EXPECT_GT(report["noise"].get<double>(), 0.0);
  EXPECT_LT(report["noise"].get<double>(), 0.02);

  // The glb loads back with the same triangles.
  EXPECT_EQ(loadScene((out / "baked.glb").string()).scene.triangles.size(), 12u);
}

TEST_F(ReferenceCommand, CompareLightAgainstItselfAndAnotherSeed) {
  const fs::path scene = writeFurnace(0.6f, 2.0f);
  const fs::path a = dir_ / "a", b = dir_ / "b";
  const std::string common = " --texels-per-quad 4 --spp 64 -q";
  ASSERT_EQ(runCpgi("reference " + scene.string() + " -o " + a.string() + common + " --seed 1", dir_).status,
            0);
  ASSERT_EQ(runCpgi("reference " + scene.string() + " -o " + b.string() + common + " --seed 2", dir_).status,
            0);

  RunResult r = runCpgi("compare-light " + a.string() + " " + a.string() + " --json", dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rel_rmse"], 0.0);
  EXPECT_EQ(j["max_abs"], 0.0);
  EXPECT_EQ(j["texels"], 96);

  // Two independent runs differ by about their combined noise, sqrt(2)·noise: the noise is honest.
  r = runCpgi("compare-light " + a.string() + " " + b.string() + " --json", dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  const double noise = j["reference_noise"].get<double>();
  EXPECT_GT(noise, 0.0);
  EXPECT_GT(j["rel_rmse"].get<double>(), 0.6 * std::sqrt(2.0) * noise);
  EXPECT_LT(j["rel_rmse"].get<double>(), 1.6 * std::sqrt(2.0) * noise);
  EXPECT_LT(std::abs(j["rel_mean_error"].get<double>()), 4.0 * noise);
}

TEST_F(ReferenceCommand, UserErrorsExitOne) {
  const fs::path scene = writeFurnace(0.5f, 1.0f);
  const fs::path a = dir_ / "a", b = dir_ / "b";
  ASSERT_EQ(
      runCpgi("reference " + scene.string() + " -o " + a.string() + " --texels-per-quad 2 --spp 16 -q", dir_)
          .status,
      0);
  ASSERT_EQ(
      runCpgi("reference " + scene.string() + " -o " + b.string() + " --texels-per-quad 3 --spp 16 -q", dir_)
          .status,
      0);

  // Atlases that differ are compared through the scene the reports name; with that file gone, refused.
  RunResult r = runCpgi("compare-light " + a.string() + " " + b.string(), dir_);
  EXPECT_EQ(r.status, 0) << r.err;
  const fs::path moved = dir_ / "moved.glb";
  fs::rename(scene, moved);
  r = runCpgi("compare-light " + a.string() + " " + b.string(), dir_);
  fs::rename(moved, scene);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--scene"), std::string::npos) << r.err;

  r = runCpgi("compare-light " + a.string() + " " + (dir_ / "missing").string(), dir_);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("lightmap.exr"), std::string::npos) << r.err;

  r = runCpgi("reference " + scene.string() + " -o " + (dir_ / "c").string() + " --spp 1", dir_);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--spp"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "c" / "lightmap.exr"));

  r = runCpgi("reference " + (dir_ / "nope.glb").string() + " -o " + (dir_ / "d").string(), dir_);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace cpgi
