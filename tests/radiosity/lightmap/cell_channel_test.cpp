#include "radiosity/lightmap/cell_channel.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

TEST(CellChannel, MergedChartTexelsTakeTheirOwnQuadsCell) {
  // Two equal coplanar 1 m floor quads side by side, one per cell: the atlas merges them into one chart,
  // and each texel must still report the cell of the quad it lies on.
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addRect(s, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, m);
  addRect(s, {1, 0, 0}, {0, 0, 1}, {1, 0, 0}, m);
  CellGraph g;
  g.cells = {Cell{"left", {0, 1}, {}}, Cell{"right", {2, 3}, {}}};
  AtlasParams params;
  params.density = 8.0f;
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), params, ctx);
  ASSERT_EQ(atlas.patches.size(), 1u) << "expected the two quads merged into one chart";
  const ExrChannel c = cellChannel(atlas, s, g);
  EXPECT_EQ(c.name, "cell");
  size_t left = 0, right = 0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) {
      EXPECT_EQ(c.values[i], -1.0f);
      continue;
    }
    const float expected = atlas.position[i].x < 1.0f ? 0.0f : 1.0f;
    EXPECT_EQ(c.values[i], expected) << "texel at x = " << atlas.position[i].x;
    (expected == 0.0f ? left : right)++;
  }
  EXPECT_GT(left, 0u);
  EXPECT_GT(right, 0u);
  EXPECT_EQ(cellNames(g), (std::vector<std::string>{"left", "right"}));
}

}  // namespace
}  // namespace cpgi
