// The automatic cells' names (issue 50): by storey and floor area, unique, the outside left to "outside".
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "decomposition/decompose.h"
#include "decomposition/volume_cells.h"
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

// The rooms of an IFC export come with their names (IfcSpace, here the buildings' cellvolume: boxes): the
// watershed's cells under a room's box take its name; with the boxes moved away none does.
TEST(RoomNames, AutomaticCellsTakeTheNameOfTheRoomVolumeThatCoversThem) {
  const Building b = makeBuilding("house-stair");
  CellGraph volumes, away;
  std::set<std::string> volumeNames;
  for (const Cell& c : b.seed.cells.cells) {
    if (c.volume.empty()) continue;
    volumes.cells.push_back(Cell{c.name, {}, c.volume});
    volumeNames.insert(c.name);
    Cell moved{c.name, {}, c.volume};
    for (Triangle& t : moved.volume)
      for (glm::vec3& q : t.p) q += glm::vec3(500.0f, 0.0f, 0.0f);
    away.cells.push_back(moved);
  }
  ASSERT_GE(volumes.cells.size(), 3u);
  DecomposeParams params;
  params.voxelSize = 0.1;
  Context ctx;
  Decomposition d = decompose(b.seed.scene, params, ctx);
  Decomposition unnamed = d;
  EXPECT_EQ(nameCellsByVolumes(unnamed, away), 0);
  EXPECT_EQ(unnamed.graph.cells[0].name, d.graph.cells[0].name);

  const int renamed = nameCellsByVolumes(d, volumes);
  const int rooms = int(d.graph.cells.size()) - (d.outsideCell >= 0 ? 1 : 0);
  EXPECT_GE(renamed, rooms - 1) << "of " << rooms;  // a landing no box covers may keep its size name
  std::set<std::string> seen;
  for (size_t c = 0; c < d.graph.cells.size(); ++c) {
    const std::string& name = d.graph.cells[c].name;
    EXPECT_TRUE(seen.insert(name).second) << name << " twice";
    if (int(c) == d.outsideCell) {
      EXPECT_EQ(name, "outside");
    }
    bool fromARoom = false;
    for (const std::string& r : volumeNames)
      fromARoom = fromARoom || name == r || name.rfind(r + "-", 0) == 0;
    const bool bySize = std::regex_match(name, std::regex("s[0-9]+-[0-9]+m2(-[0-9]+)?"));
    EXPECT_TRUE(name == "outside" || fromARoom || bySize) << name;
  }
  for (const PortalQuad& q : d.graph.portals)
    EXPECT_EQ(q.name,
              "portal:" + d.graph.cells[size_t(q.cellA)].name + ":" + d.graph.cells[size_t(q.cellB)].name);
}

}  // namespace
}  // namespace cpgi::decomp
