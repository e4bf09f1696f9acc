// requireFiniteResult: a non-finite texel or energy total stops the command with one line.
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "radiosity/lightmap/finite_result.h"

namespace cpgi {
namespace {

LightmapAtlas threeTexels() {
  LightmapAtlas atlas;
  atlas.width = 3, atlas.height = 1;
  atlas.patch = {0, 0, -1};  // the last is padding
  atlas.area = {0.5f, 0.5f, 0.0f};
  atlas.albedo.assign(3, glm::vec3(0.5f));
  return atlas;
}

std::string problemOf(const LightmapAtlas& atlas, const std::vector<glm::vec3>& radiosity,
                      const std::vector<std::pair<const char*, double>>& totals = {}) {
  try {
    requireFiniteResult("scene.glb", atlas, radiosity, totals);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "scene.glb");
    return e.problem();
  }
  return "";
}

TEST(FiniteResult, FiniteResultPasses) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Padding may hold anything: it is filled from its neighbours before writing.
  EXPECT_EQ(problemOf(threeTexels(), {glm::vec3(1.0f), glm::vec3(2.0f), glm::vec3(nan)}, {{"emitted", 10.0}}),
            "");
}

TEST(FiniteResult, NonFiniteTexelOrEnergyIsNamed) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(problemOf(threeTexels(), {glm::vec3(1.0f), glm::vec3(0.0f, inf, 0.0f), glm::vec3(0.0f)}),
            "the solve went non-finite (1 texel not finite (the first at 1,0)): the scene's numbers overflow "
            "float arithmetic; nothing was written");
  const std::string both = problemOf(threeTexels(), {glm::vec3(nan), glm::vec3(nan), glm::vec3(0.0f)},
                                     {{"emitted", HUGE_VAL}, {"shot", 1.0}});
  EXPECT_NE(both.find("emitted energy inf W, 2 texels not finite (the first at 0,0)"), std::string::npos)
      << both;
  EXPECT_EQ(both.find("shot"), std::string::npos) << both;
}

}  // namespace
}  // namespace cpgi
