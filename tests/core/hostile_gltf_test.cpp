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

}  // namespace
}  // namespace cpgi
