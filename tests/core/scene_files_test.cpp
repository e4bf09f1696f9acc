// The reference policy (issue 15, defect 4): a scene's buffers, images and mtllib files are read inside
// the scene's folder only, regular files only, size-checked first; the scene file itself is a regular
// file. Every refusal is one line naming the scene file and the reference.
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/image_io.h"
#include "core/scene_io.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A folder holding scene/ (the scene's folder) and, beside it, files the scene must not reach.
struct SceneFolder {
  test::TempDir root;
  std::string scene(const std::string& name) const { return root / ("scene/" + name); }
  SceneFolder() { fs::create_directory(root / "scene"); }
};

// One triangle whose buffer is the external file `uri`; g.bin holds the bytes that file should have.
std::string gltfWithBuffer(const std::string& uri, test::GlbBuilder& g) {
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  json doc = g.doc;
  doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", uri}}});
  return doc.dump();
}

// The InputError of loading `path`, or a failure.
InputError loadFailure(const std::string& path, LoadOptions options = {}) {
  try {
    loadScene(path, options);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << path << " loaded";
  return InputError(path, "loaded");
}

void expectOneLineNaming(const InputError& e, const std::string& scene, const std::string& text) {
  EXPECT_EQ(e.where(), scene);
  EXPECT_NE(e.problem().find(text), std::string::npos) << e.what();
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
}

TEST(SceneFiles, BufferUriEscapingTheFolderIsRefused) {
  SceneFolder f;
  test::GlbBuilder g;
  const std::string text = gltfWithBuffer("../secret.bin", g);
  write(f.root / "secret.bin", g.bin);
  write(f.scene("a.gltf"), text);
  const InputError e = loadFailure(f.scene("a.gltf"));
  expectOneLineNaming(e, f.scene("a.gltf"), "'../secret.bin': resolves outside the scene's folder");
  EXPECT_NE(e.problem().find("`outside files`"), std::string::npos);  // the CLI prints --allow-outside-files
}

TEST(SceneFiles, PercentEncodedDotDotIsDecodedBeforeTheCheck) {
  SceneFolder f;
  test::GlbBuilder g;
  write(f.scene("a.gltf"), gltfWithBuffer("%2e%2e/secret.bin", g));
  write(f.root / "secret.bin", g.bin);
  expectOneLineNaming(loadFailure(f.scene("a.gltf")), f.scene("a.gltf"), "outside the scene's folder");
}

// A glTF URI is an RFC 3986 reference: '+' is itself, %2B a '+', %20 a space, and a '%' without two hex
// digits after it is itself. (tinygltf alone decodes URIs as form data: `a+b.bin` would open `a b.bin`.)
TEST(SceneFiles, BufferUrisNameTheFilesTheySpell) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"a+b.bin", "a+b.bin"}, {"a%2Bc.bin", "a+c.bin"}, {"a%20d.bin", "a d.bin"}, {"a%zze.bin", "a%zze.bin"}};
  for (const auto& [uri, file] : cases) {
    SceneFolder f;
    test::GlbBuilder g;
    write(f.scene("a.gltf"), gltfWithBuffer(uri, g));
    write(f.scene(file), g.bin);
    try {
      EXPECT_EQ(loadScene(f.scene("a.gltf")).scene.triangles.size(), 1u) << uri;
    } catch (const InputError& e) {
      ADD_FAILURE() << uri << ": " << e.what();
    }
  }
}

// A scene whose material's base colour is the texture in the file `uri`.
void writeTexturedScene(const std::string& path, const std::string& uri) {
  test::GlbBuilder g;
  g.doc["images"] = json::array({{{"uri", uri}}});
  g.doc["textures"] = json::array({{{"source", 0}}});
  const int m = g.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  g.addNode({{"mesh", g.addMesh(kTriangle, {}, m)}});
  g.writeGlb(path);
}

void writeOneColourPng(const std::string& path, glm::vec3 colour) {
  ImageRGB tex;
  tex.width = tex.height = 1;
  tex.pixels = {colour};
  writePng(path, tex);
}

TEST(SceneFiles, ImageUriWithAPlusReadsItsOwnFileNotTheOneWithASpace) {
  SceneFolder f;
  writeOneColourPng(f.scene("wood+oak.png"), glm::vec3(0.0f, 1.0f, 0.0f));
  writeOneColourPng(f.scene("wood oak.png"), glm::vec3(1.0f, 0.0f, 0.0f));
  writeTexturedScene(f.scene("a.glb"), "wood+oak.png");
  const LoadedScene s = loadScene(f.scene("a.glb"));
  ASSERT_EQ(s.scene.materials.size(), 1u);
  EXPECT_EQ(s.scene.materials[0].albedo, glm::vec3(0.0f, 1.0f, 0.0f));
  std::filesystem::remove(f.scene("wood oak.png"));
  EXPECT_EQ(loadScene(f.scene("a.glb")).scene.materials[0].albedo, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(SceneFiles, MissingImageOrBufferIsNamedAsNoSuchFile) {
  SceneFolder f;
  writeTexturedScene(f.scene("a.glb"), "textures/gone+1.png");
  expectOneLineNaming(loadFailure(f.scene("a.glb")), f.scene("a.glb"),
                      "material 'material0': texture image 0 'textures/gone+1.png': no such file");
  fs::create_directory(f.scene("textures"));
  write(f.scene("textures/gone+1.png"), "");
  expectOneLineNaming(loadFailure(f.scene("a.glb")), f.scene("a.glb"), "texture image 0 is empty");
  test::GlbBuilder g;
  write(f.scene("b.gltf"), gltfWithBuffer("gone+1.bin", g));
  expectOneLineNaming(loadFailure(f.scene("b.gltf")), f.scene("b.gltf"),
                      "buffer file 'gone+1.bin': no such file");
}

// `x+y.bin` and `x%20y.bin` are two files; the parser asks for both by one name, so neither is read
// for the other.
TEST(SceneFiles, TwoUrisTheParserDecodesAlikeAreRefused) {
  SceneFolder f;
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  json doc = g.doc;
  doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", "x+y.bin"}},
                                {{"byteLength", g.bin.size()}, {"uri", "x%20y.bin"}}});
  write(f.scene("a.gltf"), doc.dump());
  write(f.scene("x+y.bin"), g.bin);
  write(f.scene("x y.bin"), g.bin);
  expectOneLineNaming(loadFailure(f.scene("a.gltf")), f.scene("a.gltf"),
                      "the URIs 'x+y.bin' and 'x%20y.bin' name two files");
}

TEST(SceneFiles, AbsoluteBufferPathIsRefused) {
  SceneFolder f;
  test::GlbBuilder g;
  write(f.scene("a.gltf"), gltfWithBuffer(f.root / "secret.bin", g));
  write(f.root / "secret.bin", g.bin);
  expectOneLineNaming(loadFailure(f.scene("a.gltf")), f.scene("a.gltf"), "is an absolute path");
}

TEST(SceneFiles, SymlinkPointingOutsideIsRefusedButOneInsideIsRead) {
  SceneFolder f;
  test::GlbBuilder g;
  write(f.scene("a.gltf"), gltfWithBuffer("link.bin", g));
  write(f.root / "secret.bin", g.bin);
  fs::create_symlink(f.root / "secret.bin", f.scene("link.bin"));
  expectOneLineNaming(loadFailure(f.scene("a.gltf")), f.scene("a.gltf"), "outside the scene's folder");

  fs::remove(f.scene("link.bin"));
  fs::create_directory(f.scene("data"));
  write(f.scene("data/real.bin"), g.bin);
  fs::create_symlink("data/real.bin", f.scene("link.bin"));
  EXPECT_EQ(loadScene(f.scene("a.gltf")).scene.triangles.size(), 1u);
}

TEST(SceneFiles, AllowOutsideFilesReadsThem) {
  SceneFolder f;
  test::GlbBuilder g;
  write(f.scene("a.gltf"), gltfWithBuffer("../secret.bin", g));
  write(f.root / "secret.bin", g.bin);
  EXPECT_EQ(loadScene(f.scene("a.gltf"), LoadOptions{.allowOutsideFiles = true}).scene.triangles.size(), 1u);
}

TEST(SceneFiles, FifoDirectoryAndDeviceAreNotRead) {
  SceneFolder f;
  test::GlbBuilder g;
  ASSERT_EQ(::mkfifo(f.scene("fifo.bin").c_str(), 0600), 0);
  fs::create_directory(f.scene("dir.bin"));
  for (const std::string uri : {"fifo.bin", "dir.bin"}) {
    test::GlbBuilder h;
    write(f.scene("a.gltf"), gltfWithBuffer(uri, h));
    expectOneLineNaming(loadFailure(f.scene("a.gltf")), f.scene("a.gltf"), "not a regular file");
  }
  write(f.scene("a.gltf"), gltfWithBuffer("/dev/zero", g));
  expectOneLineNaming(loadFailure(f.scene("a.gltf"), LoadOptions{.allowOutsideFiles = true}),
                      f.scene("a.gltf"), "is a device, not a regular file");
}

TEST(SceneFiles, ImageOutsideTheFolderOrAFifoIsRefused) {
  SceneFolder f;
  ImageRGB tex;
  tex.width = tex.height = 1;
  tex.pixels = {glm::vec3(0.5f)};
  writePng(f.root / "outside.png", tex);
  ASSERT_EQ(::mkfifo(f.scene("fifo.png").c_str(), 0600), 0);
  for (const std::string uri : {"../outside.png", "fifo.png"}) {
    test::GlbBuilder g;
    g.doc["images"] = json::array({{{"uri", uri}}});
    g.doc["textures"] = json::array({{{"source", 0}}});
    const int m = g.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
    g.addNode({{"mesh", g.addMesh(kTriangle, {}, m)}});
    g.writeGlb(f.scene("a.glb"));
    expectOneLineNaming(loadFailure(f.scene("a.glb")), f.scene("a.glb"),
                        uri == "fifo.png" ? "a FIFO" : "outside");
  }
}

TEST(SceneFiles, ReferencedFileLargerThanTheCapIsRefusedBeforeReading) {
  SceneFolder f;
  test::GlbBuilder g;
  write(f.scene("a.gltf"), gltfWithBuffer("data.bin", g));
  write(f.scene("data.bin"), g.bin + std::string(5000 - g.bin.size(), '\0'));
  const InputError e = loadFailure(f.scene("a.gltf"), LoadOptions{.maxFileBytes = 1000});
  expectOneLineNaming(e, f.scene("a.gltf"), "'data.bin': is 5000 bytes, more than the 1000 bytes");
}

TEST(SceneFiles, OneFileNamedManyTimesCountsAgainstTheCapEveryTime) {
  SceneFolder f;
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  json doc = g.doc;
  doc["buffers"] = json::array();
  for (int i = 0; i < 5; ++i) doc["buffers"].push_back({{"byteLength", 1000}, {"uri", "data.bin"}});
  write(f.scene("a.gltf"), doc.dump());
  write(f.scene("data.bin"), g.bin + std::string(1000 - g.bin.size(), '\0'));
  // 5 × 1000 bytes > 3000, though each read alone is well below the cap.
  expectOneLineNaming(loadFailure(f.scene("a.gltf"), LoadOptions{.maxFileBytes = 3000}), f.scene("a.gltf"),
                      "with the files read before it, more than the 3000 bytes a scene may refer to");
  EXPECT_EQ(loadScene(f.scene("a.gltf"), LoadOptions{.maxFileBytes = 5000}).scene.triangles.size(), 1u);
}

TEST(SceneFiles, SceneFileThatIsAFifoIsRefused) {
  SceneFolder f;
  for (const std::string name : {"fifo.glb", "fifo.obj"}) {
    ASSERT_EQ(::mkfifo(f.scene(name).c_str(), 0600), 0);
    expectOneLineNaming(loadFailure(f.scene(name)), f.scene(name), "a FIFO, not a regular file");
  }
}

TEST(SceneFiles, ObjMtllibOutsideTheFolderAFifoOrADeviceIsRefused) {
  SceneFolder f;
  write(f.root / "outside.mtl", "newmtl stolen\nKd 0.1 0.2 0.3\n");
  ASSERT_EQ(::mkfifo(f.scene("fifo.mtl").c_str(), 0600), 0);
  const std::string geometry = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl stolen\nf 1 2 3\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"../outside.mtl", "outside the scene's folder"},
      {"fifo.mtl", "a FIFO"},
      {"/dev/zero", "absolute path"}};
  for (const auto& [mtllib, problem] : cases) {
    write(f.scene("a.obj"), "mtllib " + mtllib + "\n" + geometry);
    expectOneLineNaming(loadFailure(f.scene("a.obj")), f.scene("a.obj"), problem);
  }
  write(f.scene("a.obj"), "mtllib /dev/zero\n" + geometry);
  expectOneLineNaming(loadFailure(f.scene("a.obj"), LoadOptions{.allowOutsideFiles = true}), f.scene("a.obj"),
                      "is a device");
}

TEST(SceneFiles, MissingMtllibIsStillOnlyAWarning) {
  SceneFolder f;
  write(f.scene("a.obj"), "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const LoadedScene s = loadScene(f.scene("a.obj"));
  EXPECT_EQ(s.scene.triangles.size(), 1u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("missing.mtl"), std::string::npos) << s.warnings[0];
}

TEST(SceneFiles, HugeDataUriAndNewlinesInNamesStayOneShortLine) {
  SceneFolder f;
  test::GlbBuilder g;
  g.addNode({{"mesh", g.addMesh(kTriangle)}});
  json doc = g.doc;
  // 15 KB of a data URI whose base64 is broken: the parser's message must not echo it.
  doc["buffers"] =
      json::array({{{"byteLength", g.bin.size()},
                    {"uri", "data:application/octet-stream;base64," + std::string(15000, '!')}}});
  write(f.scene("a.gltf"), doc.dump());
  const InputError e = loadFailure(f.scene("a.gltf"));
  EXPECT_LT(std::string(e.what()).size(), 600u) << e.what();

  test::GlbBuilder h;
  h.addNode({{"name", "portal:A\nB"}, {"mesh", h.addMesh(kTriangle)}});
  h.writeGlb(f.scene("b.glb"));
  const InputError n = loadFailure(f.scene("b.glb"));
  EXPECT_EQ(std::string(n.what()).find('\n'), std::string::npos) << n.what();
  EXPECT_NE(n.problem().find("portal:A\\nB"), std::string::npos) << n.what();
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// Issue 49, item 11: a reference is checked to lie inside the folder (symlinks resolved) before it is
// opened; opening may act by itself (a device, a FIFO), so a file outside is never opened at all. inotify
// sees every open of the file outside.
TEST(SceneFiles, SymlinkOutsideIsRefusedWithoutOpeningItsTarget) {
  SceneFolder f;
  test::GlbBuilder g;
  write(f.scene("a.gltf"), gltfWithBuffer("link.bin", g));
  write(f.root / "secret.bin", g.bin);
  fs::create_symlink(f.root / "secret.bin", f.scene("link.bin"));
  const int watch = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  ASSERT_GE(watch, 0);
  ASSERT_GE(::inotify_add_watch(watch, (f.root / "secret.bin").c_str(), IN_OPEN), 0);
  expectOneLineNaming(loadFailure(f.scene("a.gltf")), f.scene("a.gltf"), "outside the scene's folder");
  alignas(inotify_event) char events[4096];
  EXPECT_LE(::read(watch, events, sizeof events), 0) << "the file outside the folder was opened";
  ::close(watch);
}

// `mtllib .` names the scene's folder: a directory, not a file outside it.
TEST(SceneFiles, MtllibNamingTheFolderItselfIsADirectoryNotOutside) {
  SceneFolder f;
  write(f.scene("a.obj"), "mtllib .\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectOneLineNaming(loadFailure(f.scene("a.obj")), f.scene("a.obj"), "is a directory, not a regular file");
}

}  // namespace
}  // namespace cpgi
