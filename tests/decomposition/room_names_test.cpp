// The automatic cells' names (issue 50): by storey and floor area, unique, the outside left to "outside".
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "decomposition/decompose.h"
#include "scenes/buildings.h"

namespace cpgi::decomp {
namespace {

CellStats box(glm::vec3 lo, glm::vec3 hi) {
  CellStats s;
  s.bounds.extend(lo);
  s.bounds.extend(hi);
  const glm::vec3 size = hi - lo;
  s.volume = double(size.x) * size.y * size.z;
  return s;
}

TEST(RoomNames, StoreyAndFloorAreaAndASuffixForTwins) {
  const std::vector<CellStats> stats = {
      box({0, 0, 0}, {4, 2.5f, 6}),       // 24 m² on the ground floor
      box({0, 3, 0}, {4, 5.5f, 6}),       // the same upstairs
      box({-50, -5, -50}, {50, 20, 50}),  // the outside
      box({4, 0.2f, 0}, {8, 2.5f, 6}),    // a step up is the same storey, and the same area: a twin
      box({0, 6, 0}, {2, 8.5f, 3.2f}),    // 6.4 m² in the attic
  };
  const std::vector<std::string> names = roomNames(stats, 2);
  EXPECT_EQ(names, (std::vector<std::string>{"s1-24m2", "s2-24m2", "", "s1-24m2-2", "s3-6m2"}));
}

TEST(RoomNames, TheTwoStoreyHousesCellsAreNamedByTheirFloor) {
  const Building b = makeBuilding("house-stair");
  DecomposeParams params;
  params.voxelSize = 0.1;
  Context ctx;
  const Decomposition d = decompose(b.seed.scene, params, ctx);
  std::set<std::string> seen;
  const std::regex pattern("s([12])-[0-9]+m2(-[0-9]+)?");
  for (size_t c = 0; c < d.graph.cells.size(); ++c) {
    const std::string& name = d.graph.cells[c].name;
    EXPECT_TRUE(seen.insert(name).second) << name << " twice";
    if (int(c) == d.outsideCell) {
      EXPECT_EQ(name, "outside");
      continue;
    }
    std::smatch m;
    ASSERT_TRUE(std::regex_match(name, m, pattern)) << name;
    EXPECT_EQ(m[1].str(), d.cellStats[c].bounds.lo.y < 2.0f ? "1" : "2") << name;
  }
}

}  // namespace
}  // namespace cpgi::decomp
