#include "radiosity/metrics/metrics.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace cpgi {
namespace {

TEST(Metrics, HandComputedValues) {
  const std::vector<glm::vec3> reference = {{1, 0, 0}, {0, 2, 0}, {3, 4, 0}, {100, 100, 100}};
  const std::vector<glm::vec3> test = {{2, 0, 0}, {0, 2, 1}, {3, 4, 0}, {0, 0, 0}};
  const std::vector<float> area = {1.0f, 0.5f, 2.0f, 0.0f};  // the last texel is padding
  const LightmapError e = compareLightmaps(test, reference, area);
  // Σ a|d|² = 1·1 + 0.5·1 + 0 = 1.5;  Σ a|R|² = 1·1 + 0.5·4 + 2·25 = 53
  EXPECT_NEAR(e.relRmse, std::sqrt(1.5 / 53.0), 1e-12);
  // Σ a(d·1) = 1 + 0.5 = 1.5;  Σ a(R·1) = 1 + 1 + 14 = 16
  EXPECT_NEAR(e.relMeanError, 1.5 / 16.0, 1e-12);
  EXPECT_NEAR(e.maxAbs, 1.0, 1e-12);
  EXPECT_EQ(e.texels, 3u);
}

TEST(Metrics, SignedMeanErrorAndRgbNorm) {
  const std::vector<glm::vec3> reference = {{2, 2, 2}, {1, 1, 1}};
  const std::vector<glm::vec3> test = {{1, 1, 1}, {1, 1, 1}};
  const std::vector<float> area = {1.0f, 3.0f};
  const LightmapError e = compareLightmaps(test, reference, area);
  EXPECT_NEAR(e.relMeanError, -3.0 / (6.0 + 9.0), 1e-12);
  EXPECT_NEAR(e.maxAbs, std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(e.relRmse, std::sqrt(3.0 / (12.0 + 9.0)), 1e-12);
}

TEST(Metrics, IdenticalLightmapsHaveNoError) {
  const std::vector<glm::vec3> b = {{0.3f, 0.2f, 0.1f}, {5, 6, 7}};
  const std::vector<float> area = {0.01f, 0.02f};
  const LightmapError e = compareLightmaps(b, b, area);
  EXPECT_EQ(e.relRmse, 0.0);
  EXPECT_EQ(e.relMeanError, 0.0);
  EXPECT_EQ(e.maxAbs, 0.0);
}

TEST(Metrics, UniformScaleGivesThatRelativeError) {
  std::vector<glm::vec3> reference, test;
  std::vector<float> area;
  for (int i = 0; i < 50; ++i) {
    reference.emplace_back(float(i), float(2 * i), 1.0f);
    test.push_back(reference.back() * 1.1f);
    area.push_back(0.5f + 0.01f * i);
  }
  const LightmapError e = compareLightmaps(test, reference, area);
  EXPECT_NEAR(e.relRmse, 0.1, 1e-6);
  EXPECT_NEAR(e.relMeanError, 0.1, 1e-6);
}

TEST(Metrics, DarkReference) {
  const std::vector<glm::vec3> zero = {{0, 0, 0}};
  const std::vector<glm::vec3> lit = {{1, 0, 0}};
  const std::vector<float> area = {1.0f};
  EXPECT_EQ(compareLightmaps(zero, zero, area).relRmse, 0.0);
  EXPECT_EQ(compareLightmaps(lit, zero, area).relRmse, std::numeric_limits<double>::infinity());
}

TEST(Metrics, SizeMismatchThrows) {
  const std::vector<glm::vec3> a = {{0, 0, 0}}, b = {{0, 0, 0}, {1, 1, 1}};
  const std::vector<float> area = {1.0f};
  EXPECT_THROW(compareLightmaps(a, b, area), std::invalid_argument);
}

}  // namespace
}  // namespace cpgi
