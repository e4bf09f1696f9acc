// End to end: `cpgi info` on broken scenes exits 1 with exactly one line on stderr that names the file
// and the problem; degenerate input is dropped with one warning (exit 0) unless --strict.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/support/glb_builder.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

using test::CommandRun;
using test::cpgi;
using test::quote;

// Asserts the contract for a bad file: exit 1, one line "cpgi: FILE: ...PROBLEM...", nothing on stdout.
void expectOneLineError(const test::TempDir& dir, const std::string& file, const std::string& problem,
                        const std::string& extraArgs = "") {
  const CommandRun r = cpgi(dir, "info " + quote(file) + extraArgs);
  EXPECT_EQ(r.status, 1) << file << "\n" << r.err;
  const std::vector<std::string> lines = r.errLines();
  ASSERT_EQ(lines.size(), 1u) << r.err;
  EXPECT_EQ(lines[0].rfind("cpgi: " + file + ": ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(problem), std::string::npos) << "expected '" << problem << "' in: " << lines[0];
  EXPECT_TRUE(r.out.empty()) << r.out;
}

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

test::GlbBuilder oneTriangle() {
  test::GlbBuilder g;
  g.addNode({{"name", "t"}, {"mesh", g.addMesh(kTriangle)}});
  return g;
}

// Two unit floors as cells A and B and a portal mesh between them.
test::GlbBuilder twoCells(const std::string& portalName, float bulge) {
  test::GlbBuilder g;
  g.addNode(
      {{"name", "cell:A"}, {"mesh", g.addMesh({0, 0, 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0})}});
  g.addNode(
      {{"name", "cell:B"}, {"mesh", g.addMesh({1, 0, 0, 1, 0, 1, 2, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0, 0})}});
  g.addNode({{"name", portalName},
             {"mesh", g.addMesh({1, 0, 0, 1, 1, 0, 1 + bulge, 1, 1, 1, 0, 1}, {0, 1, 2, 0, 2, 3})}});
  return g;
}

TEST(BadInput, MissingFile) {
  test::TempDir dir;
  expectOneLineError(dir, dir / "nowhere.glb", "no such file");
}

TEST(BadInput, DirectoryInsteadOfAFile) {
  test::TempDir dir;
  std::filesystem::create_directory(dir / "folder.glb");
  expectOneLineError(dir, dir / "folder.glb", "is a directory");
}

TEST(BadInput, TruncatedGlb) {
  test::TempDir dir;
  const std::string whole = oneTriangle().glb();
  for (size_t keep : {size_t(0), size_t(7), size_t(30), whole.size() - 5}) {
    test::GlbBuilder::writeBytes(dir / "cut.glb", whole.substr(0, keep));
    expectOneLineError(dir, dir / "cut.glb", "truncated");
  }
}

TEST(BadInput, InvalidJsonChunk) {
  test::TempDir dir;
  test::GlbBuilder::writeBytes(dir / "bad.glb",
                               oneTriangle().glbWithJson("{\"asset\": {\"version\": \"2.0\"},"));
  expectOneLineError(dir, dir / "bad.glb", "invalid JSON");
  std::ofstream(dir / "bad.gltf") << "{ not json";
  expectOneLineError(dir, dir / "bad.gltf", "invalid JSON");
}

TEST(BadInput, NotGltfAtAll) {
  test::TempDir dir;
  std::ofstream(dir / "noise.glb") << std::string(64, '\x7f');
  expectOneLineError(dir, dir / "noise.glb", "not a binary glTF");
  std::ofstream(dir / "mesh.ply") << "ply\n";
  expectOneLineError(dir, dir / "mesh.ply", "unknown scene format");
}

TEST(BadInput, NanAndInfPositions) {
  test::TempDir dir;
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    test::GlbBuilder g;
    g.addNode({{"name", "broken"}, {"mesh", g.addMesh({0, 0, 0, 1, bad, 0, 0, 1, 0})}});
    g.writeGlb(dir / "nan.glb");
    expectOneLineError(dir, dir / "nan.glb", "node 'broken': a vertex position is not finite");
  }
}

TEST(BadInput, ZeroAreaTrianglesAreDroppedWithOneWarningAndRefusedWithStrict) {
  test::TempDir dir;
  test::GlbBuilder g;
  g.addNode(
      {{"name", "sliver"}, {"mesh", g.addMesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 1, 2, 2, 2})}});
  g.writeGlb(dir / "zero.glb");
  const std::string dropped =
      "warning: " + (dir / "zero.glb") +
      ": dropped 1 zero-area triangle (first in node 'sliver'); --strict refuses them\n";
  for (const char* flags : {"", " --repair"}) {  // --repair: the default, kept for old scripts
    const CommandRun r = cpgi(dir, "info " + quote(dir / "zero.glb") + flags);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, dropped);
    EXPECT_NE(r.out.find("triangles      1 "), std::string::npos) << r.out;
  }
  expectOneLineError(dir, dir / "zero.glb",
                     "1 zero-area triangle (first in node 'sliver'); without --strict they are dropped",
                     " --strict");
  const CommandRun both = cpgi(dir, "info " + quote(dir / "zero.glb") + " --strict --repair");
  EXPECT_EQ(both.status, 1);
  EXPECT_EQ(both.errLines().size(), 1u) << both.err;
}

TEST(BadInput, DuplicateTrianglesAreDroppedWithOneWarningAndRefusedWithStrict) {
  test::TempDir dir;
  test::GlbBuilder g;
  const int mesh = g.addMesh(kTriangle);
  g.addNode({{"name", "once"}, {"mesh", mesh}});
  g.addNode({{"name", "twice"}, {"mesh", mesh}});
  g.writeGlb(dir / "dup.glb");
  expectOneLineError(dir, dir / "dup.glb", "1 duplicate triangle (first in node 'twice')", " --strict");
  const CommandRun r = cpgi(dir, "info " + quote(dir / "dup.glb") + " --json");
  EXPECT_EQ(r.status, 0) << r.err;
  const json info = json::parse(r.out);
  EXPECT_EQ(info["triangles"], 1);
  EXPECT_EQ(info["warnings"],
            json::array({"dropped 1 duplicate triangle (first in node 'twice'); --strict refuses them"}));
}

// slivers.glb in `dir`: one zero-area triangle in node 'sliver' beside a real one; its path, quoted.
std::string writeSliverScene(const test::TempDir& dir) {
  test::GlbBuilder sliver;
  sliver.addNode(
      {{"name", "sliver"}, {"mesh", sliver.addMesh({0, 0, 0, 1, 1, 1, 2, 2, 2, 0, 0, 0, 0, 0, 1, 1, 0, 0})}});
  sliver.writeGlb(dir / "slivers.glb");
  return quote(dir / "slivers.glb");
}

// Every command that loads a scene loads it the same way: the slivers of a real export do not stop
// decompose or bake, and --strict stops each of them.
TEST(BadInput, EveryLoadingCommandDropsDegenerateTrianglesAndTakesStrict) {
  test::TempDir dir;
  const std::string scene = writeSliverScene(dir);
  const std::vector<std::string> commands = {
      "info " + scene, "decompose " + scene + " -o " + quote(dir / "d"),
      "bake " + scene + " -o " + quote(dir / "b") + " -q --allow-dark --texels-per-quad 2",
      "reference " + scene + " -o " + quote(dir / "r") + " -q --allow-dark --texels-per-quad 2 --spp 2",
      "compare-cells " + scene + " auto auto"};
  for (const std::string& command : commands) {
    const CommandRun strict = cpgi(dir, command + " --strict");
    EXPECT_EQ(strict.status, 1) << command;
    ASSERT_EQ(strict.errLines().size(), 1u) << command << "\n" << strict.err;
    EXPECT_NE(strict.err.find("1 zero-area triangle (first in node 'sliver')"), std::string::npos)
        << command << "\n"
        << strict.err;
  }
  const CommandRun info = cpgi(dir, commands[0]);
  EXPECT_EQ(info.status, 0) << info.err;
}

// A loader's warning reads as a warning in every command that loads a scene, in one form,
// "warning: FILE: TEXT", never in the form of an error's line ("cpgi: FILE: PROBLEM"): the run goes on.
TEST(BadInput, EveryLoadingCommandPrintsTheLoadersWarningAsAWarning) {
  test::TempDir dir;
  const std::string scene = writeSliverScene(dir);
  const std::string warning =
      "warning: " + (dir / "slivers.glb") +
      ": dropped 1 zero-area triangle (first in node 'sliver'); --strict refuses them";
  for (const std::string& command :
       {"info " + scene, "decompose " + scene + " -o " + quote(dir / "d"),
        "bake " + scene + " -o " + quote(dir / "b") + " --allow-dark --texels-per-quad 2",
        "reference " + scene + " -o " + quote(dir / "r") + " -q --allow-dark --texels-per-quad 2 --spp 2"}) {
    const CommandRun r = cpgi(dir, command);
    EXPECT_EQ(r.status, 0) << command << "\n" << r.err;
    const std::vector<std::string> lines = r.errLines();
    EXPECT_EQ(std::count(lines.begin(), lines.end(), warning), 1) << command << "\n" << r.err;
    for (const std::string& line : lines) EXPECT_NE(line.rfind("cpgi: ", 0), 0u) << command << ": " << line;
  }
}

TEST(BadInput, BadPunctualLightsNameTheFileAndTheLight) {
  test::TempDir dir;
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"type", "point"}, {"name", "bulb"}, {"intensity", -5}},
       "light 'bulb': intensity -5 is negative or not finite"},
      {{{"type", "spot"}, {"name", "cone"}, {"spot", {{"innerConeAngle", 1.0}, {"outerConeAngle", 0.5}}}},
       "light 'cone': spot cone angles must satisfy"},
      {{{"type", "point"}, {"name", "sun-sized"}, {"intensity", 1e30}}, "more than 1e+20 W"}};
  for (const auto& [light, problem] : cases) {
    test::GlbBuilder g = oneTriangle();
    g.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({light});
    g.addNode({{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    g.writeGlb(dir / "light.glb");
    expectOneLineError(dir, dir / "light.glb", problem);
  }
}

TEST(BadInput, LinesPrimitive) {
  test::TempDir dir;
  test::GlbBuilder g;
  const int mesh = g.addMesh(kTriangle, {}, -1, 1);
  g.doc["meshes"][mesh]["name"] = "wire";
  g.addNode({{"mesh", mesh}});
  g.writeGlb(dir / "lines.glb");
  expectOneLineError(dir, dir / "lines.glb",
                     "mesh 'wire' primitive 0: primitive mode LINES is not supported");
}

TEST(BadInput, PortalNotPlanar) {
  test::TempDir dir;
  twoCells("portal:A:B", 0.3f).writeGlb(dir / "bent.glb");
  expectOneLineError(dir, dir / "bent.glb", "portal:A:B: not planar");
}

TEST(BadInput, PortalNamingAnUnknownCell) {
  test::TempDir dir;
  twoCells("portal:A:Kitchen", 0.0f).writeGlb(dir / "unknown.glb");
  expectOneLineError(dir, dir / "unknown.glb", "portal:A:Kitchen: names a cell that does not exist");
}

TEST(BadInput, EmptyScene) {
  test::TempDir dir;
  test::GlbBuilder g;
  g.addNode({{"name", "nothing here"}});
  g.writeGlb(dir / "empty.glb");
  expectOneLineError(dir, dir / "empty.glb", "the scene has no triangles");
}

TEST(BadInput, AccessorPastTheEndAndUnsupportedExtension) {
  test::TempDir dir;
  test::GlbBuilder g = oneTriangle();
  g.doc["accessors"][0]["byteOffset"] = 4;
  g.writeGlb(dir / "range.glb");
  expectOneLineError(dir, dir / "range.glb", "runs past the end");
  test::GlbBuilder d = oneTriangle();
  d.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  d.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  d.writeGlb(dir / "draco.glb");
  expectOneLineError(dir, dir / "draco.glb", "requires the glTF extension KHR_draco_mesh_compression");
}

// Every single-byte corruption of a small valid file, and every truncation, ends in exit 0 or a one-line
// error, never a crash (a cheap in-suite fuzz; the sanitizer build makes it strict).
TEST(BadInput, CorruptedBytesNeverCrash) {
  test::TempDir dir;
  test::GlbBuilder g = twoCells("portal:A:B", 0.0f);
  const std::string whole = g.glb();
  size_t runs = 0;
  for (size_t at = 0; at < whole.size(); at += 7) {
    std::string bytes = whole;
    bytes[at] = static_cast<char>(bytes[at] ^ 0x5a);
    test::GlbBuilder::writeBytes(dir / "fuzz.glb", bytes);
    const CommandRun r = cpgi(dir, "info " + quote(dir / "fuzz.glb"));
    ++runs;
    ASSERT_TRUE(r.status == 0 || r.status == 1) << "byte " << at << " status " << r.status << "\n" << r.err;
    if (r.status == 1) {
      ASSERT_EQ(r.errLines().size(), 1u) << "byte " << at << "\n" << r.err;
      EXPECT_EQ(r.err.find("internal error"), std::string::npos) << "byte " << at << ": " << r.err;
    }
  }
  EXPECT_GT(runs, 20u);
}

}  // namespace
}  // namespace cpgi
