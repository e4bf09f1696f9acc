// The glTF reader against files built byte by byte (tests/support/glb_builder.h), not by cpgi's writer.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "core/scene_io.h"
#include "tests/support/expect_vec.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

using test::expectNear;

LoadedScene load(const test::GlbBuilder& g, const std::string& name = "scene.glb", LoadOptions options = {}) {
  test::TempDir dir;
  if (name.size() > 5 && name.substr(name.size() - 5) == ".gltf")
    test::GlbBuilder::writeBytes(dir / name, g.gltf());
  else
    g.writeGlb(dir / name);
  return loadScene(dir / name, options);
}

std::string loadError(const test::GlbBuilder& g, LoadOptions options = {}) {
  try {
    load(g, "scene.glb", options);
  } catch (const InputError& e) {
    return e.problem();
  }
  return "no error";
}

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

TEST(GltfReader, TranslatedRotatedScaledNode) {
  test::GlbBuilder g;
  const int mesh = g.addMesh(kTriangle);
  const double s = std::sqrt(0.5);
  g.addNode({{"name", "trs"},
             {"mesh", mesh},
             {"translation", {1, 2, 3}},
             {"rotation", {0, 0, s, s}},
             {"scale", {2, 2, 2}}});
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.triangles.size(), 1u);
  const Triangle& t = scene.triangles[0];
  // Scale by 2, turn 90° about +z ((x, y) → (−y, x)), move by (1, 2, 3).
  expectNear(t.p[0], {1, 2, 3});
  expectNear(t.p[1], {1, 4, 3});
  expectNear(t.p[2], {-1, 2, 3});
  expectNear(t.n[0], {0, 0, 1});
  EXPECT_EQ(scene.nodePaths[t.node], "trs");
}

TEST(GltfReader, MatrixOfChildComposesWithParentAndNormalsUseInverseTranspose) {
  test::GlbBuilder g;
  // A triangle whose plane is x + y = 1 (normal (1,1,0)/√2) with per-vertex normals.
  const std::vector<float> p = {1, 0, 0, 0, 1, 0, 1, 0, 1};
  const float r = std::sqrt(0.5f);
  json prim = {
      {"attributes", {{"POSITION", g.addVec3(p)}, {"NORMAL", g.addVec3({r, r, 0, r, r, 0, r, r, 0})}}}};
  g.doc["meshes"].push_back({{"name", "slanted"}, {"primitives", json::array({prim})}});
  // Child: a column-major matrix scaling x by 2; parent: a translation.
  const int child = g.addNode(
      {{"name", "child"}, {"mesh", 0}, {"matrix", {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}}, false);
  g.addNode({{"name", "parent"}, {"translation", {10, 0, 0}}, {"children", {child}}});
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.triangles.size(), 1u);
  const Triangle& t = scene.triangles[0];
  expectNear(t.p[0], {12, 0, 0});
  expectNear(t.p[1], {10, 1, 0});
  expectNear(t.p[2], {12, 0, 1});
  // The scaled plane is x/2 + y = 1: its normal is (1, 2, 0)/√5, which the inverse transpose gives.
  expectNear(t.n[1], glm::normalize(glm::vec3(1, 2, 0)));
  expectNear(t.geometricNormal(), glm::normalize(glm::vec3(1, 2, 0)));
  EXPECT_EQ(scene.nodePaths[t.node], "parent/child");
}

TEST(GltfReader, MirroringTransformKeepsWindingConsistentWithNormals) {
  test::GlbBuilder g;
  json prim = {{"attributes",
                {{"POSITION", g.addVec3(kTriangle)}, {"NORMAL", g.addVec3({0, 0, 1, 0, 0, 1, 0, 0, 1})}}}};
  g.doc["meshes"].push_back({{"primitives", json::array({prim})}});
  g.addNode({{"mesh", 0}, {"scale", {-1, 1, 1}}});
  const Triangle t = load(g).scene.triangles.at(0);
  expectNear(t.n[0], {0, 0, 1});
  expectNear(t.geometricNormal(), {0, 0, 1});
}

TEST(GltfReader, MissingNormalsBecomeGeometricNormals) {
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh({0, 0, 0, 0, 0, 1, 1, 0, 0})}});
  const Triangle t = load(g).scene.triangles.at(0);
  for (const glm::vec3& n : t.n) expectNear(n, {0, 1, 0});
}

TEST(GltfReader, EveryIndexTypeStripAndFan) {
  test::GlbBuilder g;
  // A unit square as 4 vertices: as a list (u8, u16, u32), a strip and a fan: 2 triangles each.
  const std::vector<float> sq = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int list8 = g.addMesh(sq, {0, 1, 2, 0, 2, 3}, -1, 4, 5121);
  const int list16 = g.addMesh(sq, {0, 1, 2, 0, 2, 3}, -1, 4, 5123);
  const int list32 = g.addMesh(sq, {0, 1, 2, 0, 2, 3}, -1, 4, 5125);
  const int strip = g.addMesh(sq, {0, 1, 3, 2}, -1, 5, 5123);
  const int fan = g.addMesh(sq, {0, 1, 2, 3}, -1, 6, 5121);
  int z = 0;
  for (int m : {list8, list16, list32, strip, fan}) g.addNode({{"mesh", m}, {"translation", {0, 0, z++}}});
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.triangles.size(), 10u);
  for (const Triangle& t : scene.triangles) {
    EXPECT_NEAR(t.area(), 0.5f, 1e-6f);
    expectNear(t.geometricNormal(), {0, 0, 1});  // strips alternate winding; the reader undoes it
  }
}

TEST(GltfReader, LinesArePointsAreRejectedNamingMeshAndMode) {
  for (const auto& [mode, name] :
       {std::pair{1, "LINES"}, std::pair{0, "POINTS"}, std::pair{3, "LINE_STRIP"}}) {
    test::GlbBuilder g;
    const int mesh = g.addMesh(kTriangle, {}, -1, mode);
    g.doc["meshes"][mesh]["name"] = "wires";
    g.addNode({{"mesh", mesh}});
    const std::string problem = loadError(g);
    EXPECT_NE(problem.find("wires"), std::string::npos) << problem;
    EXPECT_NE(problem.find(name), std::string::npos) << problem;
  }
}

TEST(GltfReader, MaterialsFactorTextureMeanEmissiveStrengthAndDefault) {
  test::GlbBuilder g;
  // A 2×1 texture, linear (1, 0.5, 0) and (0, 0.5, 1): its linear mean is 0.5 in every channel
  // (up to 8-bit sRGB rounding of 0.5).
  ImageRGB tex;
  tex.width = 2, tex.height = 1;
  tex.pixels = {glm::vec3(1, 0.5f, 0), glm::vec3(0, 0.5f, 1)};
  const std::string png = encodePng(tex);
  g.doc["images"] =
      json::array({{{"bufferView", g.addView(png.data(), png.size())}, {"mimeType", "image/png"}}});
  g.doc["textures"] = json::array({{{"source", 0}}});
  const int textured =
      g.addMaterial({{"name", "textured"},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {0.8, 0.4, 0.2, 1}}, {"baseColorTexture", {{"index", 0}}}}}});
  const int lamp =
      g.addMaterial({{"name", "lamp"},
                     {"emissiveFactor", {1.0, 0.5, 0.25}},
                     {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 40.0}}}}}});
  g.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  g.doc["extensionsRequired"] = {"KHR_materials_emissive_strength"};
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, textured)}});
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, lamp)}, {"translation", {0, 0, 1}}});
  g.addNode({{"mesh", g.addMesh(kTriangle)}, {"translation", {0, 0, 2}}});
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.triangles.size(), 3u);
  const Material& m0 = scene.materials[scene.triangles[0].material];
  const Material& m1 = scene.materials[scene.triangles[1].material];
  const Material& m2 = scene.materials[scene.triangles[2].material];
  EXPECT_EQ(m0.name, "textured");
  expectNear(m0.albedo, glm::vec3(0.8f, 0.4f, 0.2f) * 0.5f, 2e-3f);
  EXPECT_FALSE(m0.isEmitter());
  EXPECT_EQ(m1.name, "lamp");
  expectNear(m1.emission, {40, 20, 10}, 1e-4f);
  expectNear(m1.albedo, {1, 1, 1});  // glTF's default baseColorFactor
  expectNear(m2.albedo, {0.5f, 0.5f, 0.5f});
  expectNear(m2.emission, {0, 0, 0});
  expectNear(scene.emittedPower(), glm::vec3(40, 20, 10) * 0.5f, 1e-4f);
}

TEST(GltfReader, ExtrasAndExtensionsOfTheWrongTypeAreIgnored) {
  test::GlbBuilder g;
  const int m = g.addMaterial({{"emissiveFactor", {1.0, 1.0, 1.0}},
                               {"extras", 5},
                               {"extensions", {{"KHR_materials_emissive_strength", 3}}}});
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, m)}});
  const Scene scene = load(g).scene;
  expectNear(scene.materials[scene.triangles[0].material].emission, {1, 1, 1});
}

TEST(GltfReader, PerspectiveCameraFromNode) {
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  g.doc["cameras"] =
      json::array({{{"type", "perspective"},
                    {"name", "eye"},
                    {"perspective", {{"yfov", 0.7}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
                   {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
  const double s = std::sqrt(0.5);
  // Turned 90° about +y: looks down −x instead of −z.
  g.addNode({{"name", "cam"}, {"camera", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}});
  g.addNode({{"name", "second"}, {"camera", 1}});
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.cameras.size(), 2u);
  const Camera& c = scene.cameras[0];
  EXPECT_EQ(c.name, "eye");
  expectNear(c.position, {1, 2, 3});
  expectNear(c.forward, {-1, 0, 0});
  expectNear(c.up, {0, 1, 0});
  EXPECT_NEAR(c.yfov, 0.7f, 1e-6f);
  EXPECT_NEAR(c.aspect, 2.0f, 1e-6f);
  EXPECT_EQ(scene.cameras[1].name, "second");
  EXPECT_NEAR(scene.cameras[1].aspect, 4.0f / 3.0f, 1e-6f);
  expectNear(scene.cameras[1].forward, {0, 0, -1});
}

TEST(GltfReader, DefaultSceneIsChosenAndInstancedMeshesRepeat) {
  test::GlbBuilder g;
  const int mesh = g.addMesh(kTriangle);
  g.addNode({{"name", "in0"}, {"mesh", mesh}});  // scene 0
  const int a = g.addNode({{"name", "a"}, {"mesh", mesh}}, false);
  const int b = g.addNode({{"name", "b"}, {"mesh", mesh}, {"translation", {0, 0, 5}}}, false);
  g.doc["scenes"].push_back({{"nodes", {a, b}}});
  g.doc["scene"] = 1;
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.triangles.size(), 2u);
  EXPECT_EQ(scene.nodePaths[scene.triangles[0].node], "a");
  EXPECT_EQ(scene.nodePaths[scene.triangles[1].node], "b");
  EXPECT_NEAR(scene.triangles[1].p[0].z, 5.0f, 1e-6f);
}

TEST(GltfReader, WithoutScenesAllRootNodesAreRead) {
  test::GlbBuilder g;
  const int mesh = g.addMesh(kTriangle);
  const int child = g.addNode({{"name", "child"}, {"mesh", mesh}, {"translation", {0, 0, 1}}}, false);
  g.addNode({{"name", "root"}, {"mesh", mesh}, {"children", {child}}}, false);
  g.doc.erase("scene");
  g.doc.erase("scenes");
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.triangles.size(), 2u);
  EXPECT_EQ(scene.nodePaths[scene.triangles[1].node], "root/child");
}

TEST(GltfReader, AsciiGltfWithEmbeddedBuffer) {
  test::GlbBuilder g;
  g.addNode({{"name", "t"}, {"mesh", g.addMesh(kTriangle, {0, 1, 2})}});
  const Scene scene = load(g, "scene.gltf").scene;
  ASSERT_EQ(scene.triangles.size(), 1u);
  expectNear(scene.triangles[0].p[1], {1, 0, 0});
}

TEST(GltfReader, ExternalBufferAndImageFilesNextToTheGltf) {
  test::GlbBuilder g;
  ImageRGB tex;
  tex.width = 1, tex.height = 1;
  tex.pixels = {glm::vec3(0.5f, 0.25f, 1.0f)};
  g.doc["images"] = json::array({{{"uri", "tex.png"}}});
  g.doc["textures"] = json::array({{{"source", 0}}});
  const int m = g.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, m)}});
  json doc = g.doc;
  doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", "data.bin"}}});
  test::TempDir dir;
  test::GlbBuilder::writeBytes(dir / "external.gltf", doc.dump());
  test::GlbBuilder::writeBytes(dir / "data.bin", g.bin);
  writePng(dir / "tex.png", tex);
  const Scene scene = loadScene(dir / "external.gltf").scene;
  ASSERT_EQ(scene.triangles.size(), 1u);
  // One texel: the mean is the texel, back through 8-bit sRGB.
  expectNear(scene.materials[scene.triangles[0].material].albedo, {0.5f, 0.25f, 1.0f}, 4e-3f);

  std::filesystem::remove(dir / "data.bin");
  try {
    loadScene(dir / "external.gltf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir / "external.gltf");
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(GltfReader, UnsupportedRequiredExtensionIsNamed) {
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  g.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_NE(loadError(g).find("KHR_draco_mesh_compression"), std::string::npos) << loadError(g);
}

TEST(GltfReader, OutOfRangeAccessorsAndIndicesAreInputErrors) {
  {
    test::GlbBuilder g;
    g.addNode({{"mesh", g.addMesh(kTriangle)}});
    g.doc["accessors"][0]["count"] = 1000;  // runs past the bufferView
    EXPECT_NE(loadError(g).find("past the end"), std::string::npos) << loadError(g);
  }
  {
    test::GlbBuilder g;
    g.addNode({{"mesh", g.addMesh(kTriangle, {0, 1, 7})}});
    EXPECT_NE(loadError(g).find("index 7 is out of range"), std::string::npos) << loadError(g);
  }
  {
    test::GlbBuilder g;
    g.addNode({{"mesh", g.addMesh(kTriangle)}});
    g.doc["bufferViews"][0]["byteLength"] = 4096;  // past the end of the buffer
    EXPECT_NE(loadError(g), "no error");
  }
  {
    test::GlbBuilder g;
    const int n = g.addNode({{"name", "loop"}, {"mesh", g.addMesh(kTriangle)}});
    g.doc["nodes"][n]["children"] = {n};
    EXPECT_NE(loadError(g), "no error");
  }
}

TEST(GltfReader, DegenerateAndDuplicateTrianglesAreDroppedWithOneWarningOrRefusedWhenStrict) {
  test::GlbBuilder g;
  // Two copies of one triangle, one with its corners rotated (the same triangle), a zero-area one and
  // the mirror-wound copy (a two-sided face, kept).
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0,
                                0, 0, 0, 1, 1, 1, 2, 2, 2, 0, 0, 0, 0, 1, 0, 1, 0, 0};
  g.addNode({{"name", "messy"}, {"mesh", g.addMesh(p)}});
  const LoadedScene loaded = load(g);
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_EQ(loaded.warnings[0],
            "dropped 1 zero-area triangle and 1 duplicate triangle (first in node 'messy'); --strict refuses "
            "them");

  LoadOptions strict;
  strict.strict = true;
  const std::string error = loadError(g, strict);
  EXPECT_EQ(error, "1 zero-area triangle and 1 duplicate triangle (first in node 'messy'); without `strict` "
                   "they are dropped");
}

TEST(GltfReader, NothingLeftOnceDegenerateTrianglesAreDroppedIsAnError) {
  test::GlbBuilder g;
  g.addNode({{"name", "sliver"}, {"mesh", g.addMesh({0, 0, 0, 1, 1, 1, 2, 2, 2})}});
  EXPECT_EQ(loadError(g), "no triangles left once the degenerate ones are dropped");
}

}  // namespace
}  // namespace cpgi
