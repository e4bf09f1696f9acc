// bench/q3bsp.h, the Quake III BSP reader the decomposition's real levels come through, on a BSP built in
// memory: which faces become walls.
#include "bench/q3bsp.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

// A world model of square planar faces 10 units across, one per texture given (flags, contents), each at
// its own height and facing up, written as a version 46 BSP with the lumps the reader uses.
std::string squareFacesBsp(const std::vector<std::pair<int32_t, int32_t>>& textures) {
  std::vector<q3bsp::Texture> tex;
  std::vector<q3bsp::Vertex> vertices;
  std::vector<q3bsp::Face> faces;
  const std::vector<int32_t> meshverts = {0, 1, 2, 0, 2, 3};
  for (size_t k = 0; k < textures.size(); ++k) {
    q3bsp::Texture t{};
    std::snprintf(t.name, sizeof(t.name), "textures/test/%zu", k);
    t.flags = textures[k].first, t.contents = textures[k].second;
    tex.push_back(t);
    q3bsp::Face f{};
    f.texture = int32_t(k), f.type = 1, f.vertex = int32_t(vertices.size()), f.nVertices = 4;
    f.meshvert = 0, f.nMeshverts = 6, f.normal[2] = 1.0f;
    faces.push_back(f);
    const float corners[4][2] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    for (const auto& c : corners) {
      q3bsp::Vertex v{};
      v.pos[0] = c[0], v.pos[1] = c[1], v.pos[2] = 20.0f * float(k);
      v.normal[2] = 1.0f;
      vertices.push_back(v);
    }
  }
  q3bsp::Model world{};
  world.face = 0, world.nFaces = int32_t(faces.size());
  q3bsp::Lump lumps[q3bsp::kLumpCount] = {};
  std::string body;
  auto put = [&](int index, const void* data, size_t bytes) {
    lumps[index] = {int32_t(8 + sizeof(lumps) + body.size()), int32_t(bytes)};
    body.append(static_cast<const char*>(data), bytes);
  };
  put(q3bsp::kTextures, tex.data(), tex.size() * sizeof(q3bsp::Texture));
  put(q3bsp::kModels, &world, sizeof(world));
  put(q3bsp::kVertices, vertices.data(), vertices.size() * sizeof(q3bsp::Vertex));
  put(q3bsp::kMeshverts, meshverts.data(), meshverts.size() * sizeof(int32_t));
  put(q3bsp::kFaces, faces.data(), faces.size() * sizeof(q3bsp::Face));
  std::string file = "IBSP";
  const int32_t version = 46;
  file.append(reinterpret_cast<const char*>(&version), 4);
  file.append(reinterpret_cast<const char*>(lumps), sizeof(lumps));
  return file + body;
}

constexpr int32_t kTranslucent = 0x20000000;

// Issue 46 (hydronex): its water's shader holds water contents without the non-solid flag, and the
// surface was kept as a face, sealing the level under it. Light crosses water and fog; lava (whose
// shaders hold water and fog too) and slime stay walls.
TEST(Q3Bsp, WaterAndFogFacesAreNoWallsLavaAndSlimeAre) {
  const std::string bsp = squareFacesBsp({
      {0, q3bsp::kContentsSolid},                                                    // a floor
      {0x20, q3bsp::kContentsWater | kTranslucent},                                  // hydronex's water
      {0x4c00, q3bsp::kContentsFog | kTranslucent},                                  // fog, flagged non-solid
      {0x8c20, q3bsp::kContentsLava | q3bsp::kContentsWater | q3bsp::kContentsFog},  // lava
      {0xc10, q3bsp::kContentsSlime | kTranslucent},                                 // slime
      {0x40, q3bsp::kContentsFog},                                                   // fog, not flagged
  });
  const q3bsp::Mesh mesh = q3bsp::convert(bsp, q3bsp::Options());
  ASSERT_TRUE(mesh.error.empty()) << mesh.error;
  EXPECT_EQ(mesh.triangles.size(), 6u);  // the floor, the lava and the slime
  EXPECT_EQ(mesh.skippedLiquid, 2u);     // the water and the unflagged fog
  EXPECT_EQ(mesh.skippedNonsolid, 1u);
  for (const auto& t : mesh.triangles) {
    const double y = mesh.points[t[0]][1];  // the face's height, 0.6 m a face
    EXPECT_TRUE(std::abs(y) < 1e-9 || std::abs(y - 1.8) < 1e-6 || std::abs(y - 2.4) < 1e-6) << y;
  }

  q3bsp::Options keep;
  keep.keepNonsolid = true;
  const q3bsp::Mesh all = q3bsp::convert(bsp, keep);
  EXPECT_EQ(all.triangles.size(), 12u);
  EXPECT_EQ(all.skippedLiquid, 0u);
}

TEST(Q3Bsp, ANonBspFileIsSaidSo) {
  EXPECT_FALSE(q3bsp::convert("PK\x03\x04", q3bsp::Options()).error.empty());
}

}  // namespace
