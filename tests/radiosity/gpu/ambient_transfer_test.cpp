// Where the light leaving each cell's surfaces goes, measured by rays (radiosity/solve/ambient_transfer.h),
// against what reciprocity says of an enclosure with one open face: of the light its inner faces send
// out (spread over them by area), the share leaving through the opening is A_opening / A_faces.
#include "radiosity/solve/ambient_transfer.h"

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;

struct Box {
  Scene scene;
  LightmapAtlas atlas;
  std::vector<float> cell;  ///< per texel: 0 for x < 0.5, 1 beyond
  explicit Box(bool open, float albedo = 0.5f) {
    addClosedBox(scene, glm::vec3(0.0f), glm::vec3(1.0f), addMaterial(scene, glm::vec3(albedo)));
    if (open) scene.triangles.erase(scene.triangles.begin() + 2, scene.triangles.begin() + 4);  // the top
    Context ctx;
    atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.density = 16.0f}, ctx);
    cell.assign(atlas.texelCount(), -1.0f);
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (atlas.patch[t] >= 0) cell[t] = atlas.position[t].x < 0.5f ? 0.0f : 1.0f;
  }
};

double escape(const std::vector<double>& row) {
  double landed = 0.0;
  for (double v : row) landed += v;
  return 1.0 - landed;
}

TEST(AmbientTransfer, AnOpenBoxSendsOutItsOpeningsShareAndItsHalvesTradeAlike) {
  const Box box(true);
  const AmbientTransfer t = measureAmbientTransfer(box.atlas, RayScene(box.scene), box.cell, 2);
  ASSERT_EQ(t.share.size(), 3u);  // two cells and "no cell"
  // 1 m² open against 5 m² of faces: 0.2 leaves, for either half by symmetry (8192 rays: σ ≈ 0.005).
  EXPECT_NEAR(escape(t.share[0]), 0.2, 0.02);
  EXPECT_NEAR(escape(t.share[1]), 0.2, 0.02);
  EXPECT_NEAR(t.share[0][1], t.share[1][0], 0.03);
  EXPECT_GT(t.share[0][1], 0.2);  // each half sees much of the other
  // No texel is in no cell: that entry keeps what it has, and nobody sends it anything.
  EXPECT_DOUBLE_EQ(t.share[2][2], 1.0);
  EXPECT_DOUBLE_EQ(t.share[0][2], 0.0);
}

TEST(AmbientTransfer, AClosedBoxKeepsAllItsLight) {
  const Box box(false);
  const AmbientTransfer t = measureAmbientTransfer(box.atlas, RayScene(box.scene), box.cell, 2);
  EXPECT_LT(std::abs(escape(t.share[0])), 0.005);
  EXPECT_LT(std::abs(escape(t.share[1])), 0.005);
  // The same rays for the same seed.
  const AmbientTransfer again = measureAmbientTransfer(box.atlas, RayScene(box.scene), box.cell, 2);
  EXPECT_EQ(t.share, again.share);
}

// Albedo 1, closed, one cell: no walk loses light or leaves the cell, so only the bounce bound ends them;
// the arrival's landed light is the bounces followed, at most the bound's 256 and the arrival itself.
TEST(AmbientTransfer, WalksInAClosedRoomOfAlbedoOneEnd) {
  Box box(false, 1.0f);
  for (float& c : box.cell)
    if (c >= 0.0f) c = 0.0f;
  const AmbientTransfer t =
      measureAmbientTransfer(box.atlas, RayScene(box.scene), box.cell, 1, /*raysPerCell=*/256, 0x5eed, 64);
  ASSERT_EQ(t.arrivals.size(), 1u);
  EXPECT_LE(t.arrivals[0].landed.r, 257.0);
  EXPECT_GT(t.arrivals[0].landed.r, 200.0);  // the walks were followed to the bound, not dropped
}

}  // namespace
}  // namespace cpgi
