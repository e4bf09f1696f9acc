#include "radiosity/lightmap/shooter_layout.h"

#include <gtest/gtest.h>

#include <chrono>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;

// A 2 m × 2 m floor (2 × 2 regions of 1 m) with a 0.4 m closed box standing on the centre of its first
// region: that region's eye must move out from under the box; the others stay at their centres.
TEST(ShooterLayout, EyesLeaveCoveredSpots) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addRect(s, glm::vec3(0.0f), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0), m);  // floor z = 0, normal +z
  addClosedBox(s, glm::vec3(0.3f, 0.3f, 0.0f), glm::vec3(0.7f, 0.7f, 0.4f), m);
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), AtlasParams{.texelsPerQuad = 16}, ctx, {0, 1});
  const std::vector<ShooterLayout> layouts = layoutShooters(s, atlas, LayoutParams{});
  ASSERT_EQ(layouts.size(), 1u);
  const ShooterLayout& l = layouts[0];
  ASSERT_EQ(l.regions, glm::ivec2(2, 2));
  ASSERT_EQ(l.rects.size(), 4u);
  EXPECT_EQ(l.rects[0], glm::ivec4(0, 0, 8, 8));
  EXPECT_EQ(l.rects[3], glm::ivec4(8, 8, 16, 16));
  ASSERT_EQ(l.eyes.size(), 4u);
  for (const glm::vec3& e : l.eyes) EXPECT_NEAR(e.z, 0.0f, 1e-5f);
  // Uncovered regions keep the texel next to their centre (texels are 0.125 m).
  int covered = 0;
  for (const glm::vec3& e : l.eyes) {
    const bool firstRegion = e.x < 1.0f && e.y < 1.0f;
    const bool underBox = e.x > 0.3f && e.x < 0.7f && e.y > 0.3f && e.y < 0.7f;
    EXPECT_FALSE(underBox) << e.x << " " << e.y;
    if (firstRegion)
      ++covered;
    else
      EXPECT_NEAR(glm::length(glm::vec2(e) - glm::round(glm::vec2(e) - 0.5f) - 0.5f), 0.0f, 0.125f)
          << e.x << " " << e.y;
  }
  EXPECT_EQ(covered, 1);
}

// Past its deadline the layout stops before its next batch of patches and says so by returning fewer
// layouts than patches: an engine's set-up then stops (radiosity/solve/shot_engine.h).
TEST(ShooterLayout, PastTheDeadlineItLaysOutNoMorePatches) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f, 2.0f, 2.0f), m);
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), AtlasParams{.texelsPerQuad = 8}, ctx);
  ASSERT_GT(atlas.patches.size(), 1u);
  EXPECT_EQ(layoutShooters(s, atlas, LayoutParams{}).size(), atlas.patches.size());
  EXPECT_TRUE(
      layoutShooters(s, atlas, LayoutParams{}, std::chrono::steady_clock::now() - std::chrono::seconds(1))
          .empty());
}

}  // namespace
}  // namespace cpgi
