// End to end: `cpgi reference --texels N` traces a stratified sample of texels, and `cpgi compare-light`
// against it estimates the metric of the full comparison, on seed1 at 8² texels per quad.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/suite_setup.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;
using test::cpgi;

constexpr int kSampled = 600;

/// One generated scene, its full and sampled references (same seed and spp) and a global bake, shared by
/// the tests: the traces are the slow part.
class SparseReference : public ::testing::Test {
 protected:
  void SetUp() override { setup_.require(); }
  static inline test::SuiteSetup setup_;
  static void SetUpTestSuite() {
    setup_.run([] {
      dir_ = std::make_unique<test::TempDir>();
      auto run = [](const std::string& args) { test::cpgiOrThrow(*dir_, args); };
      const std::string scene = test::quote(*dir_ / "seed1.glb");
      const std::string atlas = " --texels-per-quad 8 ";
      // --cell-noise 0: the same paths on every texel of both (a noisy cell's extra paths would differ
      // between a full and a sampled reference, whose cells' noise differs).
      const std::string paths = "--spp 16 --cell-noise 0 -q";
      run("generate seed1 -o " + scene);
      run("reference " + scene + " -o " + test::quote(*dir_ / "full") + atlas + paths);
      run("reference " + scene + " -o " + test::quote(*dir_ / "sparse") + atlas + paths + " --texels " +
          std::to_string(kSampled));
      run("bake " + scene + " -o " + test::quote(*dir_ / "bake") + atlas + "--method global -q");
    });
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::string at(const std::string& name) { return *dir_ / name; }
  static nlohmann::json compare(const std::string& a, const std::string& b) {
    const test::CommandRun r =
        cpgi(*dir_, "compare-light " + test::quote(at(a)) + " " + test::quote(at(b)) + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }

  static std::unique_ptr<test::TempDir> dir_;
};
std::unique_ptr<test::TempDir> SparseReference::dir_;

const std::vector<float>& channel(const std::vector<ExrChannel>& extra, const std::string& name) {
  for (const ExrChannel& c : extra)
    if (c.name == name) return c.values;
  throw std::runtime_error("no channel " + name);
}

TEST_F(SparseReference, TracedTexelsHoldTheFullReferencesValuesAndTheOthersAreMarked) {
  std::vector<ExrChannel> fullExtra, sparseExtra;
  const ImageRGB full = readExr(at("full") + "/lightmap.exr", &fullExtra);
  const ImageRGB sparse = readExr(at("sparse") + "/lightmap.exr", &sparseExtra);
  const std::vector<float>& area = channel(sparseExtra, "area");
  const std::vector<float>& weight = channel(sparseExtra, "sample_weight");
  const std::vector<float>& sigma = channel(sparseExtra, "stderr");
  EXPECT_EQ(area, channel(fullExtra, "area"));
  EXPECT_THROW(channel(fullExtra, "sample_weight"), std::runtime_error);  // a full reference has none

  size_t valid = 0, traced = 0;
  double weights = 0.0;
  for (size_t i = 0; i < area.size(); ++i) {
    if (!(area[i] > 0.0f)) {
      EXPECT_EQ(weight[i], 0.0f);
      continue;
    }
    ++valid;
    if (weight[i] > 0.0f) {
      ++traced;
      weights += weight[i];
      // Same seed, same stream per texel: the very same value, not merely within noise.
      EXPECT_EQ(sparse.pixels[i], full.pixels[i]) << "texel " << i;
      EXPECT_EQ(sigma[i], channel(fullExtra, "stderr")[i]) << "texel " << i;
    } else {
      EXPECT_TRUE(std::isnan(sparse.pixels[i].x) && std::isnan(sparse.pixels[i].y) &&
                  std::isnan(sparse.pixels[i].z))
          << "untraced texel " << i << " must not read as light";
    }
  }
  EXPECT_EQ(traced, size_t(kSampled));
  EXPECT_EQ(weights, double(valid));  // every valid texel stood for once
  EXPECT_GT(valid, 4u * size_t(kSampled));

  const nlohmann::json report = nlohmann::json::parse(test::slurp(at("sparse") + "/report.json"));
  EXPECT_EQ(report["texels"], valid);
  EXPECT_EQ(report["texels_traced"], kSampled);
  EXPECT_EQ(report["views"], nlohmann::json::array());
  const nlohmann::json fullReport = nlohmann::json::parse(test::slurp(at("full") + "/report.json"));
  EXPECT_EQ(fullReport["texels_traced"], valid);
  // Pictures of a lightmap that is mostly holes would pass for a broken bake: none are written.
  EXPECT_FALSE(fs::exists(at("sparse") + "/baked.glb"));
  for (const auto& entry : fs::directory_iterator(at("sparse")))
    EXPECT_EQ(entry.path().filename().string().rfind("view-", 0), std::string::npos) << entry.path();
  EXPECT_TRUE(fs::exists(at("full") + "/baked.glb"));
}

TEST_F(SparseReference, CompareLightEstimatesTheFullComparison) {
  const nlohmann::json full = compare("bake", "full");
  const nlohmann::json sparse = compare("bake", "sparse");
  EXPECT_EQ(full["sparse_reference"], false);
  EXPECT_EQ(sparse["sparse_reference"], true);
  EXPECT_EQ(sparse["texels"], kSampled);
  EXPECT_EQ(sparse["texels_valid"], full["texels"]);
  EXPECT_EQ(full["rel_rmse_sampling_error"], 0.0);

  // The sample's RMSE differs from the full one only by which texels were drawn (their values are the
  // same): within 4 of the standard errors the sample size implies (texel_sample.h), which must itself be
  // small enough for the check to mean something.
  for (const char* key : {"rel_rmse", "rel_rmse_nonemissive"}) {
    const std::string error =
        std::string(key) == "rel_rmse" ? "rel_rmse_sampling_error" : "rel_rmse_nonemissive_sampling_error";
    const double exact = full[key].get<double>(), estimate = sparse[key].get<double>();
    const double sigma = sparse[error].get<double>();
    EXPECT_GT(exact, 0.0) << key;
    EXPECT_GT(sigma, 0.0) << key;
    EXPECT_LT(sigma, 0.2 * exact) << key;
    EXPECT_NEAR(estimate, exact, 4.0 * sigma) << key;
  }
  // The reference's noise is taken over the same texels with the same weights: the sparse reference's
  // own report says the same, and it estimates the full reference's noise.
  const nlohmann::json report = nlohmann::json::parse(test::slurp(at("sparse") + "/report.json"));
  EXPECT_NEAR(sparse["reference_noise"].get<double>(), report["noise"].get<double>(),
              1e-5 * report["noise"].get<double>());
  EXPECT_NEAR(sparse["reference_noise_nonemissive"].get<double>(), report["noise_nonemissive"].get<double>(),
              1e-5 * report["noise_nonemissive"].get<double>());
  EXPECT_NEAR(sparse["reference_noise"].get<double>(), full["reference_noise"].get<double>(),
              0.25 * full["reference_noise"].get<double>());
}

TEST_F(SparseReference, ASampleAsLargeAsTheAtlasIsTheFullReference) {
  const nlohmann::json fullReport = nlohmann::json::parse(test::slurp(at("full") + "/report.json"));
  const std::string out = at("all");
  const test::CommandRun r =
      cpgi(*dir_, "reference " + test::quote(at("seed1.glb")) + " -o " + test::quote(out) +
                      " --texels-per-quad 8 --spp 16 --cell-noise 0 --texels " +
                      std::to_string(fullReport["texels"].get<size_t>() + 1));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("all are traced"), std::string::npos) << r.err;
  EXPECT_EQ(test::slurp(out + "/lightmap.exr"), test::slurp(at("full") + "/lightmap.exr"));
  EXPECT_TRUE(fs::exists(out + "/baked.glb"));
}

TEST_F(SparseReference, BadTexelCountsAndASparseLightmapUnderTestFailWithOneLine) {
  const std::string scene = test::quote(at("seed1.glb"));
  for (const std::string texels : {"0", "-5", "=-5", "lots"}) {
    const std::string out = at("bad");
    const std::string option = texels[0] == '=' ? "--texels" + texels : "--texels " + texels;
    const test::CommandRun r =
        cpgi(*dir_, "reference " + scene + " -o " + test::quote(out) + " --texels-per-quad 2 " + option);
    EXPECT_EQ(r.status, 1) << option;
    EXPECT_EQ(r.errLines().size(), 1u) << option << ": " << r.err;
    EXPECT_NE(r.err.find("--texels"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out + "/lightmap.exr"));
  }
  const test::CommandRun r =
      cpgi(*dir_, "compare-light " + test::quote(at("sparse")) + " " + test::quote(at("full")));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find("sparse reference"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cpgi
