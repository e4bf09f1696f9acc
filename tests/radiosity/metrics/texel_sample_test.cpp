#include "radiosity/metrics/texel_sample.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "radiosity/metrics/metrics.h"

namespace cpgi {
namespace {

TEST(TexelSample, OneTexelPerEqualStratumWeightedByItsSize) {
  const size_t valid = 1003, count = 100;  // strata of 10 and 11 texels
  const TexelSample s = sampleTexels(valid, count, 42);
  ASSERT_EQ(s.ranks.size(), count);
  ASSERT_EQ(s.weights.size(), count);
  double total = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const size_t begin = valid * k / count, end = valid * (k + 1) / count;
    EXPECT_GE(s.ranks[k], begin) << k;
    EXPECT_LT(s.ranks[k], end) << k;
    EXPECT_EQ(s.weights[k], float(end - begin)) << k;
    total += s.weights[k];
  }
  EXPECT_EQ(total, double(valid));  // the weights stand for every texel once

  EXPECT_EQ(sampleTexels(valid, count, 42).ranks, s.ranks);  // deterministic
  EXPECT_NE(sampleTexels(valid, count, 43).ranks, s.ranks);
  EXPECT_THROW(sampleTexels(valid, 0, 42), std::invalid_argument);
}

TEST(TexelSample, AsManyAsTheTexelsTakesThemAll) {
  for (size_t count : {size_t(7), size_t(50)}) {
    const TexelSample s = sampleTexels(7, count, 1);
    ASSERT_EQ(s.ranks.size(), 7u);
    for (size_t k = 0; k < 7; ++k) {
      EXPECT_EQ(s.ranks[k], k);
      EXPECT_EQ(s.weights[k], 1.0f);
    }
  }
}

/// A population that varies along the atlas order and has spikes, as lightmaps do (lamps).
double population(size_t i) {
  return 1.0 + std::sin(0.01 * double(i)) * std::sin(0.01 * double(i)) + (i % 37 == 0 ? 20.0 : 0.0);
}

TEST(TexelSample, WeightedSumIsUnbiasedAndEveryTexelEquallyLikelyInItsStratum) {
  const size_t valid = 1003, count = 100;
  const int seeds = 4000;
  double exact = 0.0;
  for (size_t i = 0; i < valid; ++i) exact += population(i);
  std::vector<int> chosen(valid, 0);
  double sum = 0.0, sumSquares = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    const TexelSample s = sampleTexels(valid, count, uint64_t(seed));
    double estimate = 0.0;
    for (size_t k = 0; k < s.ranks.size(); ++k) {
      estimate += s.weights[k] * population(s.ranks[k]);
      ++chosen[s.ranks[k]];
    }
    sum += estimate;
    sumSquares += estimate * estimate;
  }
  const double mean = sum / seeds;
  const double spread = std::sqrt(std::max(0.0, sumSquares / seeds - mean * mean));
  EXPECT_GT(spread, 0.0);
  EXPECT_NEAR(mean, exact, 4.0 * spread / std::sqrt(double(seeds))) << "spread " << spread;
  // Each texel of an m-texel stratum is chosen with probability 1/m: binomial counts within 5σ.
  for (size_t k = 0; k < count; ++k) {
    const size_t begin = valid * k / count, end = valid * (k + 1) / count;
    const double p = 1.0 / double(end - begin);
    for (size_t i = begin; i < end; ++i)
      EXPECT_NEAR(chosen[i], seeds * p, 5.0 * std::sqrt(seeds * p * (1.0 - p))) << "texel " << i;
  }
}

/// Pseudo-random per-texel values, uncorrelated with the atlas order, where stratification gains nothing
/// and the spread of the sampled RMSE should be what sampledRelRmseError predicts.
float hashed(size_t i, uint64_t salt) {
  uint64_t x = i * 0x9E3779B97F4A7C15ull + salt;
  x = (x ^ (x >> 31)) * 0xBF58476D1CE4E5B9ull;
  x ^= x >> 29;
  return float(x >> 40) * 0x1p-24f;
}

TEST(TexelSample, SampledRelRmseErrorPredictsTheSpreadOverSeeds) {
  const size_t valid = 20000, count = 500;
  std::vector<glm::vec3> test(valid), reference(valid);
  std::vector<float> area(valid);
  for (size_t i = 0; i < valid; ++i) {
    reference[i] = glm::vec3(1.0f + 4.0f * hashed(i, 1));
    // Errors of 0–20 % with a heavy tail on a few texels.
    const float relative = 0.2f * hashed(i, 2) * (hashed(i, 3) < 0.02f ? 5.0f : 1.0f);
    test[i] = reference[i] * (1.0f + relative);
    area[i] = 0.5f + hashed(i, 4);
  }
  const double full = compareLightmaps(test, reference, area).relRmse;

  const int seeds = 400;
  double sum = 0.0, sumSquares = 0.0, predicted = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    const TexelSample s = sampleTexels(valid, count, uint64_t(seed));
    std::vector<float> weight(valid, 0.0f), weightedArea(valid, 0.0f);
    for (size_t k = 0; k < s.ranks.size(); ++k) weight[s.ranks[k]] = s.weights[k];
    for (size_t i = 0; i < valid; ++i) weightedArea[i] = area[i] * weight[i];
    const double estimate = compareLightmaps(test, reference, weightedArea).relRmse;
    sum += estimate;
    sumSquares += estimate * estimate;
    predicted += sampledRelRmseError(test, reference, area, weight, valid);
  }
  const double mean = sum / seeds, spread = std::sqrt(sumSquares / seeds - mean * mean);
  predicted /= seeds;
  EXPECT_GT(predicted, 0.0);
  EXPECT_NEAR(spread, predicted, 0.2 * predicted) << "full " << full << ", mean " << mean;
  // The ratio estimator's bias is O(1/n), far below its spread.
  EXPECT_NEAR(mean, full, 4.0 * spread / std::sqrt(double(seeds)) + 0.1 * spread);

  // The whole atlas has no sampling error.
  EXPECT_EQ(sampledRelRmseError(test, reference, area, std::vector<float>(valid, 1.0f), valid), 0.0);
}

}  // namespace
}  // namespace cpgi
