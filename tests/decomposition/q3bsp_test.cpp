// bench/q3bsp.h, the Quake III BSP reader the decomposition's real levels come through, on a BSP built in
// memory: which faces become walls; and bench/q3_materials.h, the level's materials from the game's data.
#include "bench/q3bsp.h"

#define STB_IMAGE_IMPLEMENTATION
#include "bench/q3_materials.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/scene_io.h"
#include "tests/support/temp_dir.h"

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

// A zip archive (a .pk3) of `files`, each stored, or deflated as given: (name, bytes, deflated size; 0 for
// stored, else the uncompressed size the deflated bytes give).
std::string zipArchive(const std::vector<std::tuple<std::string, std::string, uint32_t>>& files) {
  std::string body, directory;
  auto put16 = [](std::string& s, uint32_t v) { s += char(v & 0xff), s += char(v >> 8 & 0xff); };
  auto put32 = [&](std::string& s, uint32_t v) { put16(s, v & 0xffff), put16(s, v >> 16); };
  for (const auto& [name, bytes, size] : files) {
    const uint32_t offset = uint32_t(body.size()), method = size ? 8 : 0,
                   full = size ? size : uint32_t(bytes.size());
    put32(body, 0x04034b50), put16(body, 20), put16(body, 0), put16(body, method), put32(body, 0);
    put32(body, 0), put32(body, uint32_t(bytes.size())), put32(body, full);
    put16(body, uint32_t(name.size())), put16(body, 0);
    body += name + bytes;
    put32(directory, 0x02014b50), put16(directory, 20), put16(directory, 20), put16(directory, 0);
    put16(directory, method), put32(directory, 0), put32(directory, 0),
        put32(directory, uint32_t(bytes.size()));
    put32(directory, full), put16(directory, uint32_t(name.size())), put16(directory, 0), put16(directory, 0);
    put16(directory, 0), put16(directory, 0), put32(directory, 0), put32(directory, offset);
    directory += name;
  }
  std::string end;
  put32(end, 0x06054b50), put16(end, 0), put16(end, 0), put16(end, uint32_t(files.size()));
  put16(end, uint32_t(files.size())), put32(end, uint32_t(directory.size())),
      put32(end, uint32_t(body.size()));
  put16(end, 0);
  return body + directory + end;
}

// A 2 × 2 uncompressed true-colour TGA of one colour (8-bit sRGB, given as R, G, B).
std::string solidTga(uint8_t r, uint8_t g, uint8_t b) {
  std::string tga(18, '\0');
  tga[2] = 2, tga[12] = 2, tga[14] = 2, tga[16] = 24;
  for (int k = 0; k < 4; ++k) tga += char(b), tga += char(g), tga += char(r);
  return tga;
}

// A script naming textures/test/0 a lamp (q3map_surfacelight 1000) showing textures/test/lamp.tga, and
// textures/test/1 a wall whose image is not in the archive; deflated (raw, as zip stores it), 183 bytes.
const unsigned char kShaderScriptDeflated[] = {
    0x5d, 0x8e, 0xb1, 0x0e, 0xc2, 0x30, 0x0c, 0x44, 0xe7, 0xf8, 0x2b, 0x3c, 0x30, 0x37, 0xa9, 0xf8, 0xa0,
    0xca, 0xa2, 0x26, 0x0d, 0x4a, 0x68, 0x48, 0x5c, 0x81, 0x54, 0xf5, 0xdf, 0xeb, 0x50, 0x31, 0x94, 0xed,
    0xe4, 0x7b, 0xbe, 0x3b, 0x6b, 0x91, 0x30, 0x52, 0xca, 0x48, 0xcf, 0x51, 0xe5, 0x9b, 0x62, 0x04, 0xe1,
    0x8f, 0x2c, 0x85, 0xab, 0x15, 0xae, 0x62, 0x1d, 0xac, 0x60, 0x5e, 0x5c, 0x06, 0x1e, 0x83, 0xcc, 0x25,
    0x24, 0xf2, 0x8c, 0x67, 0xa4, 0x05, 0x74, 0xe2, 0x49, 0xb9, 0x6b, 0xa2, 0x3c, 0xd4, 0xa5, 0xdc, 0xe9,
    0xc6, 0x31, 0xf8, 0x49, 0xb0, 0x77, 0xce, 0x81, 0xd1, 0x0c, 0xa3, 0x16, 0x5e, 0xbe, 0x47, 0x55, 0x60,
    0x36, 0xd8, 0xfe, 0xaa, 0xfa, 0x56, 0xf5, 0x23, 0xcf, 0x56, 0x1b, 0xd6, 0x3d, 0xb2, 0x3f, 0xde, 0x76};

// Issue 46: a closed level has no sky to light it and its lamps are its light shaders; with one material
// for the whole level `--emit` could only make every face a lamp. Each shader is its own material, named
// by its path, coloured by its texture's mean from the game's archive, and `--emit NAME` lights that
// shader's faces alone.
TEST(Q3Materials, EachShaderIsAMaterialAndEmitLightsTheLampShaderAlone) {
  const std::string bsp = squareFacesBsp({{0, q3bsp::kContentsSolid}, {0, q3bsp::kContentsSolid}});
  const q3bsp::Mesh mesh = q3bsp::convert(bsp, q3bsp::Options());
  ASSERT_TRUE(mesh.error.empty()) << mesh.error;
  ASSERT_EQ(mesh.triangleShader, (std::vector<int32_t>{0, 0, 1, 1}));
  EXPECT_EQ(mesh.shaders, (std::vector<std::string>{"textures/test/0", "textures/test/1"}));

  cpgi::test::TempDir dir;
  const std::string script(reinterpret_cast<const char*>(kShaderScriptDeflated),
                           sizeof kShaderScriptDeflated);
  std::ofstream(dir / "pak0.pk3", std::ios::binary) << zipArchive(
      {{"scripts/test.shader", script, 183}, {"textures/test/lamp.tga", solidTga(255, 0, 128), 0}});
  const q3materials::GameData data({dir / "pak0.pk3"});
  EXPECT_TRUE(data.unread.empty());
  const q3materials::Level level = q3materials::levelFiles(mesh, &data, "test level", "level.mtl");
  ASSERT_EQ(level.materials.size(), 2u);
  const q3materials::Material& lamp = level.materials[0];
  EXPECT_EQ(lamp.name, "textures/test/0");
  EXPECT_EQ(lamp.surfaceLight, 1000.0);
  EXPECT_TRUE(lamp.colourFound);
  EXPECT_NEAR(lamp.kd[0], 1.0, 1e-6);  // the texels' mean in linear reflectance: sRGB 128 is 0.2159
  EXPECT_NEAR(lamp.kd[1], 0.0, 1e-6);
  EXPECT_NEAR(lamp.kd[2], 0.2159, 1e-4);
  EXPECT_FALSE(level.materials[1].colourFound);  // its image is not in the archive: grey
  EXPECT_EQ(level.materials[1].kd[0], 0.5);
  EXPECT_EQ(q3materials::emitFlags(level.materials), "--emit textures/test/0=100");

  std::ofstream(dir / "level.obj") << level.obj;
  std::ofstream(dir / "level.mtl") << level.mtl;
  cpgi::LoadOptions options;
  options.overrides.push_back({"textures/test/0", glm::vec3(100.0f), std::nullopt});
  const cpgi::LoadedScene loaded = cpgi::loadScene(dir / "level.obj", options);
  ASSERT_EQ(loaded.scene.triangles.size(), 4u);
  int lit = 0;
  for (const cpgi::Triangle& t : loaded.scene.triangles) {
    const cpgi::Material& m = loaded.scene.materials[t.material];
    const bool isLamp = t.centroid().y < 0.1f;  // face 0 lies at height 0, face 1 at 0.6 m
    lit += m.emission.x > 0.0f;
    EXPECT_EQ(m.emission, isLamp ? glm::vec3(100.0f) : glm::vec3(0.0f));
    EXPECT_NEAR(m.albedo.z, isLamp ? 0.2159f : 0.5f, 1e-3f);
  }
  EXPECT_EQ(lit, 2);
}

// Shader paths become names --emit can take (it splits on '='); a script's stages and comments are read.
TEST(Q3Materials, NamesAreShaderPathsAndScriptsGiveImageAndLight) {
  EXPECT_EQ(q3materials::materialName("textures/base_light/ceil1_39"), "textures/base_light/ceil1_39");
  EXPECT_EQ(q3materials::materialName("textures/odd name=2"), "textures/odd_name_2");
  EXPECT_EQ(q3materials::materialName(""), "noshader");
  const auto shaders = q3materials::parseShaderScript(
      "Textures/A/Lamp // a comment { }\n{\n q3map_surfacelight 2500\n {\n map $lightmap\n }\n {\n"
      " map textures/a/lamp_glow.tga\n }\n}\ntextures/a/plain\n{\n}\n");
  ASSERT_EQ(shaders.size(), 2u);
  EXPECT_EQ(shaders.at("textures/a/lamp").surfaceLight, 2500.0);
  EXPECT_EQ(shaders.at("textures/a/lamp").image, "textures/a/lamp_glow.tga");
  EXPECT_EQ(shaders.at("textures/a/plain").surfaceLight, 0.0);
}

TEST(Q3Bsp, ANonBspFileIsSaidSo) {
  EXPECT_FALSE(q3bsp::convert("PK\x03\x04", q3bsp::Options()).error.empty());
}

}  // namespace
