// decomposition.png of a two-storey house: one plan per storey, so the rooms of both floors show (a single
// plan from above showed only the upper floor's); each room's colour stands where the room is.
#include <gtest/gtest.h>

#include <set>

#include "decomposition/decompose.h"
#include "decomposition/picture.h"
#include "scenes/buildings.h"

namespace cpgi::decomp {
namespace {

// The two-storey house with a stair and its cells at 0.1 m voxels, decomposed once for the tests that
// draw it.
struct DecomposedHouse {
  Building building;
  Decomposition cells;
};
const DecomposedHouse& houseStairAt10cm() {
  static const DecomposedHouse house = [] {
    Building b = makeBuilding("house-stair");
    DecomposeParams params;
    params.voxelSize = 0.1;
    Context ctx;
    Decomposition d = decompose(b.seed.scene, params, ctx);
    return DecomposedHouse{std::move(b), std::move(d)};
  }();
  return house;
}

TEST(Picture, TwoStoreyHouseShowsEveryRoomOfBothFloorsWhereItIs) {
  const auto& [b, d] = houseStairAt10cm();
  const PictureParams picture;
  const ImageRGB img = drawDecomposition(d, picture);
  const GridFrame& f = d.frame;
  const int scale = std::max(1, picture.targetWidth / std::max(f.dims.x, f.dims.z));
  const int panel = f.dims.x * scale, gap = 8;
  ASSERT_EQ(img.width, 3 * panel + 2 * gap);  // two storeys side by side, then the elevation
  ASSERT_EQ(img.height, std::max(f.dims.z, f.dims.y) * scale);

  // In each room, 1.2 m above its floor, the empty voxel nearest a point a quarter of the way across it
  // (its middle holds the cell's name): in the panel of its storey (ground floor left) the picture shows
  // that voxel's cell colour.
  std::set<int> shown;
  for (const BuildingRoom& room : b.rooms) {
    SCOPED_TRACE(room.name);
    const Box3& box = room.boxes.front();
    const glm::ivec3 lo = f.voxelOf(box.lo), hi = f.voxelOf(box.hi);
    const glm::ivec3 middle = f.voxelOf(
        glm::vec3(glm::mix(box.lo.x, box.hi.x, 0.25f), box.lo.y + 1.2f, glm::mix(box.lo.z, box.hi.z, 0.25f)));
    glm::ivec3 best(-1);
    int bestDistance = 1 << 30;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int x = lo.x; x <= hi.x; ++x) {
        const int cell = d.voxelCell[f.index(x, middle.y, z)];
        const int distance = (x - middle.x) * (x - middle.x) + (z - middle.z) * (z - middle.z);
        if (cell >= 0 && cell != d.outsideCell && distance < bestDistance)
          best = {x, middle.y, z}, bestDistance = distance;
      }
    ASSERT_GE(best.x, 0);
    const int cell = d.voxelCell[f.index(best)];
    const int storey = box.lo.y > 2.0f ? 1 : 0;
    EXPECT_EQ(img.at(storey * (panel + gap) + best.x * scale + scale / 2, best.z * scale + scale / 2),
              cellColour(cell));
    shown.insert(cell);
  }
  EXPECT_EQ(shown.size(), b.rooms.size());
}

// The names and the scale bar are drawn: a room's name covers its middle in dark ink on a light box, and
// each plan's bottom left corner holds the bar (dark pixels where the plan shows only outside).
TEST(Picture, NamesEveryRoomAndHasAScaleBar) {
  const auto& [b, d] = houseStairAt10cm();
  const ImageRGB img = drawDecomposition(d);
  const GridFrame& f = d.frame;
  const int scale = std::max(1, PictureParams{}.targetWidth / std::max(f.dims.x, f.dims.z));
  const glm::vec3 ink(0.08f), paper(0.92f);
  auto count = [&](int x0, int y0, int x1, int y1, glm::vec3 colour) {
    int n = 0;
    for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
      for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) n += img.at(x, y) == colour;
    return n;
  };
  const glm::ivec3 middle = f.voxelOf(b.rooms.front().boxes.front().centre());
  const int cx = middle.x * scale, cz = middle.z * scale;
  EXPECT_GT(count(cx - 20, cz - 10, cx + 20, cz + 10, ink), 10);
  EXPECT_GT(count(cx - 20, cz - 10, cx + 20, cz + 10, paper), 50);
  const int bottom = f.dims.z * scale;
  EXPECT_GT(count(0, bottom - 30, f.dims.x * scale / 2, bottom, ink), 50);
}

}  // namespace
}  // namespace cpgi::decomp
