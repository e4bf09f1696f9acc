// Numbers a solve cannot survive (issue 15, defects 3 and 6), refused at load by one rule for glTF and
// OBJ: albedo within [0, 1], emission finite and not negative, total emitted power far from float's
// range, OBJ numbers that really are numbers, cameras with a usable frame.
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

std::string loadError(const std::string& path) {
  try {
    loadScene(path);
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.problem();
  }
  return "no error";
}

std::string gltfError(const test::GlbBuilder& g) {
  test::TempDir dir;
  g.writeGlb(dir / "scene.glb");
  return loadError(dir / "scene.glb");
}

// A one-triangle OBJ using material "m" of the given MTL text.
std::string objError(const std::string& mtl, const std::string& vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n") {
  test::TempDir dir;
  std::ofstream(dir / "scene.mtl") << mtl;
  std::ofstream(dir / "scene.obj") << "mtllib scene.mtl\n" << vertices << "usemtl m\nf 1 2 3\n";
  return loadError(dir / "scene.obj");
}

test::GlbBuilder withMaterial(const json& material) {
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, g.addMaterial(material))}});
  return g;
}

void expectHas(const std::string& problem, const std::string& text) {
  EXPECT_NE(problem.find(text), std::string::npos) << problem;
}

TEST(HostileNumbers, AlbedoAboveOneIsRefusedInGltfAndObjAlike) {
  expectHas(gltfError(withMaterial(
                {{"name", "m"}, {"pbrMetallicRoughness", {{"baseColorFactor", {2, 0.5, 0.5, 1}}}}})),
            "material 'm': albedo (2, 0.5, 0.5) is not within [0, 1]");
  expectHas(objError("newmtl m\nKd 2 0.5 0.5\n"), "material 'm': albedo (2, 0.5, 0.5) is not within [0, 1]");
}

TEST(HostileNumbers, ObjNumbersThatAreNotFiniteNumbersAreRefusedNotReadAsZero) {
  expectHas(objError("newmtl m\nKd inf 0 0\n"),
            "material file 'scene.mtl' line 2 'Kd inf 0 0': 'inf' is not a finite number");
  expectHas(objError("newmtl m\nKd nan 0 0\n"), "'nan' is not a finite number");
  expectHas(objError("newmtl m\nKd 1e39 0 0\n"), "'1e39' is not a finite number");
  expectHas(objError("newmtl m\nKe 1 1 x\n"), "'x' is not a finite number");
  expectHas(objError("newmtl m\nKd 0.5\n"), "Kd takes 3 numbers, found 1");
  expectHas(objError("newmtl m\nKd 0.5 0.5 0.5\n", "v abc 0 0\nv 1 0 0\nv 0 1 0\n"),
            "line 2 'v abc 0 0': 'abc' is not a finite number");
  expectHas(objError("newmtl m\nKd 0.5 0.5 0.5\n", "v 0 0\nv 1 0 0\nv 0 1 0\n"),
            "v takes 3 to 7 numbers, found 2");
}

TEST(HostileNumbers, OrdinaryNumbersStillLoad) {
  EXPECT_EQ(objError("newmtl m\nKd 0.5 0.25 1 # grey\nKe +0 0 1.5e2\n",
                     "v 0 0 0\n  v\t1.0 -0 0 1\nv 0 1 0 0.1 0.2 0.3\nvn 0 0 1\n"),
            "no error");
}

TEST(HostileNumbers, EmissionTimesAreaBeyondFloatIsRefusedInGltfAndObjAlike) {
  const json lamp = {{"name", "lamp"},
                     {"emissiveFactor", {1, 1, 1}},
                     {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 1e30}}}}}};
  expectHas(gltfError(withMaterial(lamp)), "the scene emits 5e+29 W, more than 1e+20 W");
  expectHas(objError("newmtl m\nKd 0.5 0.5 0.5\nKe 1e30 1e30 1e30\n"), "the scene emits 5e+29 W");
  expectHas(gltfError(withMaterial({{"name", "m"}, {"emissiveFactor", {1, -1, 1}}})), "emission");
}

TEST(HostileNumbers, CameraWhoseTransformFlattensItsUpAxisIsRefused) {
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  g.doc["cameras"] =
      json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}});
  g.addNode({{"name", "flat"}, {"camera", 0}, {"scale", {1, 0, 1}}});
  expectHas(gltfError(g), "node 'flat': camera transform is degenerate");
}

TEST(HostileNumbers, CameraWithAbsurdAspectRatioIsRefused) {
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  g.doc["cameras"] = json::array(
      {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"aspectRatio", 1e-30}, {"znear", 0.1}}}}});
  g.addNode({{"name", "thin"}, {"camera", 0}});
  expectHas(gltfError(g), "aspectRatio must be within [0.001, 1000]");
}

}  // namespace
}  // namespace cpgi
