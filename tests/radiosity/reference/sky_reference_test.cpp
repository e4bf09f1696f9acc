// The reference's sky (core/sky.h), picked up where a path leaves the scene: in a black box whose ceiling
// has a hole, the grey floor's B is ρ π Lz F(point → hole) under a uniform sky; a closed box under any
// sky stays black.
#include <numbers>

#include <gtest/gtest.h>

#include "radiosity/metrics/form_factors.h"
#include "radiosity/reference/reference_tracer.h"
#include "tests/radiosity/reference/path_test_scenes.h"
#include "tests/radiosity/test_sky_scenes.h"

namespace cpgi {
namespace {

TEST(SkyReference, FloorUnderAHoleInTheCeilingMatchesTheFormFactor) {
  Scene s = testing::boxOpenToTheSky(0.5f);
  s.sky.kind = Sky::Kind::Uniform;
  s.sky.zenithRadiance = 3.0f;
  s.sky.groundRadiance = 7.0f;  // the hole shows only sky
  const std::vector<SamplePoint> points = pathtest::floorPoints({0.25f, 1.0f, 1.6f}, {0.3f, 1.0f, 1.8f});
  Context ctx;
  ReferenceParams params;
  params.spp = 1024;
  const ReferenceResult r = traceReference(s, points, params, ctx);
  const auto hole = testing::skyHole();
  for (size_t i = 0; i < points.size(); ++i) {
    const double f = pointToPolygonFormFactor(glm::dvec3(points[i].position), {0, 1, 0}, hole);
    const double want = 0.5 * std::numbers::pi * 3.0 * f;
    EXPECT_NEAR(r.radiosity[i].g, want, 4.0 * r.standardError[i].g + 0.01 * want) << "point " << i;
  }

  Scene closed;
  testing::addClosedBox(closed, glm::vec3(0.0f), glm::vec3(2.0f),
                        testing::addMaterial(closed, glm::vec3(0.5f)));
  closed.sky = s.sky;
  const ReferenceResult dark = traceReference(closed, std::span(points).first(3), params, ctx);
  for (const glm::vec3& b : dark.radiosity) EXPECT_EQ(b, glm::vec3(0.0f));
}

}  // namespace
}  // namespace cpgi
