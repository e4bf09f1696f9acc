// writeGltf → loadScene keeps triangles, materials, cells, portals and cameras (.glb and .gltf).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/scene_io.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

void addQuad(Scene& s, glm::vec3 o, glm::vec3 u, glm::vec3 v, uint32_t material, uint32_t node) {
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  Triangle a, b;
  a.p = {o, o + u, o + u + v};
  b.p = {o, o + u + v, o + v};
  a.n = b.n = {n, n, n};
  a.material = b.material = material;
  a.node = b.node = node;
  s.triangles.push_back(a);
  s.triangles.push_back(b);
}

// Two unit rooms side by side along +x: A = [0,1], B = [1,2], each a floor and a ceiling, and in A an
// emissive quad under the ceiling. The portal is the opening at x = 1.
struct TwoRooms {
  Scene scene;
  CellGraph cells;
  TwoRooms() {
    scene.materials = {Material{"floor", glm::vec3(0.5f, 0.25f, 0.125f), glm::vec3(0.0f)},
                       Material{"light", glm::vec3(0.8f), glm::vec3(100.0f, 50.0f, 0.5f)},
                       Material{"dim", glm::vec3(0.1f, 0.2f, 0.3f), glm::vec3(0.25f, 0.5f, 0.75f)}};
    scene.nodePaths = {"house/floorA", "house/lampA", "house/floorB"};
    addQuad(scene, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0, 0);                    // A floor, normal +y
    addQuad(scene, {0.25f, 0.99f, 0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f}, 1, 1);  // A lamp, normal -y
    addQuad(scene, {1, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2, 2);                    // B floor
    addQuad(scene, {1, 1, 0}, {1, 0, 0}, {0, 0, 1}, 0, 2);                    // B ceiling, normal -y
    scene.cameras.push_back(Camera{"view", glm::vec3(0.5f, 0.5f, 2.0f),
                                   glm::normalize(glm::vec3(0.3f, -0.1f, -1.0f)), glm::vec3(0, 1, 0), 0.9f,
                                   1.5f});
    scene.cameras[0].up =
        glm::normalize(scene.cameras[0].up -
                       glm::dot(scene.cameras[0].up, scene.cameras[0].forward) * scene.cameras[0].forward);
    cells.cells = {Cell{"A", {0, 1, 2, 3}, {}}, Cell{"B", {4, 5, 6, 7}, {}}};
    PortalQuad p;
    p.name = "portal:A:B";
    p.corners = {glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(1, 1, 1), glm::vec3(1, 0, 1)};
    p.cellA = 0, p.cellB = 1;
    computePortalFrame(p);
    if (p.normal.x < 0) std::swap(p.corners[1], p.corners[3]), computePortalFrame(p);
    cells.portals.push_back(p);
    // A box volume for A (12 triangles) to check cellvolume round trips.
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        Scene tmp;
        glm::vec3 o(0.0f), u(0.0f), v(0.0f);
        o[axis] = float(side);
        u[(axis + 1) % 3] = 1.0f;
        v[(axis + 2) % 3] = 1.0f;
        addQuad(tmp, o, side ? u : v, side ? v : u, 0, 0);
        for (const Triangle& t : tmp.triangles) cells.cells[0].volume.push_back(t);
      }
  }
};

class GltfRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfRoundTrip, PreservesTrianglesMaterialsCellsPortalsCameras) {
  const TwoRooms rooms;
  test::TempDir dir;
  const std::string path = dir / (std::string("rooms") + GetParam());
  GltfWriteOptions options;
  options.cells = &rooms.cells;
  writeGltf(path, rooms.scene, options);
  const LoadedScene loaded = loadScene(path);
  const Scene& s = loaded.scene;

  // Triangles come back grouped by node and material; match each original by its positions.
  ASSERT_EQ(s.triangles.size(), rooms.scene.triangles.size());
  std::vector<int> match(rooms.scene.triangles.size(), -1);
  for (size_t i = 0; i < rooms.scene.triangles.size(); ++i) {
    const Triangle& want = rooms.scene.triangles[i];
    for (size_t j = 0; j < s.triangles.size(); ++j) {
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && glm::length(s.triangles[j].p[k] - want.p[k]) <= 1e-6f;
      if (same) match[i] = static_cast<int>(j);
    }
    ASSERT_GE(match[i], 0) << "triangle " << i << " lost";
    const Triangle& got = s.triangles[match[i]];
    for (int k = 0; k < 3; ++k) EXPECT_LE(glm::length(got.n[k] - want.n[k]), 1e-6f);
    const Material& gm = s.materials[got.material];
    const Material& wm = rooms.scene.materials[want.material];
    EXPECT_EQ(gm.name, wm.name);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(gm.albedo[c], wm.albedo[c], 1e-6f);
      EXPECT_NEAR(gm.emission[c], wm.emission[c], 1e-5f * std::max(1.0f, wm.emission[c]));
    }
    // Node paths survive under the cell node that replaced nothing (these paths had no cell: part).
    const std::string cellName = i < 4 ? "A" : "B";
    EXPECT_EQ(s.nodePaths[got.node], "cell:" + cellName + "/" + rooms.scene.nodePaths[want.node]);
  }

  ASSERT_EQ(loaded.cells.cells.size(), 2u);
  for (size_t c = 0; c < 2; ++c) {
    const Cell& cell = loaded.cells.cells[c];
    const int original = rooms.cells.findCell(cell.name);
    ASSERT_GE(original, 0);
    std::vector<int> want;
    for (uint32_t t : rooms.cells.cells[original].triangles) want.push_back(match[t]);
    std::vector<int> got(cell.triangles.begin(), cell.triangles.end());
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << "cell " << cell.name;
    EXPECT_EQ(cell.volume.size(), rooms.cells.cells[original].volume.size());
  }

  ASSERT_EQ(loaded.cells.portals.size(), 1u);
  const PortalQuad& p = loaded.cells.portals[0];
  EXPECT_EQ(p.name, "portal:A:B");
  EXPECT_EQ(loaded.cells.cells[p.cellA].name, "A");
  EXPECT_EQ(loaded.cells.cells[p.cellB].name, "B");
  EXPECT_NEAR(p.normal.x, 1.0f, 1e-6f);
  EXPECT_NEAR(p.area, 1.0f, 1e-6f);
  EXPECT_LE(glm::length(p.centre() - glm::vec3(1.0f, 0.5f, 0.5f)), 1e-6f);

  ASSERT_EQ(s.cameras.size(), 1u);
  const Camera& want = rooms.scene.cameras[0];
  const Camera& got = s.cameras[0];
  EXPECT_EQ(got.name, want.name);
  EXPECT_LE(glm::length(got.position - want.position), 1e-6f);
  EXPECT_LE(glm::length(got.forward - want.forward), 1e-5f);
  EXPECT_LE(glm::length(got.up - want.up), 1e-5f);
  EXPECT_NEAR(got.yfov, want.yfov, 1e-6f);
  EXPECT_NEAR(got.aspect, want.aspect, 1e-6f);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
}

INSTANTIATE_TEST_SUITE_P(Formats, GltfRoundTrip, ::testing::Values(".glb", ".gltf"));

TEST(GltfWriter, WithoutCellsKeepsNodePathsAndHasNoGraph) {
  const TwoRooms rooms;
  test::TempDir dir;
  writeGltf(dir / "plain.glb", rooms.scene);
  const LoadedScene loaded = loadScene(dir / "plain.glb");
  EXPECT_TRUE(loaded.cells.empty());
  EXPECT_TRUE(loaded.cells.portals.empty());
  std::vector<std::string> paths;
  for (const Triangle& t : loaded.scene.triangles) paths.push_back(loaded.scene.nodePaths[t.node]);
  EXPECT_EQ(std::count(paths.begin(), paths.end(), "house/floorA"), 2);
  EXPECT_EQ(std::count(paths.begin(), paths.end(), "house/floorB"), 4);
  EXPECT_NEAR(loaded.scene.emittedPower().r, rooms.scene.emittedPower().r, 1e-3f);
}

TEST(GltfWriter, BakedFileIsUnlitWithLightmapAndKeepsMaterialsInExtras) {
  const TwoRooms rooms;
  test::TempDir dir;
  std::vector<std::array<glm::vec2, 3>> uvs(rooms.scene.triangles.size());
  for (size_t i = 0; i < uvs.size(); ++i)
    uvs[i] = {glm::vec2(0.1f * i, 0.0f), glm::vec2(0.1f * i, 1.0f), glm::vec2(0.5f, 0.5f)};
  ImageRGB light;
  light.width = 2, light.height = 2;
  light.pixels = {glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(0.25f), glm::vec3(0.0f)};
  GltfWriteOptions options;
  options.lightmapUVs = &uvs;
  options.lightmapPng = encodePng(light);
  writeGltf(dir / "baked.glb", rooms.scene, options);

  std::ifstream in(dir / "baked.glb", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t jsonLength;
  std::memcpy(&jsonLength, bytes.data() + 12, 4);
  const nlohmann::json doc = nlohmann::json::parse(bytes.substr(20, jsonLength));
  EXPECT_EQ(doc["extensionsUsed"], nlohmann::json::array({"KHR_materials_unlit"}));
  ASSERT_EQ(doc["materials"].size(), rooms.scene.materials.size());
  for (const auto& m : doc["materials"]) {
    EXPECT_TRUE(m["extensions"].contains("KHR_materials_unlit"));
    EXPECT_EQ(m["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
    EXPECT_EQ(m["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"], 1);
  }
  for (const auto& mesh : doc["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      EXPECT_TRUE(prim["attributes"].contains("TEXCOORD_0"));
      EXPECT_TRUE(prim["attributes"].contains("TEXCOORD_1"));
    }
  EXPECT_EQ(doc["images"][0]["mimeType"], "image/png");

  // Reading it back gives the materials it was baked with, not the lightmap's mean.
  const LoadedScene loaded = loadScene(dir / "baked.glb");
  ASSERT_EQ(loaded.scene.materials.size(), rooms.scene.materials.size());
  for (const Material& m : loaded.scene.materials) {
    const auto it = std::find_if(rooms.scene.materials.begin(), rooms.scene.materials.end(),
                                 [&](const Material& w) { return w.name == m.name; });
    ASSERT_NE(it, rooms.scene.materials.end());
    EXPECT_LE(glm::length(m.albedo - it->albedo), 1e-6f);
    EXPECT_LE(glm::length(m.emission - it->emission), 1e-4f);
  }
  // And each triangle's lightmap coordinates (TEXCOORD_1), for `cpgi view`; by position, as the cells
  // are not written here and the triangle order may change.
  ASSERT_EQ(loaded.lightmapUVs.size(), loaded.scene.triangles.size());
  for (size_t t = 0; t < loaded.scene.triangles.size(); ++t) {
    size_t match = uvs.size();
    for (size_t u = 0; u < rooms.scene.triangles.size(); ++u)
      if (rooms.scene.triangles[u].p == loaded.scene.triangles[t].p) match = u;
    ASSERT_LT(match, uvs.size()) << t;
    EXPECT_EQ(loaded.lightmapUVs[t], uvs[match]) << t;
  }
  // A scene without them has none.
  writeGltf(dir / "plain.glb", rooms.scene);
  EXPECT_TRUE(loadScene(dir / "plain.glb").lightmapUVs.empty());
}

TEST(GltfWriter, WritesThroughAnOutputDir) {
  const TwoRooms rooms;
  test::TempDir dir;
  {
    OutputDir out(dir.path());
    writeGltf(out.file("cells.glb").string(), rooms.scene);
    writeGltf(out.file("cells.gltf").string(), rooms.scene);
    out.commit();
  }
  EXPECT_EQ(loadScene(dir / "cells.glb").scene.triangles.size(), rooms.scene.triangles.size());
  EXPECT_EQ(loadScene(dir / "cells.gltf").scene.triangles.size(), rooms.scene.triangles.size());
}

TEST(GltfWriter, RejectsOtherExtensionsAndLeavesNoTemporary) {
  const TwoRooms rooms;
  test::TempDir dir;
  EXPECT_THROW(writeGltf(dir / "scene.obj", rooms.scene), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace cpgi
