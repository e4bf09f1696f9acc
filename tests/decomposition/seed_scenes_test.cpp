// The automatic decomposition of the seed scenes (design.md §4) against their hand-made cells.
#include <gtest/gtest.h>

#include "decomposition/compare.h"
#include "decomposition/decompose.h"
#include "scenes/seed_scenes.h"

namespace cpgi::decomp {
namespace {

class SeedDecomposition : public ::testing::TestWithParam<int> {};

TEST_P(SeedDecomposition, MatchesTheHandMadeCells) {
  const SeedScene seed = makeSeedScene(GetParam());
  Context ctx;
  DecomposeParams p;
  p.voxelSize = 0.05;
  p.sourceName = "seed" + std::to_string(GetParam());
  const Decomposition d = decompose(seed.scene, p, ctx);
  for (const auto& w : ctx.warnings()) ADD_FAILURE() << w;
  ASSERT_EQ(d.graph.cells.size(), 3u);
  ASSERT_EQ(d.graph.portals.size(), 2u);
  EXPECT_EQ(d.leakingFaces, 0u);

  // Portal centres within one voxel of the doors, planes parallel to them.
  const std::vector<PortalMatch> matches = matchPortals(seed.cells.portals, d.graph.portals);
  std::vector<int> used;
  for (const PortalMatch& m : matches) {
    EXPECT_LT(m.centreDistance, float(p.voxelSize)) << seed.cells.portals[size_t(m.reference)].name;
    EXPECT_LT(m.normalAngle, 2.0f);
    EXPECT_NEAR(m.areaRatio, 1.0f, 0.15f);
    used.push_back(m.candidate);
  }
  EXPECT_NE(used[0], used[1]);

  const std::vector<int32_t> manual = labelsFromCells(seed.scene, seed.cells, d.frame, d.space);
  EXPECT_GE(adjustedRandIndex(d.voxelCell, manual), 0.95);
  for (double iou : bestMatchIoU(manual, 3, d.voxelCell, 3)) EXPECT_GE(iou, 0.95);

  // Triangles: each piece goes to the cell of the room it lies in, rooms bounded by the automatic portal
  // planes (pieces of the door reveals are split there), cells matched to rooms by their voxels.
  std::vector<int> roomToCell(3, -1);
  for (int c = 0; c < 3; ++c) {
    std::vector<size_t> votes(3, 0);
    for (size_t i = 0; i < manual.size(); ++i)
      if (manual[i] == c && d.voxelCell[i] >= 0) ++votes[size_t(d.voxelCell[i])];
    roomToCell[size_t(c)] = int(std::max_element(votes.begin(), votes.end()) - votes.begin());
  }
  const float x1 = std::min(d.graph.portals[0].centre().x, d.graph.portals[1].centre().x);
  const float x2 = std::max(d.graph.portals[0].centre().x, d.graph.portals[1].centre().x);
  const std::vector<int> cellOf = d.graph.cellOfTriangle(d.scene.triangles.size());
  double wrongArea = 0.0, totalArea = 0.0;
  size_t wrong = 0;
  for (size_t t = 0; t < d.scene.triangles.size(); ++t) {
    const Triangle& tri = d.scene.triangles[t];
    const float x = tri.centroid().x;
    const int room = x < x1 ? 0 : x < x2 ? 1 : 2;
    totalArea += tri.area();
    if (cellOf[t] != roomToCell[size_t(room)]) wrongArea += tri.area(), ++wrong;
  }
  EXPECT_LT(wrongArea, 1e-4 * totalArea) << wrong << " triangles in the wrong cell";
}

INSTANTIATE_TEST_SUITE_P(Seeds, SeedDecomposition, ::testing::Values(1, 2, 3));

}  // namespace
}  // namespace cpgi::decomp
