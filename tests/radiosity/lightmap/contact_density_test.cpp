#include "radiosity/lightmap/contact_density.h"

#include <vector>

#include <gtest/gtest.h>

#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;

// A 4 × 3 × 2.5 m room (y up) with a 1 × 0.5 m slab lying 2 mm over its floor: the slab's underside is
// covered all over by the floor, the floor only where the slab lies.
struct SlabRoom {
  Scene scene;
  size_t slabFirst = 0;  // the slab's two triangles follow the room's twelve
  SlabRoom() {
    const uint32_t grey = addMaterial(scene, glm::vec3(0.7f));
    addClosedBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 2.5f, 3.0f), grey);
    slabFirst = scene.triangles.size();
    // Normal −y (u × v = x × z): the underside, facing the floor.
    addRect(scene, glm::vec3(1.0f, 0.002f, 1.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 0.5f),
            grey);
  }
  std::vector<float> density(float coarse, float fine) const {
    return contactDensity(scene, RayScene(scene), coarse, std::vector<float>(scene.triangles.size(), fine));
  }
  // Both triangles of the room's face whose normal is `n`.
  std::vector<float> face(const std::vector<float>& d, glm::vec3 n) const {
    std::vector<float> out;
    for (size_t i = 0; i < slabFirst; ++i)
      if (glm::dot(scene.triangles[i].geometricNormal(), n) > 0.99f) out.push_back(d[i]);
    return out;
  }
};

TEST(ContactDensity, AFloorPartlyUnderASlabIsRefinedTheSlabsCoveredUndersideIsNot) {
  const SlabRoom room;
  ASSERT_EQ(glm::dot(room.scene.triangles[room.slabFirst].geometricNormal(), glm::vec3(0, -1, 0)), 1.0f);
  const std::vector<float> d = room.density(5.0f, 20.0f);
  // The floor holds the slab's contact shadow and its edge: at the finest the output allows, on the
  // triangle the slab lies over (the other half of the floor may be clear of it).
  const std::vector<float> floor = room.face(d, glm::vec3(0, 1, 0));
  ASSERT_EQ(floor.size(), 2u);
  EXPECT_EQ(std::max(floor[0], floor[1]), 20.0f);
  // The underside sees the floor 2 mm away from every point: a shade without an edge, kept coarse.
  EXPECT_EQ(d[room.slabFirst], 5.0f);
  EXPECT_EQ(d[room.slabFirst + 1], 5.0f);
  // Nothing stands near the ceiling.
  for (float c : room.face(d, glm::vec3(0, -1, 0))) EXPECT_EQ(c, 5.0f);
}

TEST(ContactDensity, NeverFinerThanTheOutputNorCoarserUnlessItIs) {
  const SlabRoom room;
  for (float c : room.density(5.0f, 3.0f)) EXPECT_EQ(c, 3.0f);  // the output is coarser than the solve
  for (float c : room.face(room.density(5.0f, 8.0f), glm::vec3(0, 1, 0))) EXPECT_LE(c, 8.0f);
}

}  // namespace
}  // namespace cpgi
