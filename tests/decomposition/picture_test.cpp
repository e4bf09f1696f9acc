// decomposition.png of a two-storey house: one plan per storey, so the rooms of both floors show (a single
// plan from above showed only the upper floor's); each room's colour stands where the room is.
#include <gtest/gtest.h>

#include <set>

#include "decomposition/decompose.h"
#include "decomposition/picture.h"
#include "scenes/buildings.h"

namespace cpgi::decomp {
namespace {

TEST(Picture, TwoStoreyHouseShowsEveryRoomOfBothFloorsWhereItIs) {
  const Building b = makeBuilding("house-stair");
  DecomposeParams params;
  params.voxelSize = 0.1;
  Context ctx;
  const Decomposition d = decompose(b.seed.scene, params, ctx);
  const PictureParams picture;
  const ImageRGB img = drawDecomposition(d, picture);
  const GridFrame& f = d.frame;
  const int scale = std::max(1, picture.targetWidth / std::max(f.dims.x, f.dims.z));
  const int panel = f.dims.x * scale, gap = 8;
  ASSERT_EQ(img.width, 2 * panel + gap);  // two storeys side by side
  ASSERT_EQ(img.height, (f.dims.z + f.dims.y) * scale + gap);

  // In each room, 1.2 m above its floor, the empty voxel nearest its middle: in the panel of its storey
  // (ground floor left) the picture shows that voxel's cell colour.
  std::set<int> shown;
  for (const BuildingRoom& room : b.rooms) {
    SCOPED_TRACE(room.name);
    const Box3& box = room.boxes.front();
    const glm::ivec3 lo = f.voxelOf(box.lo), hi = f.voxelOf(box.hi);
    const glm::ivec3 middle = f.voxelOf(glm::vec3(box.centre().x, box.lo.y + 1.2f, box.centre().z));
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

}  // namespace
}  // namespace cpgi::decomp
