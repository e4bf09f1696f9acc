#include "radiosity/lightmap/atlas_resample.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addTriangle;

// A 4 × 3 × 2.5 m room and a loose triangle (a chart with empty texels), at 20 and at 5 texels per metre.
struct TwoAtlases {
  Scene scene;
  LightmapAtlas fine, coarse;
  AtlasMapping mapping;
  TwoAtlases() {
    const uint32_t wall = addMaterial(scene, glm::vec3(0.7f));
    addClosedBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 2.5f), wall);
    addTriangle(scene, glm::vec3(2.0f, 0.5f, 0.3f), glm::vec3(2.0f, 0.9f, 0.3f), glm::vec3(2.0f, 0.5f, 1.1f),
                wall, 3);
    Context ctx;
    AtlasParams p;
    p.density = 20.0f;
    fine = buildAtlas(scene, findQuads(scene), p, ctx);
    p.density = 5.0f;
    coarse = buildAtlas(scene, findQuads(scene), p, ctx);
    mapping = mapAtlas(fine, coarse);
  }
};

TEST(AtlasResample, EveryFineTexelLandsOnTheCoarseTexelUnderIt) {
  const TwoAtlases a;
  for (size_t t = 0; t < a.fine.texelCount(); ++t) {
    if (a.fine.patch[t] < 0) {
      EXPECT_EQ(a.mapping.coarseTexel[t], -1);
      continue;
    }
    const int64_t c = a.mapping.coarseTexel[t];
    ASSERT_GE(c, 0) << "fine texel " << t;
    // Same surface, within a coarse texel's diagonal (0.2 m × √2) of the fine texel's centre.
    EXPECT_NEAR(glm::dot(a.fine.normal[t], a.coarse.normal[size_t(c)]), 1.0f, 1e-5f);
    EXPECT_LT(glm::distance(a.fine.position[t], a.coarse.position[size_t(c)]), 0.2f * 1.5f)
        << "fine texel " << t;
  }
}

TEST(AtlasResample, DownsampleKeepsThePowerAndUpsampleIsExactOnLinearLight) {
  const TwoAtlases a;
  // Light varying linearly over every surface: bilinear interpolation between coarse centres gives it
  // back exactly wherever four centres of the chart surround the point.
  auto light = [](glm::vec3 x) { return glm::vec3(1.0f + 0.5f * x.x + 0.25f * x.y + 0.1f * x.z); };
  std::vector<glm::vec3> fineValues(a.fine.texelCount(), glm::vec3(0.0f));
  double finePower = 0.0;
  for (size_t t = 0; t < a.fine.texelCount(); ++t)
    if (a.fine.patch[t] >= 0)
      fineValues[t] = light(a.fine.position[t]), finePower += fineValues[t].x * a.fine.area[t];
  const std::vector<glm::vec3> coarse = downsample(a.mapping, a.fine, a.coarse, fineValues);
  double coarsePower = 0.0;
  for (size_t c = 0; c < a.coarse.texelCount(); ++c) coarsePower += coarse[c].x * a.coarse.area[c];
  EXPECT_NEAR(coarsePower, finePower, 1e-6 * finePower);

  // Upsampled from the exact light at the coarse centres.
  std::vector<glm::vec3> atCentres(a.coarse.texelCount(), glm::vec3(0.0f));
  for (size_t c = 0; c < a.coarse.texelCount(); ++c)
    if (a.coarse.patch[c] >= 0) atCentres[c] = light(a.coarse.position[c]);
  const std::vector<glm::vec3> back = upsample(a.mapping, a.fine, a.coarse, atCentres);
  int interior = 0;
  for (size_t t = 0; t < a.fine.texelCount(); ++t) {
    if (a.fine.patch[t] < 0) continue;
    const Patch& c = a.coarse.patches[size_t(a.mapping.coarsePatch[t])];
    const glm::vec2 g = a.mapping.chartPoint[t];
    const bool inside =
        c.quads.size() > 0 && g.x >= 0.5f && g.y >= 0.5f && g.x <= c.w - 0.5f && g.y <= c.h - 0.5f;
    interior += inside;
    if (c.quads.size() > 0) {
      // Between the centres and in the half texel beyond the outer ones (extrapolated): exact.
      EXPECT_NEAR(back[t].x, light(a.fine.position[t]).x, 1e-4f) << "fine texel " << t;
    } else {
      // The loose triangle's empty corners: nearest valid centres, within the light's change over a
      // coarse texel.
      EXPECT_NEAR(back[t].x, light(a.fine.position[t]).x, 0.5f * 0.2f + 1e-4f) << "fine texel " << t;
    }
  }
  EXPECT_GT(interior, 1000);
}

// Light with a step at x = 2 (a shadow's edge) and linear elsewhere, given at the coarse texel
// centres: only fine texels interpolated across the step, or from a flagged coarse texel, are refined.
TEST(AtlasResample, RefinesOnlyWhereTheCoarseLightStepsOrIsFlagged) {
  const TwoAtlases a;
  auto light = [](glm::vec3 x) {
    return glm::vec3(x.x < 2.0f ? 1.0f : 0.2f) * (1.0f + 0.5f * x.y + 0.3f * x.z);
  };
  std::vector<glm::vec3> atCentres(a.coarse.texelCount(), glm::vec3(0.0f));
  for (size_t c = 0; c < a.coarse.texelCount(); ++c)
    if (a.coarse.patch[c] >= 0) atCentres[c] = light(a.coarse.position[c]);
  // One flagged coarse texel on the floor, far from the step.
  std::vector<uint8_t> flags(a.coarse.texelCount(), 0);
  size_t flagged = 0;
  for (size_t c = 0; c < a.coarse.texelCount(); ++c)
    if (a.coarse.patch[c] >= 0 && a.coarse.normal[c].z > 0.5f &&
        glm::distance(a.coarse.position[c], {0.7f, 1.3f, 0.0f}) < 0.1f)
      flagged = c, flags[c] = 1;
  ASSERT_NE(flags[flagged], 0);
  const std::vector<uint8_t> refine =
      texelsToRefine(a.mapping, a.fine, a.coarse, atCentres, flags, 0.01f, 0.0f);
  size_t refined = 0, valid = 0;
  for (size_t t = 0; t < a.fine.texelCount(); ++t) {
    if (a.fine.patch[t] < 0) {
      EXPECT_EQ(refine[t], 0);
      continue;
    }
    ++valid;
    refined += refine[t];
    const glm::vec3 x = a.fine.position[t];
    // The coarse texels either side of the step are bent; fine texels interpolated from them are up to a
    // coarse texel beyond their centres.
    const bool nearStep = std::abs(x.x - 2.0f) < 0.3f + 1e-3f;
    const bool nearFlag = glm::distance(x, a.coarse.position[flagged]) < 0.2f * 1.5f;
    if (!nearStep && !nearFlag) {
      EXPECT_EQ(refine[t], 0) << "smooth light at " << x.x << ", " << x.y << ", " << x.z;
    }
    // Across the step on walls, floor and ceiling (not the loose triangle at x = 2, which lies on it).
    if (std::abs(x.x - 2.0f) < 0.05f && std::abs(a.fine.normal[t].x) < 0.5f) {
      EXPECT_EQ(refine[t], 1);
    }
  }
  for (size_t t = 0; t < a.fine.texelCount(); ++t) {
    if (a.mapping.coarseTexel[t] == int64_t(flagged)) {
      EXPECT_EQ(refine[t], 1);
    }
  }
  EXPECT_LT(refined * 5, valid);
}

}  // namespace
}  // namespace cpgi
