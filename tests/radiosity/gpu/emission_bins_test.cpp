// Binned directional emission (radiosity/gpu/emission_bins.h): equal-area bins make ∫ f cos θ dω = π for
// any weights; a square above a point gives, by rays, its closed-form irradiance, all of it in the bins its
// directions fall in.
#include "radiosity/gpu/emission_bins.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {
using namespace testing;

constexpr double kPi = std::numbers::pi;

// (1/π) ∫ f cos θ dω by cosine-weighted sampling: 1 for a normalised emission.
double meanFactor(const ArrivalBins& bins, const glm::vec3& n, int samples) {
  const BinFrame frame = binFrame(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  double sum = 0.0;
  for (int k = 0; k < samples; ++k) {
    const float r = std::sqrt(U(rng)), phi = float(2.0 * kPi) * U(rng);
    const glm::vec3 w = r * std::cos(phi) * frame.t1 + r * std::sin(phi) * frame.t2 +
                        std::sqrt(std::max(0.0f, 1.0f - r * r)) * frame.n;
    sum += binnedEmissionFactor(bins, frame, glm::normalize(w));
  }
  return sum / samples;
}

TEST(EmissionBins, AnyWeightsKeepTheExitance) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  for (const glm::vec3 n :
       {glm::vec3(0, 0, 1), glm::vec3(-1, 0, 0), glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f))}) {
    ArrivalBins bins{};
    for (float& b : bins) b = U(rng) < 0.3f ? 10.0f * U(rng) : 0.0f;  // spiky, with empty bins
    EXPECT_NEAR(meanFactor(bins, n, 400000), 1.0, 0.01);
    EXPECT_NEAR(meanFactor(ArrivalBins{}, n, 1000), 1.0, 1e-9);    // no weights: a Lambertian
    EXPECT_EQ(binnedEmissionFactor(bins, binFrame(n), -n), 0.0f);  // nothing behind the surface
  }
}

TEST(EmissionBins, BinsHaveEqualProjectedSolidAngle) {
  // Cosine-weighted directions fall evenly into the bins.
  const BinFrame frame = binFrame(glm::vec3(0, 1, 0));
  std::vector<int> count(kArrivalBins, 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const int samples = 256000;
  for (int k = 0; k < samples; ++k) {
    const float r = std::sqrt(U(rng)), phi = float(2.0 * kPi) * U(rng);
    const glm::vec3 w = r * std::cos(phi) * frame.t1 + r * std::sin(phi) * frame.t2 +
                        std::sqrt(std::max(0.0f, 1.0f - r * r)) * frame.n;
    ++count[size_t(arrivalBin(frame, glm::normalize(w)))];
  }
  for (int b = 0; b < kArrivalBins; ++b)
    EXPECT_NEAR(count[size_t(b)], samples / kArrivalBins, 150) << "bin " << b;
}

TEST(EmissionBins, RaysGiveASquaresIrradianceInItsDirections) {
  // A 1 m square 1 m above a small patch at the origin, sending 1 W/m² everywhere: the point-to-square
  // form factor (2/π)(2 · 0.5/√1.25 · atan(0.5/√1.25)) = 0.2394; every direction from it lies within
  // sin θ ≤ 1/√3, the first three rings of r² = sin²θ in eighths.
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.5f));
  addRect(scene, {-0.5f, -0.5f, 1.0f}, {0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, m);  // faces −z
  Context ctx;
  AtlasParams params;
  params.density = 8.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), params, ctx);
  const RayScene rays(scene);
  const float side = 0.01f;
  const ArrivalBins bins = traceArrivalBins(rays, atlas, {-0.5f * side, -0.5f * side, 0.0f},
                                            {side, 0.0f, 0.0f}, {0.0f, side, 0.0f}, {0.0f, 0.0f, 1.0f},
                                            160000, 5, [](size_t, const glm::vec3&) { return 1.0f; });
  double total = 0.0, outer = 0.0;
  for (int b = 0; b < kArrivalBins; ++b) {
    total += bins[size_t(b)];
    if (b / kBinSectors >= 3) outer += bins[size_t(b)];
  }
  const double expected = 2.0 / kPi * (2.0 * 0.5 / std::sqrt(1.25) * std::atan(0.5 / std::sqrt(1.25)));
  EXPECT_NEAR(total, expected, 0.015 * expected);  // 3σ of 160k rays
  EXPECT_EQ(outer, 0.0);
  // The same light seen as one emitter of the far side: its f is 0 outside those rings, and it still
  // keeps the exitance.
  const BinFrame far = binFrame({0.0f, 0.0f, -1.0f});
  EXPECT_EQ(binnedEmissionFactor(bins, far, glm::normalize(glm::vec3(1.0f, 0.0f, -0.2f))), 0.0f);
  EXPECT_GT(binnedEmissionFactor(bins, far, glm::vec3(0.0f, 0.0f, -1.0f)), 1.5f);
  EXPECT_NEAR(meanFactor(bins, far.n, 400000), 1.0, 0.01);
}

}  // namespace
}  // namespace cpgi
