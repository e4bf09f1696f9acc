// baked.glb for engines (issue 48, items 2 and 6): the Khronos glTF validator finds no error in the engine
// glb nor in preview.glb of seed1, of the furnished house and of a textured scene; three.js loads the engine
// glb with its own materials and textures and the lightmap on TEXCOORD_1, and the picture is lit by it
// (core/html_report/web/engine_glb_test.mjs); Blender's glTF add-on imports it, on one atlas and per object,
// with each lightmap on the second UV map. Screenshots stay in BUILD_DIR/report-screenshots/engine-*.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/image_io.h"
#include "core/scene_io.h"
#include "tests/core/html_report/node_tools.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

// seed1 with a checker texture on every material through TEXCOORD_0 (0.5 a metre over each face's two
// widest axes), written as a glTF with its textures: a scene as an artist's export brings it.
std::string writeTexturedSeed1(const test::TempDir& dir) {
  const std::string plain = dir / "seed1-plain.glb", textured = dir / "textured.glb";
  EXPECT_EQ(cpgi(dir, "generate seed1 --no-cells -o " + quote(plain)).status, 0);
  LoadedScene loaded = loadScene(plain);
  Scene& scene = loaded.scene;
  std::vector<uint8_t> checker(32 * 32 * 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) checker[size_t(y * 32 + x) * 3 + c] = ((x / 8 + y / 8) % 2) ? 255 : 160;
  scene.looks = {};  // the generated file's: plain colours
  scene.looks.images.push_back({"checker", "image/png", encodePng8(32, 32, 3, checker)});
  scene.looks.textures.push_back(SurfaceTexture{});
  for (const Material& m : scene.materials) {
    MaterialLook look;
    look.baseColorFactor = glm::vec4(m.albedo, 1.0f);
    look.baseColorTexture = 0;
    scene.looks.materials.push_back(look);
  }
  for (Triangle& t : scene.triangles) {
    const glm::vec3 n = glm::abs(t.geometricNormal());
    const int drop = n.x > n.y && n.x > n.z ? 0 : n.y > n.z ? 1 : 2;
    std::array<glm::vec2, 3> uv;
    for (int k = 0; k < 3; ++k) uv[k] = 0.5f * glm::vec2(t.p[k][(drop + 1) % 3], t.p[k][(drop + 2) % 3]);
    SurfaceUV map;
    map.fit(t.p, uv, 0);
    t.uv = uint32_t(scene.looks.uvs.size());
    scene.looks.uvs.push_back(map);
  }
  GltfWriteOptions options;
  options.forEngines = true;
  writeGltf(textured, scene, options);
  return textured;
}

nlohmann::json glbJson(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

class EngineGlb : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string missing = test::missingNodeTools();
    if (!missing.empty()) GTEST_SKIP() << "SKIPPED, NOT TESTED: the node tools cannot run: " << missing;
  }
  // `cpgi bake SCENE -o DIR` at a coarse atlas, an early stop and item buffers of 128² (a sixteenth of the
  // default's pixels a shot): the files' structure is what is checked, and that the scene is lit.
  void bake(const std::string& scene, const std::string& out, const std::string& more = "",
            const std::string& atlas = " --density 3") {
    const test::CommandRun r = cpgi(dir, "bake " + quote(scene) + " -o " + quote(out) + atlas +
                                             " --unshot 0.1 --item-buffer 128 -q" + more);
    ASSERT_EQ(r.status, 0) << scene << ": " << r.err;
  }
  void expectValid(const std::vector<std::string>& files) {
    std::string args;
    for (const auto& f : files) args += " " + quote(f);
    const test::CommandRun r = test::runNodeScript(dir.path(), "validate_glb.mjs", args);
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    std::istringstream lines(r.out);
    size_t seen = 0;
    for (std::string line; std::getline(lines, line); ++seen) {
      const nlohmann::json j = nlohmann::json::parse(line);
      std::cout << std::filesystem::path(j["file"].get<std::string>()).lexically_relative(dir.path()).string()
                << ": " << j["errors"] << " errors, " << j["warnings"] << " warnings, " << j["infos"]
                << " infos\n";
      EXPECT_EQ(j["errors"], 0) << j.dump(1);
    }
    EXPECT_EQ(seen, files.size()) << r.err;
  }
  test::TempDir dir;
};

TEST_F(EngineGlb, Seed1TexturedAndFurnishedHouseHaveNoValidatorErrors) {
  const std::string seed1 = dir / "seed1.glb", house = dir / "house.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(seed1)).status, 0);
  ASSERT_EQ(cpgi(dir, "generate house-furnished -o " + quote(house)).status, 0);
  const std::string textured = writeTexturedSeed1(dir);
  bake(seed1, dir / "seed1");
  bake(seed1, dir / "seed1-helpers", " --keep-helpers");
  bake(textured, dir / "textured");
  bake(house, dir / "house", " --max-shots 20", " --density 1");
  std::vector<std::string> files = {textured};
  for (const char* out : {"seed1", "seed1-helpers", "textured", "house"})
    for (const char* glb : {"baked.glb", "preview.glb"})
      files.push_back(dir / (std::string(out) + "/" + glb));
  expectValid(files);

  // The helpers and lamps are out of the engine glb by default, in it with --keep-helpers, in the preview.
  auto names = [](const nlohmann::json& doc, const std::string& prefix) {
    int n = 0;
    for (const auto& node : doc["nodes"]) n += node.value("name", "").rfind(prefix, 0) == 0;
    return n;
  };
  const nlohmann::json engine = glbJson(dir / "house/baked.glb"),
                       preview = glbJson(dir / "house/preview.glb");
  EXPECT_EQ(names(engine, "portal:"), 0);
  EXPECT_EQ(names(engine, "cellvolume:"), 0);
  EXPECT_FALSE(engine.contains("extensions") && engine["extensions"].contains("KHR_lights_punctual"));
  EXPECT_GT(names(engine, "cell:"), 0);  // the rooms stay as node names
  EXPECT_GT(names(preview, "portal:"), 0);
  EXPECT_TRUE(preview["extensions"].contains("KHR_lights_punctual"));
  const nlohmann::json kept = glbJson(dir / "seed1-helpers/baked.glb");
  EXPECT_EQ(names(kept, "portal:"), 2);
  // Every material of the engine glb is lit (no KHR_materials_unlit) and names the lightmap.
  for (const auto& m : engine["materials"]) {
    EXPECT_FALSE(m.contains("extensions") && m["extensions"].contains("KHR_materials_unlit")) << m.dump();
    EXPECT_EQ(m["extensions"]["MOZ_lightmap"]["texCoord"], 1) << m.dump();
  }
  // The textured scene keeps its texture: two images (its checker and the lightmap), TEXCOORD_0 and _1.
  const nlohmann::json tex = glbJson(dir / "textured/baked.glb");
  EXPECT_EQ(tex["images"].size(), 2u);
  for (const auto& mesh : tex["meshes"])
    for (const auto& p : mesh["primitives"]) {
      EXPECT_TRUE(p["attributes"].contains("TEXCOORD_0"));
      EXPECT_TRUE(p["attributes"].contains("TEXCOORD_1"));
    }
  // Read back, the textured bake's engine glb has its texture as the scene had it.
  const LoadedScene back = loadScene(dir / "textured/baked.glb");
  ASSERT_EQ(back.scene.looks.images.size(), 1u);
  EXPECT_EQ(back.scene.looks.images[0].mimeType, "image/png");
}

class EngineGlbInThreeJs : public EngineGlb {
 protected:
  void SetUp() override {
    EngineGlb::SetUp();
    if (IsSkipped()) return;
    if (!std::filesystem::exists(CPGI_CHROMIUM))
      GTEST_SKIP() << "SKIPPED, NOT TESTED: chromium is not installed (./setup.sh installs it)";
  }
  void expectLit(const std::string& bakeDir, const std::string& name, const std::string& mode = "") {
    const std::string shots = std::string(CPGI_SCREENSHOTS) + "/" + name;
    const test::CommandRun r =
        test::runNodeScript(dir.path(), "engine_glb_test.mjs",
                            quote(CPGI_CHROMIUM) + " " + quote(bakeDir) + " " + quote(shots) + " " + mode);
    std::cout << "figures: " << r.out << "\nscreenshots: " << shots << "\n";
    EXPECT_EQ(r.status, 0) << r.err;
  }
};

TEST_F(EngineGlbInThreeJs, Seed1IsLitByItsLightmapOnTexcoord1) {
  const std::string seed1 = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(seed1)).status, 0);
  bake(seed1, dir / "seed1");
  expectLit(dir / "seed1", "engine-seed1");
}

// Issue 48 item 6: the directional lightmap on a normal map and a probe-lit sphere, in three.js
// (core/html_report/web/engine_directional_test.mjs says what the screenshot is checked for).
TEST_F(EngineGlbInThreeJs, Seed1DirectionalLightmapShowsANormalMapAndProbesLightASphere) {
  const std::string seed1 = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(seed1)).status, 0);
  bake(seed1, dir / "seed1", " --directional --probes");
  const std::string shots = std::string(CPGI_SCREENSHOTS) + "/engine-seed1-directional";
  const test::CommandRun r =
      test::runNodeScript(dir.path(), "engine_directional_test.mjs",
                          quote(CPGI_CHROMIUM) + " " + quote(dir / "seed1") + " " + quote(shots));
  std::cout << "figures: " << r.out << "\nscreenshots: " << shots << "\n";
  EXPECT_EQ(r.status, 0) << r.err;
}

// Issue 48 item 3's --per-object: a lightmap per object, on cpgi's charts and on the artist's UV2 (the
// per-object glb's own TEXCOORD_1, a square per object, which one layout for the scene refuses); each
// object shows its own lightmap in three.js, the picture that of the same bake on one atlas
// (core/html_report/web/engine_per_object_test.mjs), and the validator finds no error.
TEST_F(EngineGlbInThreeJs, PerObjectLightmapsEachObjectShowsItsOwn) {
  const std::string seed1 = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(seed1)).status, 0);
  bake(seed1, dir / "one");
  bake(seed1, dir / "objects", " --per-object --directional --directional-rays 16");
  const std::string artist = dir / "objects/baked.glb";
  bake(artist, dir / "artist", " --per-object --uv scene");
  const test::CommandRun refused =
      cpgi(dir, "bake " + quote(artist) + " -o " + quote(dir / "refused") + " --density 3 --uv scene -q");
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("overlapping charts"), std::string::npos) << refused.err;
  expectValid({dir / "objects/baked.glb", dir / "artist/baked.glb"});
  std::ifstream in(dir / "objects/report.json");
  const nlohmann::json engine = nlohmann::json::parse(in)["engine_lightmap"];
  ASSERT_GT(engine["objects"].size(), 1u);
  for (const auto& o : engine["objects"]) {
    EXPECT_TRUE(std::filesystem::exists(dir / ("objects/" + o["exr"].get<std::string>()))) << o.dump();
    EXPECT_TRUE(std::filesystem::exists(dir / ("objects/" + o["rgbm_png"].get<std::string>()))) << o.dump();
  }
  EXPECT_EQ(engine["directional"]["object_files"].size(), engine["objects"].size());
  for (const char* out : {"objects", "artist"}) {
    const std::string shots = std::string(CPGI_SCREENSHOTS) + "/engine-per-object-" + out;
    const test::CommandRun r = test::runNodeScript(
        dir.path(), "engine_per_object_test.mjs",
        quote(CPGI_CHROMIUM) + " " + quote(dir / out) + " " + quote(dir / "one") + " " + quote(shots));
    std::cout << out << " figures: " << r.out << "\nscreenshots: " << shots << "\n";
    EXPECT_EQ(r.status, 0) << r.err;
  }
}

// The engine glb in Blender (Debian's blender, its glTF add-on), on one atlas and with --per-object: the
// recipe of docs/engines.md wires each material's lightmap EXR on the second UV map, and every polygon
// reads the same light from its object's lightmap as from the scene's (tests/core/html_report/
// blender_engine_glb.py says what is checked).
TEST(EngineGlbInBlender, AtlasAndPerObjectLightmapsLandOnTheSecondUvMap) {
  if (!std::filesystem::exists(CPGI_BLENDER))
    GTEST_SKIP() << "SKIPPED, NOT TESTED: blender is not installed (apt-get install blender), so the engine "
                    "glb's Blender recipe is not checked";
  test::TempDir dir;
  const std::string seed1 = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(seed1)).status, 0);
  for (const auto& [out, more] :
       std::vector<std::pair<std::string, std::string>>{{"atlas", ""}, {"objects", " --per-object"}}) {
    const test::CommandRun r =
        cpgi(dir, "bake " + quote(seed1) + " -o " + quote(dir / out) + " --density 3 --unshot 0.1 -q" + more);
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const test::CommandRun r = test::runCaptured(
      dir.path(),
      quote(CPGI_BLENDER) + " -b --factory-startup --python-exit-code 1 --python " +
          quote(std::string(CPGI_SOURCE_DIR) + "/tests/core/html_report/blender_engine_glb.py") + " -- " +
          quote(dir / "atlas") + " " + quote(dir / "objects"),
      "blender-");
  std::cout << "blender: " << r.out;  // its log, the figures on the last line
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(EngineGlbInThreeJs, TexturedSceneKeepsItsTexturesAndIsLit) {
  bake(writeTexturedSeed1(dir), dir / "textured");
  expectLit(dir / "textured", "engine-textured", "textured");
}

}  // namespace
}  // namespace cpgi
