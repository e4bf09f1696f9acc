// What a newcomer meets first: `cpgi COMMAND --help` grouped by topic and no wider than 100 columns, and a
// mistyped command or option answered with the nearest valid name (issue 50).
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// Display width: UTF-8 continuation bytes take no column.
size_t columns(const std::string& line) {
  return size_t(std::count_if(line.begin(), line.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

TEST(Help, EveryCommandsHelpFitsOneHundredColumns) {
  test::TempDir dir;
  for (const char* command : {"", "generate", "info", "bake", "reference", "compare-light", "decompose",
                              "compare-cells", "view", "cell-job"}) {
    const test::CommandRun r = test::cpgi(dir, std::string(command) + " --help");
    ASSERT_EQ(r.status, 0) << command << ": " << r.err;
    for (const std::string& line : lines(r.out))
      EXPECT_LE(columns(line), 100u) << "cpgi " << command << " --help: " << line;
  }
}

TEST(Help, BakeListsItsOptionsByTopicInOrder) {
  test::TempDir dir;
  const test::CommandRun r = test::cpgi(dir, "bake --help");
  ASSERT_EQ(r.status, 0) << r.err;
  size_t previous = 0;
  for (const char* group : {"Input:", "Atlas:", "Solver:", "Cells:", "Sky:", "Output:", "Limits:"}) {
    const size_t at = r.out.find("\n" + std::string(group) + "\n");
    ASSERT_NE(at, std::string::npos) << group << "\n" << r.out;
    EXPECT_GT(at, previous) << group << " out of order";
    previous = at;
  }
  // Each option under its topic: the section from its heading to the next one holds it.
  auto section = [&](const std::string& group) {
    const size_t start = r.out.find("\n" + group + ":\n");
    return r.out.substr(start, r.out.find("\n\n", start + 1) - start);
  };
  EXPECT_NE(section("Atlas").find("--density"), std::string::npos);
  EXPECT_NE(section("Solver").find("--unshot"), std::string::npos);
  EXPECT_NE(section("Cells").find("--portals"), std::string::npos);
  EXPECT_NE(section("Cells").find("--voxel"), std::string::npos);
  EXPECT_NE(section("Sky").find("--sun"), std::string::npos);
  EXPECT_NE(section("Input").find("--scale"), std::string::npos);
  EXPECT_NE(section("Output").find("--view-size"), std::string::npos);
  EXPECT_NE(section("Limits").find("--time-limit"), std::string::npos);
  EXPECT_NE(section("Limits").find("--max-memory"), std::string::npos);
  EXPECT_NE(r.out.find("Examples:"), std::string::npos);
}

TEST(Help, MistypedOptionNamesTheNearest) {
  test::TempDir dir;
  const test::CommandRun r = test::cpgi(dir, "bake scene.glb -o out --densty 5");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find("bake: --densty is not an option; did you mean --density?"), std::string::npos)
      << r.err;
  const test::CommandRun far = test::cpgi(dir, "decompose scene.glb -o out --zzzzzz 5");
  EXPECT_EQ(far.status, 1);
  EXPECT_NE(far.err.find("--zzzzzz is not an option"), std::string::npos) << far.err;
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
  // A negative number is a value, not a mistyped option: CLI11's own message stays.
  const test::CommandRun value = test::cpgi(dir, "bake scene.glb -o out --lamp-rays -4");
  EXPECT_EQ(value.status, 1);
  EXPECT_EQ(value.err.find("not an option"), std::string::npos) << value.err;
}

TEST(Help, MistypedCommandNamesTheNearest) {
  test::TempDir dir;
  const test::CommandRun r = test::cpgi(dir, "genrate seed1 -o s.glb");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find("genrate is not a command; did you mean generate?"), std::string::npos) << r.err;
  const test::CommandRun none = test::cpgi(dir, "frobnicate");
  EXPECT_EQ(none.status, 1);
  EXPECT_NE(none.err.find("the commands: "), std::string::npos) << none.err;
}

}  // namespace
}  // namespace cpgi
