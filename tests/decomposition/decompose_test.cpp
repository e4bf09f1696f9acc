// End-to-end decomposition of scenes built in code, against their known rooms and doors.
#include "decomposition/decompose.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/decomposition/scene_builder.h"

namespace cpgi::decomp {
namespace {

using testing::makeThreeRooms;
using testing::SceneBuilder;
using testing::ThreeRooms;

TEST(Decompose, ThreeRoomsGiveThreeCellsAndTwoDoorPortals) {
  Context ctx;
  DecomposeParams p;
  p.voxelSize = 0.1;
  const Decomposition d = decompose(makeThreeRooms(), p, ctx);
  for (const auto& w : ctx.warnings()) ADD_FAILURE() << w;
  ASSERT_EQ(d.graph.cells.size(), 3u);
  ASSERT_EQ(d.graph.portals.size(), 2u);
  EXPECT_EQ(d.leakingFaces, 0u);
  for (const PortalQuad& q : d.graph.portals) {
    const int k = q.centre().x < 6.0f ? 1 : 2;
    const glm::vec3 door = ThreeRooms::doorCentre(k);
    EXPECT_LT(glm::length(q.centre() - door), p.voxelSize) << q.name;
    EXPECT_GT(std::abs(q.normal.x), 0.999f) << q.name;
    EXPECT_NEAR(q.area, 2.1f, 0.25f) << q.name;
  }
}

}  // namespace
}  // namespace cpgi::decomp
