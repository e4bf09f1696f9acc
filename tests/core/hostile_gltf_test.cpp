// Hostile glTF files (issue 15), built byte by byte by the tests: each must end in one InputError naming
// the file and the problem, never in a crash, a hang, a huge allocation or a read outside the scene.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

// The problem text of the InputError loading `g` as scene.glb, or "no error".
std::string loadError(const test::GlbBuilder& g, LoadOptions options = {}) {
  test::TempDir dir;
  g.writeGlb(dir / "scene.glb");
  try {
    loadScene(dir / "scene.glb", options);
  } catch (const InputError& e) {
    return e.problem();
  }
  return "no error";
}

// One triangle mesh under a root node; returns the builder for further damage.
test::GlbBuilder oneTriangle() {
  test::GlbBuilder g;
  g.addNode({{"name", "tri"}, {"mesh", g.addMesh(kTriangle)}});
  return g;
}

TEST(HostileGltf, BufferViewLengthThatWrapsAroundIsPastTheEnd) {
  test::GlbBuilder g = oneTriangle();
  // byteOffset 16 + byteLength 2^64 - 16 wraps to 0 in 64 bits.
  g.doc["bufferViews"][0]["byteOffset"] = 16;
  g.doc["bufferViews"][0]["byteLength"] = uint64_t(0) - 16;
  EXPECT_NE(loadError(g).find("past the end"), std::string::npos) << loadError(g);
}

TEST(HostileGltf, AccessorOffsetThatWrapsAroundIsPastTheEnd) {
  test::GlbBuilder g = oneTriangle();
  // An accessor offset of 2^64 - 8 points 8 bytes before the buffer.
  g.doc["accessors"][0]["byteOffset"] = uint64_t(0) - 8;
  EXPECT_NE(loadError(g).find("past the end"), std::string::npos) << loadError(g);
}

TEST(HostileGltf, BufferViewOffsetBeyondItsBufferIsPastTheEnd) {
  test::GlbBuilder g = oneTriangle();
  g.doc["bufferViews"][0]["byteOffset"] = uint64_t(0) - 4;
  g.doc["bufferViews"][0]["byteLength"] = 36;
  EXPECT_NE(loadError(g).find("past the end"), std::string::npos) << loadError(g);
}

// A chain of `depth` nodes, each the only child of the one before, the last holding a triangle.
test::GlbBuilder nestedNodes(int depth, const std::string& namePrefix = "n") {
  test::GlbBuilder g;
  const int mesh = g.addMesh(kTriangle);
  for (int i = 0; i < depth; ++i) {
    json node = {{"name", namePrefix + std::to_string(i)}};
    if (i + 1 < depth) node["children"] = {i + 1};
    if (i + 1 == depth) node["mesh"] = mesh;
    g.addNode(node, i == 0);
  }
  return g;
}

TEST(HostileGltf, TenThousandNestedNodesAreRefusedWithoutOverflowingTheStack) {
  EXPECT_NE(loadError(nestedNodes(10000)).find("deeper than 256 levels"), std::string::npos)
      << loadError(nestedNodes(10000));
}

TEST(HostileGltf, ModeratelyNestedNodesStillLoad) {
  EXPECT_EQ(loadError(nestedNodes(200)), "no error");
}

TEST(HostileGltf, LongNodePathsAreRefusedInsteadOfCostingQuadraticMemory) {
  // 100 levels of 200-character names: each path would be 20 KB.
  const std::string longName(200, 'x');
  EXPECT_NE(loadError(nestedNodes(100, longName)).find("longer than 4096 characters"), std::string::npos);
}

TEST(HostileGltf, DeeplyNestedJsonIsRefusedBeforeTheParserRecursesIntoIt) {
  test::GlbBuilder g = oneTriangle();
  const std::string deep = std::string(16000, '[') + std::string(16000, ']');
  std::string text = g.jsonWithBuffer().dump();
  text.insert(text.rfind('}'), ",\"extras\":" + deep);
  test::TempDir dir;
  for (const std::string name : {"scene.glb", "scene.gltf"}) {
    test::GlbBuilder::writeBytes(dir / name, name == "scene.glb" ? g.glbWithJson(text) : text);
    try {
      loadScene(dir / name);
      ADD_FAILURE() << name << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(e.problem().find("nested deeper than 64 levels"), std::string::npos) << e.what();
    }
  }
}

TEST(HostileGltf, BracketsInsideStringsDoNotCountAsNesting) {
  test::GlbBuilder g = oneTriangle();
  g.doc["nodes"][0]["extras"] = {{"note", std::string(500, '[') + "\"{"}};
  EXPECT_EQ(loadError(g), "no error");
}

TEST(HostileGltf, AccessorWithoutBufferViewCannotAskForBillionsOfZeros) {
  test::GlbBuilder g = oneTriangle();
  g.doc["accessors"][0].erase("bufferView");
  g.doc["accessors"][0]["count"] = 1000000000;  // 12 GB of zeros from a file of a few hundred bytes
  EXPECT_NE(loadError(g).find("has no bufferView and 1000000000 elements"), std::string::npos)
      << loadError(g);
}

// The start of a PNG: signature and header chunk, saying width × height 8-bit RGB; no pixel data.
std::string pngHeader(uint32_t width, uint32_t height) {
  auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
  std::string chunk = "IHDR" + be32(width) + be32(height) + std::string{8, 2, 0, 0, 0};
  uint32_t crc = 0xFFFFFFFFu;  // CRC-32 of type and data, as PNG wants it
  for (unsigned char c : chunk) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = crc & 1 ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
  }
  return "\x89PNG\r\n\x1a\n" + be32(13) + chunk + be32(~crc);
}

// A triangle; image 0 is `png`, embedded through a bufferView; the material uses it when `used`.
test::GlbBuilder withEmbeddedImage(const std::string& png, bool used) {
  test::GlbBuilder g;
  const int view = g.addView(png.data(), png.size());
  g.doc["images"] = json::array({{{"bufferView", view}, {"mimeType", "image/png"}}});
  g.doc["textures"] = json::array({{{"source", 0}}});
  const int m = used ? g.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}})
                     : g.addMaterial({{"name", "plain"}});
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, m)}});
  return g;
}

TEST(HostileGltf, UnusedImagesAreNeverDecoded) {
  // A header promising 16384² texels and no data: decoding would allocate gigabytes or fail.
  EXPECT_EQ(loadError(withEmbeddedImage(pngHeader(16384, 16384), false)), "no error");
}

TEST(HostileGltf, HugeTextureIsRefusedFromItsHeaderBeforeDecoding) {
  const std::string problem = loadError(withEmbeddedImage(pngHeader(16384, 16384), true));
  EXPECT_NE(problem.find("16384x16384, more than the 8192x8192"), std::string::npos) << problem;
}

TEST(HostileGltf, ImageBufferViewPastItsBufferIsRefused) {
  test::GlbBuilder g = withEmbeddedImage(pngHeader(1, 1), true);
  g.doc["bufferViews"][0]["byteLength"] = 1 << 20;  // tinygltf would hand 1 MB past the buffer to a decoder
  EXPECT_NE(loadError(g).find("image 0: bufferView 0 runs past the end of its buffer"), std::string::npos)
      << loadError(g);
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// A small file whose many nodes instance one mesh: refused once the placed triangles pass the cap, before
// they are all expanded (the cap is lowered here; the default is 10 million, about 800 MB).
TEST(HostileGltf, NodesInstancingOneMeshAreCappedInTriangles) {
  std::vector<float> strip;
  for (int i = 0; i < 100; ++i) {
    const float x = float(i);
    strip.insert(strip.end(), {x, 0, 0, x + 1, 0, 0, x, 1, 0});
  }
  auto instances = [&](int nodes) {
    test::GlbBuilder g;
    const int mesh = g.addMesh(strip);
    for (int n = 0; n < nodes; ++n)
      g.addNode({{"name", "copy" + std::to_string(n)}, {"mesh", mesh}, {"translation", {0, 0, float(n)}}});
    return g;
  };
  LoadOptions capped;
  capped.maxTriangles = 5000;
  const std::string refused = loadError(instances(60), capped);
  EXPECT_NE(refused.find("nodes place more than 5000 triangles"), std::string::npos) << refused;
  EXPECT_NE(refused.find("a mesh instanced by many nodes counts once per node"), std::string::npos)
      << refused;
  EXPECT_EQ(loadError(instances(50), capped), "no error");
  EXPECT_LE(LoadOptions{}.maxTriangles, size_t(20'000'000));
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// Issue 49, item 5: a triangle at ±1e8 m made Embree abort (ray.valid()); positions past 1e6 m from the
// origin, once in metres, are refused in one line naming the node, --scale counted.
TEST(HostileGltf, CoordinatesFarFromTheOriginAreRefusedAfterScale) {
  auto at = [](float far) {
    test::GlbBuilder g;
    g.addNode({{"name", "far away"}, {"mesh", g.addMesh({far, 0, 0, far, 1, 0, far, 0, 1})}});
    return g;
  };
  const std::string problem = loadError(at(1e8f));
  EXPECT_EQ(problem,
            "node 'far away': a vertex lies 1e+08 m from the origin, beyond the 1e6 m cpgi handles (is "
            "--scale right?)");
  EXPECT_EQ(loadError(at(9e5f)), "no error");
  // Millimetres: 1e8 mm is 1e5 m.
  EXPECT_EQ(loadError(at(1e8f), LoadOptions{.scale = 0.001}), "no error");
  EXPECT_NE(loadError(at(2e6f), LoadOptions{.scale = 1.0 + 1e-9}).find("beyond the 1e6 m"),
            std::string::npos);
  test::GlbBuilder lamp = oneTriangle();
  lamp.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  lamp.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 1}}}}}}};
  lamp.addNode({{"name", "lamp"},
                {"translation", {0, -3e7, 0}},
                {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  EXPECT_NE(loadError(lamp).find("light 'lamp' lies 3e+07 m from the origin"), std::string::npos)
      << loadError(lamp);
}

// Issue 49, item 12: a portal of 100 vertices was "98 triangles and 0 vertices" (vertices are counted only
// for small meshes): a large one is said in triangles alone.
TEST(HostileGltf, LargePortalMeshIsSaidInTrianglesAlone) {
  test::GlbBuilder g;
  std::vector<float> fan = {0, 0, 0};
  std::vector<uint32_t> indices;
  for (int i = 0; i < 99; ++i) fan.insert(fan.end(), {0, std::cos(i * 0.06f), std::sin(i * 0.06f)});
  for (uint32_t i = 1; i + 1 < 100; ++i) indices.insert(indices.end(), {0, i, i + 1});
  g.addNode({{"name", "cell:A"}, {"mesh", g.addMesh({-1, 0, 0, -1, 1, 0, -1, 0, 1})}});
  g.addNode({{"name", "cell:B"}, {"mesh", g.addMesh({1, 0, 0, 1, 1, 0, 1, 0, 1})}});
  g.addNode({{"name", "portal:A:B"}, {"mesh", g.addMesh(fan, indices)}});
  const std::string problem = loadError(g);
  EXPECT_EQ(problem, "portal:A:B: a portal must be one quad (2 triangles, 4 vertices), found 98 triangles");
}

}  // namespace
}  // namespace cpgi
