// Hostile glTF files (issue 15), built byte by byte by the tests: each must end in one InputError naming
// the file and the problem, never in a crash, a hang, a huge allocation or a read outside the scene.
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

}  // namespace
}  // namespace cpgi
