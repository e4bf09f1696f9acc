// bench/q3bsp.h, the Quake III BSP reader the decomposition's real levels come through, on a BSP built in
// memory: which faces become walls, which brushes seal the level (bench/q3bsp_seal.h); and
// bench/q3_materials.h, the level's materials from the game's data.
#include "bench/q3bsp.h"
#include "bench/q3bsp_seal.h"

#define STB_IMAGE_IMPLEMENTATION
#include "bench/q3_materials.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/scene_io.h"
#include "tests/support/temp_dir.h"

namespace {

// A version 46 BSP assembled in memory: each lump's data after the header, its offset and size in the
// header's directory.
struct BspFile {
  q3bsp::Lump lumps[q3bsp::kLumpCount] = {};
  std::string body;
  void put(int index, const void* data, size_t bytes) {
    lumps[index] = {int32_t(8 + sizeof(lumps) + body.size()), int32_t(bytes)};
    body.append(static_cast<const char*>(data), bytes);
  }
  std::string bytes() const {
    std::string file = "IBSP";
    const int32_t version = 46;
    file.append(reinterpret_cast<const char*>(&version), 4);
    file.append(reinterpret_cast<const char*>(lumps), sizeof(lumps));
    return file + body;
  }
};

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
  BspFile bsp;
  bsp.put(q3bsp::kTextures, tex.data(), tex.size() * sizeof(q3bsp::Texture));
  bsp.put(q3bsp::kModels, &world, sizeof(world));
  bsp.put(q3bsp::kVertices, vertices.data(), vertices.size() * sizeof(q3bsp::Vertex));
  bsp.put(q3bsp::kMeshverts, meshverts.data(), meshverts.size() * sizeof(int32_t));
  bsp.put(q3bsp::kFaces, faces.data(), faces.size() * sizeof(q3bsp::Face));
  return bsp.bytes();
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

// A world model of brushes alone: each an axis-aligned box [lo, hi] (Quake units) with the side textures
// given (flags, contents), the first on its top (+z) and the second on the other five sides.
struct BoxBrush {
  std::array<float, 3> lo, hi;
  std::pair<int32_t, int32_t> top, sides;
};
std::string brushesBsp(const std::vector<BoxBrush>& boxes) {
  std::vector<q3bsp::Texture> tex;
  std::map<std::pair<int32_t, int32_t>, int32_t> textureOf;
  auto texture = [&](std::pair<int32_t, int32_t> fc) {
    if (auto it = textureOf.find(fc); it != textureOf.end()) return it->second;
    q3bsp::Texture t{};
    std::snprintf(t.name, sizeof(t.name), "textures/test/%zu", tex.size());
    t.flags = fc.first, t.contents = fc.second;
    tex.push_back(t);
    return textureOf[fc] = int32_t(tex.size() - 1);
  };
  std::vector<q3bsp::Plane> planes;
  std::vector<q3bsp::Brush> brushes;
  std::vector<q3bsp::BrushSide> sides;
  for (const BoxBrush& b : boxes) {
    brushes.push_back({int32_t(sides.size()), 6, texture(b.sides)});
    for (int axis = 0; axis < 3; ++axis)
      for (int s = -1; s <= 1; s += 2) {
        q3bsp::Plane p{};
        p.normal[axis] = float(s);
        p.dist = s > 0 ? b.hi[size_t(axis)] : -b.lo[size_t(axis)];
        planes.push_back(p);
        sides.push_back({int32_t(planes.size() - 1), texture(axis == 2 && s > 0 ? b.top : b.sides)});
      }
  }
  q3bsp::Model world{};
  world.brush = 0, world.nBrushes = int32_t(brushes.size());
  BspFile bsp;
  bsp.put(q3bsp::kTextures, tex.data(), tex.size() * sizeof(q3bsp::Texture));
  bsp.put(q3bsp::kPlanes, planes.data(), planes.size() * sizeof(q3bsp::Plane));
  bsp.put(q3bsp::kModels, &world, sizeof(world));
  bsp.put(q3bsp::kBrushes, brushes.data(), brushes.size() * sizeof(q3bsp::Brush));
  bsp.put(q3bsp::kBrushSides, sides.data(), sides.size() * sizeof(q3bsp::BrushSide));
  return bsp.bytes();
}

// Issue 46 (am_lavaarena, ctf_gate1): a sealed map's drawn faces leave its walls' tops and blocks' insides
// open, and the outside flooded the playable space; its brushes close it. Opaque solids and opaque liquids
// seal, glass (solid but `trans`), water and clips do not; the sky's brush seals unless the sky is open.
TEST(Q3Bsp, TheSealIsTheOpaqueBrushesAndTheSkysUnlessOpen) {
  const std::pair<int32_t, int32_t> caulk{0x80, q3bsp::kContentsSolid},
      glass{0, q3bsp::kContentsSolid | kTranslucent}, water{0, q3bsp::kContentsWater | kTranslucent},
      lava{0, q3bsp::kContentsLava | kTranslucent}, sky{q3bsp::kSurfSky, q3bsp::kContentsSolid},
      playerClip{0x80, 0x10000};
  const std::string bsp = brushesBsp({
      {{0, 0, 0}, {64, 64, 8}, caulk, caulk},   // the floor
      {{0, 0, 8}, {8, 64, 72}, glass, caulk},   // a wall with one glass side: the compiler ORs them
      {{8, 0, 8}, {16, 64, 16}, water, water},  // a pool
      {{16, 0, 8}, {24, 64, 16}, lava, lava},   // a lava pit's body
      {{0, 0, 72}, {64, 64, 80}, sky, caulk},   // the sky over it
      {{24, 0, 8}, {32, 64, 72}, playerClip, playerClip},
  });
  EXPECT_EQ(q3bsp::sealBrushes(bsp, q3bsp::Options()).size(), 3u);  // floor, lava, sky
  q3bsp::Options open;
  open.openSky = true;
  EXPECT_EQ(q3bsp::sealBrushes(bsp, open).size(), 2u);
}

// The signed volume of a closed triangle mesh (divergence theorem): positive when its faces face out.
double signedVolume(const q3bsp::Solids& s) {
  double v = 0.0;
  for (const auto& t : s.triangles)
    v += q3bsp::detail::dot(s.points[t[0]], q3bsp::detail::cross(s.points[t[1]], s.points[t[2]])) / 6.0;
  return v;
}

TEST(Q3Bsp, ABrushIsAClosedSolidFacingOutInMetresYUp) {
  // A 64 × 32 × 16 box with a bevel plane that only touches its edge (as the compiler adds for collision)
  // and one that cuts its edge x = 0, z = 16 off: 10 corners.
  std::vector<q3bsp::Plane> planes;
  for (int axis = 0; axis < 3; ++axis)
    for (int s = -1; s <= 1; s += 2) {
      q3bsp::Plane p{};
      p.normal[axis] = float(s);
      const float hi[3] = {64, 32, 16};
      p.dist = s > 0 ? hi[axis] : 0.0f;
      planes.push_back(p);
    }
  const float r = float(1.0 / std::sqrt(2.0));
  planes.push_back({{r, r, 0}, (64 + 32) * r});  // bevel along the +x +y edge: touches, cuts nothing
  planes.push_back({{-r, 0, r}, (16 - 8) * r});  // cuts the edge x = 0, z = 16 back by 8 units
  const q3bsp::Solids solids = q3bsp::brushSolids({planes}, 0.5);
  ASSERT_EQ(solids.brushes, 1u);
  EXPECT_EQ(solids.degenerate, 0u);
  std::map<std::pair<size_t, size_t>, int> edges;  // each directed edge once, its reverse once: closed
  for (const auto& t : solids.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[size_t(k)], t[size_t((k + 1) % 3)]}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u);
  }
  // 64 × 32 × 16 less the prism 8 × 8 / 2 × 32, in units of 0.5 m.
  EXPECT_NEAR(signedVolume(solids), (64.0 * 32 * 16 - 32.0 * 32) * 0.125, 1e-6);
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (const q3bsp::V3& p : solids.points)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[size_t(k)]), hi[k] = std::max(hi[k], p[size_t(k)]);
  EXPECT_NEAR(hi[1] - lo[1], 8.0, 1e-9);  // Quake's z (16 units) is y
  EXPECT_NEAR(lo[2], -16.0, 1e-9);        // Quake's y (32 units) is −z
  EXPECT_NEAR(hi[0], 32.0, 1e-9);

  const std::vector<q3bsp::Plane> flat = {planes[0], planes[1], planes[2], planes[3]};  // no z sides
  EXPECT_EQ(q3bsp::brushSolids({flat}, 1.0).degenerate, 1u);
}

TEST(Q3Bsp, ANonBspFileIsSaidSo) {
  EXPECT_FALSE(q3bsp::convert("PK\x03\x04", q3bsp::Options()).error.empty());
}

}  // namespace
