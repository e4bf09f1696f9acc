#include "radiosity/metrics/cell_metrics.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace cpgi {
namespace {

TEST(CellMetrics, EachCellIsNormalisedByItsOwnReference) {
  // Cell 0 bright and right, cell 1 dim and 50 % too bright: the whole-atlas figure would hide cell 1.
  const std::vector<glm::vec3> reference = {
      {10, 10, 10}, {10, 10, 10}, {0.1f, 0.1f, 0.1f}, {0.2f, 0.2f, 0.2f}};
  const std::vector<glm::vec3> test = {{10, 10, 10}, {10, 10, 10}, {0.15f, 0.15f, 0.15f}, {0.3f, 0.3f, 0.3f}};
  const std::vector<float> weight = {1, 1, 1, 1}, cell = {0, 0, 1, 1};
  const std::vector<CellError> e = compareCells(test, reference, weight, {}, cell, {}, 4, {"lit", "dark"});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_NEAR(e[0].ratioOfMeans, 1.0, 1e-9);
  EXPECT_NEAR(e[0].relRmse, 0.0, 1e-9);
  EXPECT_NEAR(e[1].ratioOfMeans, 1.5, 1e-6);
  EXPECT_NEAR(e[1].relRmse, 0.5, 1e-6);
  EXPECT_EQ(e[1].texels, 2u);
  // How bright each room is in the reference, W/m²: the dark one at 1.5 % of the lit one.
  EXPECT_NEAR(e[0].referenceMean, 10.0, 1e-6);
  EXPECT_NEAR(e[1].referenceMean, 0.15, 1e-6);
  EXPECT_EQ(worstCell(e), std::optional<size_t>(1));
}

TEST(CellMetrics, WeightsNoiseAndSkippedTexels) {
  // Texel 2 has weight 0 (a lamp or an untraced texel, its reference NaN) and must not count.
  const float nan = std::nanf("");
  const std::vector<glm::vec3> reference = {{1, 1, 1}, {2, 2, 2}, {nan, nan, nan}};
  const std::vector<glm::vec3> test = {{2, 2, 2}, {2, 2, 2}, {5, 5, 5}};
  const std::vector<float> weight = {1, 3, 0}, sigma = {0.1f, 0.2f, 1.0f}, cell = {0, 0, 0};
  const std::vector<CellError> e = compareCells(test, reference, weight, sigma, cell, {}, 3, {"A"});
  // Σ w B = 3·2·1 + 3·2·3 = 24;  Σ w R = 3·1 + 3·2·3 = 21.
  EXPECT_NEAR(e[0].ratioOfMeans, 24.0 / 21.0, 1e-9);
  // The reference's mean weighs by w too and skips texel 2: (1 + 3·2) / 4.
  EXPECT_NEAR(e[0].referenceMean, 7.0 / 4.0, 1e-9);
  // Σ w|d|² = 3;  Σ w|R|² = 3 + 3·12 = 39.
  EXPECT_NEAR(e[0].relRmse, std::sqrt(3.0 / 39.0), 1e-9);
  // Σ w σ² = 0.01 + 3·0.04 = 0.13.
  EXPECT_NEAR(e[0].referenceNoise, std::sqrt(0.13 / 39.0), 1e-6);
  // The reference's noise taken out of the error: (3 − 0.13) / 39.
  EXPECT_NEAR(e[0].relRmseWithoutNoise, std::sqrt(2.87 / 39.0), 1e-6);
  // √3 |σ| per texel: Σ 3 (w σ)² = 3 (0.01 + 0.36) → ratio × sqrt(1.11) / 21.
  EXPECT_NEAR(e[0].ratioError, 24.0 / 21.0 * std::sqrt(1.11) / 21.0, 1e-6);
  EXPECT_EQ(e[0].texels, 2u);
}

TEST(CellMetrics, AnErrorWithinTheReferencesNoiseReadsZeroWithoutIt) {
  // The test equals the truth; the reference is off by its own noise (σ = 0.1 per texel).
  const std::vector<glm::vec3> reference = {{1.05f, 1.05f, 1.05f}, {0.95f, 0.95f, 0.95f}};
  const std::vector<glm::vec3> test = {{1, 1, 1}, {1, 1, 1}};
  const std::vector<float> weight = {1, 1}, sigma = {0.1f, 0.1f}, cell = {0, 0};
  const std::vector<CellError> e = compareCells(test, reference, weight, sigma, cell, {}, 2, {"A"});
  EXPECT_GT(e[0].relRmse, 0.04);
  EXPECT_EQ(e[0].relRmseWithoutNoise, 0.0);
}

TEST(CellMetrics, SparseSampleAddsSamplingErrorAndBlackCellIsWorst) {
  const std::vector<glm::vec3> reference = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  const std::vector<glm::vec3> test = {{1.2f, 1.2f, 1.2f}, {0.8f, 0.8f, 0.8f}, {0, 0, 0}};
  const std::vector<float> sample = {4, 4, 4}, cell = {0, 0, 1};  // each texel stands for 4
  const std::vector<CellError> e = compareCells(test, reference, sample, {}, cell, sample, 12, {"A", "B"});
  EXPECT_NEAR(e[0].ratioOfMeans, 1.0, 1e-6);
  // u = ±0.6, Σ (1 − 1/4) 16 · 0.36 = 8.64 over (Σ m a R = 24)².
  EXPECT_NEAR(e[0].ratioError, std::sqrt(8.64) / 24.0, 1e-6);
  EXPECT_EQ(e[1].ratioOfMeans, 0.0);
  EXPECT_EQ(worstCell(e), std::optional<size_t>(1));
}

TEST(CellMetrics, CellsWithoutTexelsAreNaNAndNeverWorst) {
  const std::vector<glm::vec3> r = {{1, 1, 1}}, b = {{1.1f, 1.1f, 1.1f}};
  const std::vector<float> w = {1}, cell = {-1};
  const std::vector<CellError> e = compareCells(b, r, w, {}, cell, {}, 1, {"A"});
  EXPECT_EQ(e[0].texels, 0u);
  EXPECT_TRUE(std::isnan(e[0].ratioOfMeans));
  EXPECT_TRUE(std::isnan(e[0].relRmseWithoutNoise));
  EXPECT_FALSE(worstCell(e).has_value());
  const std::vector<float> shortCell;
  EXPECT_THROW(compareCells(b, r, w, {}, shortCell, {}, 1, {"A"}), std::invalid_argument);
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

TEST(CellMetrics, ColourRatiosAgainstTheReference) {
  // Cell 0 as bright as the reference but bluer (its red lost), cell 1 the reference's colour twice over.
  const std::vector<glm::vec3> reference = {{0.6f, 0.3f, 0.1f}, {0.6f, 0.3f, 0.1f}, {1, 1, 1}};
  const std::vector<glm::vec3> test = {{0.3f, 0.3f, 0.4f}, {0.3f, 0.3f, 0.4f}, {2, 2, 2}};
  const std::vector<float> weight = {1, 1, 1}, cell = {0, 0, 1};
  const std::vector<CellError> e = compareCells(test, reference, weight, {}, cell, {}, 3, {"A", "B"});
  EXPECT_NEAR(e[0].ratioOfMeans, 1.0, 1e-6);
  EXPECT_NEAR(e[0].redGreenRatio, 1.0 / 2.0, 1e-6);
  EXPECT_NEAR(e[0].blueGreenRatio, (0.4 / 0.3) / (0.1 / 0.3), 1e-5);
  EXPECT_NEAR(e[1].redGreenRatio, 1.0, 1e-6);
  EXPECT_NEAR(e[1].blueGreenRatio, 1.0, 1e-6);
}

}  // namespace
}  // namespace cpgi
