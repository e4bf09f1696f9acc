// End to end: a scene whose buffer lies outside its folder is refused by every loading command with one
// line naming the scene and the reference, and read with --allow-outside-files (issue 15, defect 4).
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/glb_builder.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using test::CommandRun;
using test::cpgi;
using test::quote;

TEST(OutsideFiles, RefusedByDefaultReadWithTheFlag) {
  test::TempDir dir;
  std::filesystem::create_directory(dir / "scene");
  test::GlbBuilder g;
  // A closed box would be needed to bake; info and decompose's loading step are enough to show the rule.
  g.addNode({{"name", "t"}, {"mesh", g.addMesh({0, 0, 0, 1, 0, 0, 0, 1, 0})}});
  nlohmann::json doc = g.doc;
  doc["buffers"] = nlohmann::json::array({{{"byteLength", g.bin.size()}, {"uri", "..%2fsecret.bin"}}});
  const std::string scene = dir / "scene/a.gltf";
  test::GlbBuilder::writeBytes(scene, doc.dump());
  test::GlbBuilder::writeBytes(dir / "secret.bin", g.bin);

  for (const std::string command : {"info", "decompose", "bake", "reference"}) {
    const std::string output = command == "info" ? "" : " -o " + quote(dir / ("out-" + command));
    const CommandRun r = cpgi(dir, command + " " + quote(scene) + output);
    EXPECT_EQ(r.status, 1) << command << ": " << r.err;
    ASSERT_EQ(r.errLines().size(), 1u) << command << ": " << r.err;
    EXPECT_EQ(
        r.errLines()[0].rfind("cpgi: " + scene + ": referenced file '../secret.bin': resolves outside", 0),
        0u)
        << r.errLines()[0];
    EXPECT_NE(r.errLines()[0].find("(--allow-outside-files reads it anyway)"), std::string::npos)
        << r.errLines()[0];
  }
  const CommandRun allowed = cpgi(dir, "info " + quote(scene) + " --allow-outside-files");
  EXPECT_EQ(allowed.status, 0) << allowed.err;
}

}  // namespace
}  // namespace cpgi
