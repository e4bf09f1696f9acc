// OutputDir's guards (issue 15, defect 7): the folder is checked writable before any work, with the
// system's reason; one run per folder at a time; temporaries of killed runs are cleaned up.
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/output_dir.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;

std::string problemOf(const fs::path& dir) {
  try {
    OutputDir o(dir);
  } catch (const InputError& e) {
    return e.problem();
  }
  return "no error";
}

TEST(OutputDirGuards, UnwritableFolderIsRefusedUpFrontWithTheReason) {
  // /proc/self is a folder even root cannot create files in; as another user a 0500 folder does too.
  EXPECT_EQ(problemOf("/proc/self").rfind("cannot write into output folder: ", 0), 0u)
      << problemOf("/proc/self");
  if (::geteuid() != 0) {
    test::TempDir dir;
    fs::create_directory(dir / "ro");
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_EQ(problemOf(dir / "ro"), "cannot write into output folder: Permission denied");
  }
}

TEST(OutputDirGuards, SecondRunIntoTheSameFolderIsRefusedUntilTheFirstEnds) {
  test::TempDir dir;
  {
    OutputDir first(dir.path());
    EXPECT_EQ(problemOf(dir.path()), "another cpgi run is writing into this output folder");
  }
  EXPECT_EQ(problemOf(dir.path()), "no error");
}

TEST(OutputDirGuards, TemporariesOfDeadRunsAreRemovedOthersKept) {
  test::TempDir dir;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // now a PID of no process
  const std::string dead = ".lightmap.partial-" + std::to_string(child) + ".exr";
  const std::string alive = ".lightmap.partial-" + std::to_string(::getppid()) + ".exr";
  for (const std::string& name : {dead, alive, std::string("lightmap.exr"), std::string(".partial-notes")})
    std::ofstream(dir / name) << "x";
  OutputDir o(dir.path());
  EXPECT_FALSE(fs::exists(dir / dead));
  EXPECT_TRUE(fs::exists(dir / alive));
  EXPECT_TRUE(fs::exists(dir / "lightmap.exr"));
  EXPECT_TRUE(fs::exists(dir / ".partial-notes"));
}

}  // namespace
}  // namespace cpgi
