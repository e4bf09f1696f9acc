#include "radiosity/metrics/portal_seams.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace cpgi {
namespace {

constexpr float kTexel = 0.1f;  // metres

// A 4 × 2 m floor at y = 0 of 0.1 m texels under a door at x = 2 (z in [0.5, 1.5], 2.1 m high), lit with a
// smooth fall-off along x and z, ±`noise` of texel noise (a fixed hash, so the test is the same every run)
// and `step` more light past x = 2; plus a wall's texels beside the door, which face sideways and must not
// count.
struct Floor {
  std::vector<glm::vec3> position, normal, value;
  std::vector<float> area;

  Floor(double step, double noise) {
    uint32_t hash = 12345u;
    for (int i = 0; i < 40; ++i)
      for (int k = 0; k < 20; ++k) {
        const glm::vec3 p((i + 0.5f) * kTexel, 0.0f, (k + 0.5f) * kTexel);
        hash = hash * 1664525u + 1013904223u;
        const double jitter = (double(hash >> 8) / double(1u << 24) * 2.0 - 1.0) * std::sqrt(3.0) * noise;
        const double light = (10.0 - p.x - 0.5 * p.z) * (1.0 + jitter) * (p.x > 2.0f ? 1.0 + step : 1.0);
        add(p, {0, 1, 0}, float(light));
      }
    for (int k = 0; k < 20; ++k) add({2.05f, 1.0f, (k + 0.5f) * kTexel}, {1, 0, 0}, 100.0f);
  }
  void add(glm::vec3 p, glm::vec3 n, float v) {
    position.push_back(p);
    normal.push_back(n);
    value.push_back(glm::vec3(v));
    area.push_back(kTexel * kTexel);
  }
  SeamTexels texels() const { return {position, normal, value, area}; }
};

// Corners in the order whose normal, (c1 − c0) × (c3 − c0), points +x: side B is past x = 2.
SeamPortal door() {
  return {"portal:A:B", {{{2, 0, 0.5f}, {2, 2.1f, 0.5f}, {2, 2.1f, 1.5f}, {2, 0, 1.5f}}}};
}

TEST(PortalSeams, ASmoothFloorHasNoStepBeyondItsNoise) {
  const Floor f(0.0, 0.02);
  const std::vector<PortalSeam> s = measurePortalSeams(f.texels(), {door()});
  ASSERT_EQ(s.size(), 1u);
  ASSERT_TRUE(s[0].measured);
  EXPECT_EQ(s[0].texelsA, 10u);  // one texel row each side, the door's 1 m at 0.1 m texels
  EXPECT_EQ(s[0].texelsB, 10u);
  EXPECT_NEAR(s[0].noise, 0.02, 0.012);  // the noise put in, from ten texels a side
  // The fall-off alone moves the light by 1.2 % over the texel between the two rows' centres.
  EXPECT_LT(std::abs(s[0].step), s[0].noise);
}

TEST(PortalSeams, AStepPaintedOnOneSideIsMeasuredWithItsSign) {
  const Floor f(0.2, 0.02);
  const PortalSeam s = measurePortalSeams(f.texels(), {door()})[0];
  ASSERT_TRUE(s.measured);
  EXPECT_NEAR(s.step, 0.2 - 0.012, 0.03);  // B, past the plane, is 20 % brighter, less the fall-off
  EXPECT_GT(std::abs(s.step), 3.0 * s.noise);
  // The same portal the other way round sees the step from the other side.
  SeamPortal reversed = door();
  std::swap(reversed.corners[1], reversed.corners[3]);
  EXPECT_NEAR(measurePortalSeams(f.texels(), {reversed})[0].step, -s.step, 0.03);
}

TEST(PortalSeams, WithoutNoiseTheNoiseIsTheSmoothChangeAlongTheBandOnly) {
  const PortalSeam s = measurePortalSeams(Floor(0.0, 0.0).texels(), {door()})[0];
  ASSERT_TRUE(s.measured);
  // Neighbours along z differ by 0.05 W/m² of about 8: σ² = d²/2, relative 0.0044.
  EXPECT_NEAR(s.noise, 0.05 / std::sqrt(2.0) / 8.0, 0.001);
}

// A 0.1 m wall's threshold, cut at the mid-plane, keeps two texels 2.5 cm deep across each half: the band
// is the row against the plane alone (its light 10 and 12 here, the rows behind 5).
TEST(PortalSeams, AThinThresholdGivesItsRowAgainstThePlaneAlone) {
  Floor f(0.0, 0.0);
  f.position.clear(), f.normal.clear(), f.value.clear(), f.area.clear();
  for (int k = 0; k < 10; ++k)
    for (int row = 0; row < 2; ++row) {
      const float z = 0.5f + (k + 0.5f) * kTexel, d = (row + 0.5f) * 0.025f;
      f.add({2.0f - d, 0.0f, z}, {0, 1, 0}, row == 0 ? 10.0f : 5.0f);
      f.add({2.0f + d, 0.0f, z}, {0, 1, 0}, row == 0 ? 12.0f : 5.0f);
    }
  for (float& a : f.area) a = 0.025f * kTexel;
  const PortalSeam s = measurePortalSeams(f.texels(), {door()})[0];
  ASSERT_TRUE(s.measured);
  EXPECT_EQ(s.texelsA, 10u);
  EXPECT_EQ(s.texelsB, 10u);
  EXPECT_NEAR(s.meanA, 10.0, 1e-5);
  EXPECT_NEAR(s.meanB, 12.0, 1e-5);
  EXPECT_NEAR(s.step, 2.0 / 11.0, 1e-6);
  EXPECT_NEAR(s.noise, 0.0, 1e-9);
}

TEST(PortalSeams, PortalsWithNoFloorAcrossThemAreNotMeasured) {
  const Floor f(0.2, 0.0);
  const SeamPortal window{"portal:A:B.window", {{{2, 1, 0.5f}, {2, 1, 1.5f}, {2, 2, 1.5f}, {2, 2, 0.5f}}}};
  const SeamPortal hatch{"portal:A:C", {{{0, 2.6f, 0}, {1, 2.6f, 0}, {1, 2.6f, 1}, {0, 2.6f, 1}}}};
  const SeamPortal beyond{"portal:A:D", {{{2, 0, 3}, {2, 0, 4}, {2, 2, 4}, {2, 2, 3}}}};  // past the floor
  for (const PortalSeam& s : measurePortalSeams(f.texels(), {window, hatch, beyond})) {
    EXPECT_FALSE(s.measured) << s.name;
    EXPECT_TRUE(std::isnan(s.step)) << s.name;
  }
}

TEST(PortalSeams, TexelsThatDoNotCountAreLeftOut) {
  Floor f(0.0, 0.0);
  for (size_t i = 0; i < f.area.size(); ++i)
    if (f.position[i].x > 2.0f) f.area[i] = 0.0f;  // the far side untraced
  const PortalSeam s = measurePortalSeams(f.texels(), {door()})[0];
  EXPECT_EQ(s.texelsB, 0u);
  EXPECT_FALSE(s.measured);
  std::vector<float> shorter(f.area.begin(), f.area.end() - 1);
  EXPECT_THROW(measurePortalSeams({f.position, f.normal, f.value, shorter}, {door()}), std::invalid_argument);
}

}  // namespace
}  // namespace cpgi
