// `cpgi view DIR`: pictures of an existing bake without baking again. With the bake's own settings it
// draws the very pictures the bake drew (the atlas comes back from preview.glb's TEXCOORD_1); it picks one
// camera by name or places one by hand; a folder that is not a bake fails with one line.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/suite_setup.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;
using test::cpgi;
using test::quote;

class ViewCommand : public ::testing::Test {
 protected:
  void SetUp() override { setup_.require(); }
  static inline test::SuiteSetup setup_;
  static void SetUpTestSuite() {
    setup_.run([] {
      dir_ = new test::TempDir;
      const std::string scene = *dir_ / "seed1.glb";
      ASSERT_EQ(cpgi(dir_->path(), "generate seed1 -o " + quote(scene)).status, 0);
      BakeSettings s;  // in process: --texels-per-quad 4 --unshot 0.3
      s.input.scene = scene;
      s.output.folder = bake();
      s.atlas.densityAuto = false;
      s.atlas.params.texelsPerQuad = 4;
      s.solver.params.unshotFraction = 0.3;
      test::bakeHere(s);
    });
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string bake() { return *dir_ / "bake"; }
  static test::TempDir* dir_;
};
test::TempDir* ViewCommand::dir_ = nullptr;

TEST_F(ViewCommand, DrawsTheBakesOwnPicturesAgain) {
  const std::string out = *dir_ / "again";
  const test::CommandRun r = cpgi(dir_->path(), "view " + quote(bake()) + " -o " + quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* view : {"A", "B", "C"}) {
    SCOPED_TRACE(view);
    EXPECT_NE(r.out.find("view-" + std::string(view) + ".png"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(out + "/view-" + view + ".png"));
    const ImageRGB baked = readExr(bake() + "/view-" + view + ".exr");
    const ImageRGB again = readExr(out + "/view-" + view + ".exr");
    ASSERT_EQ(again.width, baked.width);
    ASSERT_EQ(again.height, baked.height);
    float worst = 0.0f, brightest = 0.0f;
    for (size_t i = 0; i < baked.pixels.size(); ++i) {
      worst = std::max(worst, glm::length(again.pixels[i] - baked.pixels[i]));
      brightest = std::max(brightest, glm::length(baked.pixels[i]));
    }
    EXPECT_GT(brightest, 0.0f);
    EXPECT_LE(worst, 1e-5f * brightest);
  }
}

TEST_F(ViewCommand, OneCameraByNameOrByHandAtTheSizeAskedFor) {
  const std::string out = *dir_ / "one";
  test::CommandRun r =
      cpgi(dir_->path(), "view " + quote(bake()) + " --camera B --view-size 200x100 -q -o " + quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/view-B.png"));
  EXPECT_FALSE(fs::exists(out + "/view-A.png"));
  const ImageRGB b = readExr(out + "/view-B.exr");
  EXPECT_EQ(b.width, 200);
  EXPECT_EQ(b.height, 100);

  // By hand: from the middle of room A (seed1: x in [0, 4]) towards its far wall. Without -o the pictures
  // go to DIR/views, beside the bake's own.
  r = cpgi(dir_->path(), "view " + quote(bake()) + " --eye 2,1.6,2 --look 0,1,2 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  const ImageRGB eye = readExr(bake() + "/views/view-eye.exr");
  size_t lit = 0;
  for (const glm::vec3& p : eye.pixels) lit += p.x > 0.0f;
  EXPECT_GT(lit, eye.pixels.size() * 9 / 10);
  EXPECT_TRUE(fs::exists(bake() + "/view-A.png"));  // the bake's own pictures stay
}

TEST_F(ViewCommand, BadRequestsFailWithOneLine) {
  const std::string empty = *dir_ / "empty";
  fs::create_directories(empty);
  const struct {
    std::string args, expected;
  } cases[] = {
      {"view " + quote(bake()) + " --camera nope", "no camera named nope"},
      {"view " + quote(empty), "not the output folder of cpgi bake"},
      {"view " + quote(*dir_ / "missing"), "no such folder"},
      {"view " + quote(bake()) + " --eye 1,2,3", "--look"},
      {"view " + quote(bake()) + " --eye 1,1,1 --look 1,1,1", "must differ"},
      {"view " + quote(bake()) + " --camera A --eye 1,2,3 --look 0,0,0", "excludes"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const test::CommandRun r = cpgi(dir_->path(), c.args);
    EXPECT_EQ(r.status, 1);
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
  }
  // A decomposition folder has a report but no lightmap.
  const std::string cells = *dir_ / "cells";
  ASSERT_EQ(
      cpgi(dir_->path(), "decompose " + quote(*dir_ / "seed1.glb") + " -o " + quote(cells) + " --voxel 0.1")
          .status,
      0);
  const test::CommandRun r = cpgi(dir_->path(), "view " + quote(cells));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("not the output folder of cpgi bake"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(cells + "/views"));
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// Issue 49, item 8: on a full disk small view files were committed empty with exit status 0 (the write
// error came only at close, unchecked). A file size limit of 0 makes every write fail as a full disk
// does; the output goes through a pipe, out of the limit's reach.
TEST_F(ViewCommand, FullDiskFailsInOneLineAndCommitsNothing) {
  const std::string out = *dir_ / "full";
  const std::string view =
      quote(CPGI_BINARY) + " view " + quote(bake()) + " -o " + quote(out) + " --view-size 32x24";
  const test::CommandRun r = test::runCaptured(
      dir_->path(),
      "bash -o pipefail -c " + quote("(ulimit -f 0; trap '' XFSZ; exec " + view + " 2>&1) | cat"), "full-");
  EXPECT_EQ(r.status, 1) << r.out;
  size_t errors = 0;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("cpgi: ", 0) == 0) {
      ++errors;
      EXPECT_EQ(line.rfind("cpgi: " + out + "/view-", 0), 0u) << line;
      EXPECT_NE(line.find(": cannot write: File too large"), std::string::npos) << line;
    }
  EXPECT_EQ(errors, 1u) << r.out;
  if (fs::exists(out)) {
    for (const auto& e : fs::directory_iterator(out)) {
      EXPECT_NE(e.path().filename().string().rfind("view-", 0), 0u) << "committed: " << e.path();
    }
  }
}

}  // namespace
}  // namespace cpgi
