// OutputDir's results as a set (issue 15, defect 7): a run killed at any instant of its commit leaves
// either the earlier result set or the new one in the folder, never a mix; names of the earlier set the
// new run does not write (views of other cameras) go with the swap; the user's own files stay.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <functional>
#include <map>

#include <gtest/gtest.h>

#include "core/output_dir.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;

const std::vector<std::string> kResultNames = {"lightmap.exr", "report.json", "view-*"};

// Every entry of `dir` by name, with the contents of files ("<dir>" for folders); the hidden list of what
// the last run wrote (.cpgi-results) left out.
Files listing(const fs::path& dir) {
  Files files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == ".cpgi-results") continue;
    if (e.is_directory()) {
      files[name] = "<dir>";
      continue;
    }
    std::ifstream in(e.path(), std::ios::binary);
    files[name] = std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  return files;
}

void writeRun(const fs::path& dir, const Files& files) {
  OutputDir out(dir, kResultNames);
  for (const auto& [name, text] : files) std::ofstream(out.file(name)) << text;
  out.commit();
}

int killAt = 0;  // the commit step at which the child run kills itself
int stepsSeen = 0;
void killAtStep(const char*) {
  if (++stepsSeen == killAt) ::raise(SIGKILL);
}

// Runs `files` into `dir` in a child process that SIGKILLs itself at commit step `step`; true when it
// was killed, false when it got through.
bool runKilledAt(const fs::path& dir, const Files& files, int step) {
  const pid_t child = ::fork();
  if (child == 0) {
    killAt = step;
    OutputDir::faultHook = killAtStep;
    try {
      writeRun(dir, files);
    } catch (...) {
      ::_exit(2);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 0)) << status;
  return WIFSIGNALED(status);
}

Files withUsersFile(Files files) {
  files["notes.txt"] = "the user's";
  return files;
}

// Kills the second run at every step of its commit in turn, each time over a fresh copy of the first.
void checkKillAtEveryStep(const std::function<fs::path(const fs::path&)>& makeOutput) {
  const Files first = {{"lightmap.exr", "1"}, {"report.json", "1"}, {"view-a.png", "1"}, {"view-b.png", "1"}};
  const Files second = {
      {"lightmap.exr", "2"}, {"report.json", "2"}, {"view-b.png", "2"}, {"view-c.png", "2"}};
  int killed = 0;
  for (int step = 1; step < 100; ++step) {
    test::TempDir root;
    const fs::path out = makeOutput(root.path());
    fs::create_directories(out);
    std::ofstream(out / "notes.txt") << "the user's";
    writeRun(out, first);
    const bool wasKilled = runKilledAt(out, second, step);
    Files seen = listing(out);
    std::erase_if(seen, [](const auto& e) { return e.first[0] == '.'; });
    EXPECT_TRUE(seen == withUsersFile(first) || seen == withUsersFile(second))
        << "killed at commit step " << step << ": a mix of the two runs";
    if (!wasKilled) {
      EXPECT_EQ(seen, withUsersFile(second)) << "a finished run leaves exactly its own set";
      break;
    }
    ++killed;
    // The next run into the folder cleans up what the killed one left, inside and beside it.
    { OutputDir next(out, kResultNames); }
    for (const fs::path& folder : {out, out.parent_path()})
      for (const auto& e : fs::directory_iterator(folder))
        EXPECT_EQ(e.path().filename().string().find(".cpgi-new-"), std::string::npos) << e.path();
    for (const auto& e : fs::directory_iterator(out))
      EXPECT_TRUE(e.path().filename().string()[0] != '.' || e.path().filename() == ".cpgi-results")
          << e.path();
  }
  EXPECT_GE(killed, 2) << "the commit has too few steps to have been tested";
}

TEST(OutputDirSet, KillAtAnyCommitStepLeavesOneWholeSet) {
  checkKillAtEveryStep([](const fs::path& root) { return root / "out"; });
}

// A folder of the user's inside the output folder cannot be carried into a swapped-in folder without a
// moment where it is missing: cpgi then moves its files one by one, but the names of the earlier set still
// go and the user's folder stays.
TEST(OutputDirSet, UsersSubfolderIsKeptAndEarlierViewsGo) {
  test::TempDir root;
  const fs::path out = root.path() / "out";
  fs::create_directories(out / "sub");
  std::ofstream(out / "sub" / "x") << "kept";
  writeRun(out, {{"lightmap.exr", "1"}, {"view-a.png", "1"}});
  writeRun(out, {{"lightmap.exr", "2"}, {"view-b.png", "2"}});
  EXPECT_EQ(listing(out), (Files{{"lightmap.exr", "2"}, {"view-b.png", "2"}, {"sub", "<dir>"}}));
  EXPECT_EQ(listing(out / "sub"), (Files{{"x", "kept"}}));
}

// -o given as a symbolic link: the link stays and its target receives the results.
TEST(OutputDirSet, SymlinkedOutputFolderStaysALink) {
  test::TempDir root;
  fs::create_directories(root.path() / "real");
  fs::create_directory_symlink("real", root.path() / "link");
  writeRun(root.path() / "link", {{"lightmap.exr", "1"}});
  writeRun(root.path() / "link", {{"lightmap.exr", "2"}});
  EXPECT_TRUE(fs::is_symlink(root.path() / "link"));
  EXPECT_EQ(listing(root.path() / "real"), (Files{{"lightmap.exr", "2"}}));
}

// A shell sitting in the output folder must not be left in a deleted one: the folder itself stays.
TEST(OutputDirSet, FolderThatIsTheWorkingDirectoryIsKept) {
  test::TempDir root;
  const fs::path out = root.path() / "out";
  fs::create_directories(out);
  struct stat before {};
  ::stat(out.c_str(), &before);
  const fs::path previous = fs::current_path();
  fs::current_path(out);
  writeRun(".", {{"lightmap.exr", "1"}});
  fs::current_path(previous);
  struct stat after {};
  ::stat(out.c_str(), &after);
  EXPECT_EQ(before.st_ino, after.st_ino);
  EXPECT_EQ(listing(out), (Files{{"lightmap.exr", "1"}}));
}

// Issue 49, item 10: a name that matches a pattern of results ("view-*") but that no run of cpgi wrote is
// the user's, and stays through every later run, whether the commit swaps the folder or moves file by
// file (a subfolder of the user's forces the latter); the views an earlier run wrote still go.
TEST(OutputDirSet, UsersOwnFileMatchingAResultPatternStays) {
  for (const bool withSubfolder : {false, true}) {
    test::TempDir root;
    const fs::path out = root.path() / "out";
    fs::create_directories(out);
    if (withSubfolder) fs::create_directories(out / "sub");
    std::ofstream(out / "view-holiday.png") << "mine";
    writeRun(out, {{"lightmap.exr", "1"}, {"view-a.png", "1"}});
    writeRun(out, {{"lightmap.exr", "2"}, {"view-b.png", "2"}});
    Files expected = {{"lightmap.exr", "2"}, {"view-b.png", "2"}, {"view-holiday.png", "mine"}};
    if (withSubfolder) expected["sub"] = "<dir>";
    EXPECT_EQ(listing(out), expected) << (withSubfolder ? "moved file by file" : "swapped");
  }
}

}  // namespace
}  // namespace cpgi
