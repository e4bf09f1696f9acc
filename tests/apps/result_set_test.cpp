// End to end (issue 15, defect 7): an output folder holds one run's result set. A sampled reference
// over a full one leaves none of the full one's files (views, baked.glb, report.html) beside its own, and
// a run SIGKILLed at any instant leaves the earlier set whole or the new one, never a mix.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <thread>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;

// The folder's visible files with their bytes (hidden staging names left out).
Files listing(const fs::path& dir) {
  Files files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string()[0] != '.') files[e.path().filename().string()] = test::slurp(e.path());
  return files;
}

std::vector<std::string> names(const Files& files) {
  std::vector<std::string> n;
  for (const auto& [name, bytes] : files) n.push_back(name);
  return n;
}

class ResultSet : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = test::quote(dir_ / "seed1.glb");
    test::cpgiOrThrow(dir_, "generate seed1 -o " + scene_);
  }
  // A full reference (views, baked.glb, report.html) and the user's notes in `out`.
  void fullReference(const fs::path& out) {
    test::cpgiOrThrow(dir_, "reference " + scene_ + " -o " + test::quote(out) + kAtlas + " --spp 2 -q");
    std::ofstream(out / "notes.txt") << "the user's";
  }
  std::vector<std::string> sampledArgs(const fs::path& out) const {
    return {CPGI_BINARY, "reference", dir_ / "seed1.glb", "-o", out.string(), "--texels-per-quad", "4",
            "--spp",     "2",         "--texels",         "50", "-q"};
  }
  static constexpr const char* kAtlas = " --texels-per-quad 4";
  test::TempDir dir_;
  std::string scene_;
};

bool isSampledSet(const Files& files) {
  if (names(files) != std::vector<std::string>{"lightmap.exr", "notes.txt", "report.json"}) return false;
  return nlohmann::json::parse(files.at("report.json")).contains("texels_traced");
}

TEST_F(ResultSet, SampledReferenceOverAFullOneLeavesOnlyItsOwnFiles) {
  const fs::path out = dir_.path() / "out";
  fullReference(out);
  ASSERT_TRUE(listing(out).count("baked.glb"));
  ASSERT_TRUE(listing(out).count("report.html"));
  const test::CommandRun r = test::cpgi(
      dir_, "reference " + scene_ + " -o " + test::quote(out) + kAtlas + " --spp 2 -q --texels 50");
  ASSERT_EQ(r.status, 0) << r.err;
  const Files after = listing(out);
  EXPECT_TRUE(isSampledSet(after)) << ::testing::PrintToString(names(after));
  EXPECT_EQ(after.at("notes.txt"), "the user's");
  for (const auto& e : fs::directory_iterator(dir_.path()))
    EXPECT_EQ(e.path().filename().string().find(".cpgi-new-"), std::string::npos) << e.path();
}

// The sampled run is killed after a growing delay, each time over a fresh copy of the full set: whatever
// the instant, the folder holds the full set byte for byte or the whole sampled one.
TEST_F(ResultSet, RunKilledAtAnyInstantLeavesOneWholeSet) {
  const fs::path full = dir_.path() / "full";
  fullReference(full);
  const Files before = listing(full);
  // How long a whole run takes here, to spread the kills over it.
  const auto start = std::chrono::steady_clock::now();
  {
    const fs::path timed = dir_.path() / "timed";
    fs::copy(full, timed);
    const test::CommandRun r = test::cpgi(
        dir_, "reference " + scene_ + " -o " + test::quote(timed) + kAtlas + " --spp 2 -q --texels 50");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  int old = 0, fresh = 0;
  constexpr int kKills = 12;
  for (int k = 0; k <= kKills; ++k) {
    const fs::path out = dir_.path() / ("kill" + std::to_string(k));
    fs::copy(full, out);
    std::vector<std::string> args = sampledArgs(out);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t child = ::fork();
    if (child == 0) {
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    // The last delays reach past the run's measured time, where the swap happens.
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds * 1.1 * k / kKills));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    const Files after = listing(out);
    if (after == before) {
      ++old;
    } else {
      EXPECT_TRUE(isSampledSet(after)) << "killed after " << seconds * 1.1 * k / kKills
                                       << " s: a mix: " << ::testing::PrintToString(names(after));
      ++fresh;
    }
    // The next run into the folder finds it usable and cleans what the killed one left beside it.
    const test::CommandRun next = test::cpgi(
        dir_, "reference " + scene_ + " -o " + test::quote(out) + kAtlas + " --spp 2 -q --texels 50");
    EXPECT_EQ(next.status, 0) << next.err;
    EXPECT_TRUE(isSampledSet(listing(out)));
  }
  for (const auto& e : fs::directory_iterator(dir_.path()))
    EXPECT_EQ(e.path().filename().string().find(".cpgi-new-"), std::string::npos) << e.path();
  EXPECT_GT(old, 0);
  RecordProperty("kills_old_set", old);
  RecordProperty("kills_new_set", fresh);
}

}  // namespace
}  // namespace cpgi
