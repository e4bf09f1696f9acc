// OutputDir: results appear on commit(), temporaries vanish on failure, the user's files survive.
#include <sys/resource.h>

#include <csignal>
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/output_dir.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(OutputDir, CommitRenamesStagedFiles) {
  test::TempDir dir;
  const fs::path out = dir.path() / "nested" / "out";
  {
    OutputDir o(out);
    const fs::path a = o.file("a.txt");
    const fs::path skipped = o.file("never-written.txt");
    // In a hidden staging folder until commit().
    EXPECT_NE(a.parent_path(), out);
    EXPECT_EQ(a.parent_path().filename().string().front(), '.');
    std::ofstream(a) << "alpha";
    EXPECT_FALSE(fs::exists(out / "a.txt"));
    o.commit();
    (void)skipped;
  }
  EXPECT_EQ(slurp(out / "a.txt"), "alpha");
  EXPECT_FALSE(fs::exists(out / "never-written.txt"));
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(out))
    files += e.is_regular_file() && e.path().filename() != ".cpgi-results";  // the list of what it wrote
  EXPECT_EQ(files, 1u);
}

// Writers choose the format by the extension (writeGltf: .glb or .gltf), so staged names keep it.
TEST(OutputDir, StagedFilesKeepTheirExtensionSoWritersPickTheFormat) {
  test::TempDir dir;
  OutputDir o(dir.path());
  const fs::path staged = o.file("cells.glb");
  EXPECT_EQ(staged.extension(), ".glb");
  EXPECT_NE(staged, dir.path() / "cells.glb");
  std::ofstream(staged) << "x";
  o.commit();
  EXPECT_TRUE(fs::exists(dir.path() / "cells.glb"));
}

TEST(OutputDir, FailureRemovesTemporariesAndKeepsTheUsersFiles) {
  test::TempDir dir;
  std::ofstream(dir.path() / "lightmap.exr") << "the user's earlier result";
  try {
    OutputDir o(dir.path());
    std::ofstream(o.file("lightmap.exr")) << "half written";
    throw std::runtime_error("the solver failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(slurp(dir.path() / "lightmap.exr"), "the user's earlier result");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) entries += 1, (void)e;
  EXPECT_EQ(entries, 1u);
}

TEST(OutputDir, UncreatableFolderIsAnInputError) {
  test::TempDir dir;
  std::ofstream(dir.path() / "file") << "x";
  EXPECT_THROW(OutputDir(dir.path() / "file" / "sub"), InputError);
}

TEST(OutputDir, WriteFileAtomicallyReplacesWholeAndLeavesNoTemporary) {
  test::TempDir dir;
  const fs::path p = dir.path() / "report.json";
  std::ofstream(p) << "old";
  writeFileAtomically(p, "new contents");
  EXPECT_EQ(slurp(p), "new contents");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) entries += 1, (void)e;
  EXPECT_EQ(entries, 1u);
  EXPECT_THROW(writeFileAtomically(dir.path() / "no" / "such" / "folder.json", "x"), SystemError);
}

// A full disk (issue 49, item 8), made by a file size limit: write(2) fails with EFBIG once a file would
// pass it, as with ENOSPC, while the bytes before the limit were written. A short file is never renamed
// into place and the message names the file as the user knows it, not a staging path.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    previous_ = std::signal(SIGXFSZ, SIG_IGN);  // else the process dies of the signal
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_);
  }

 private:
  rlimit saved_{};
  void (*previous_)(int) = SIG_DFL;
};

TEST(OutputDir, WriteErrorOfAFullDiskIsAnErrorAndCommitsNothing) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  {
    OutputDir first(out, {"report.json"});
    writeFileAtomically(first.file("report.json"), "earlier");
    first.commit();
  }
  std::string message;
  {
    OutputDir second(out, {"report.json"});
    const fs::path staged = second.file("report.json");
    FileSizeLimit full(4);
    try {
      writeFileAtomically(staged, "a report longer than the disk has room for");
      ADD_FAILURE() << "a write past the file size limit succeeded";
    } catch (const SystemError& e) {
      message = e.what();
    }
    EXPECT_FALSE(fs::exists(staged)) << "a cut-short file was put in place";
  }  // not committed: the run failed
  EXPECT_EQ(message, (out / "report.json").string() + ": cannot write: " + std::strerror(EFBIG));
  EXPECT_EQ(slurp(out / "report.json"), "earlier");
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_TRUE(e.path().filename() == "report.json" || e.path().filename() == ".cpgi-results") << e.path();
}

}  // namespace
}  // namespace cpgi
