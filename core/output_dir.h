// Outputs that appear whole, as a set, or not at all. A command writes every file into a fresh hidden
// staging folder beside the target folder; commit() then swaps that folder in with one atomic rename
// (renameat2 RENAME_EXCHANGE), so a run killed at any instant leaves either the earlier result set or the
// new one, never a mix, and names of the earlier set the new run did not write (views of other cameras)
// go with the swap. The user's own files in the folder are carried over as hard links before the swap.
// Where a swap cannot keep its promises (the folder is a working directory or a mount point, holds a
// folder of the user's, belongs to another user, its parent is read-only, or the file system has no
// exchange), the staging folder sits inside the target and commit() moves the files in one by one.
// If the command fails first, the destructor removes the staging folder: no half-written lightmap ever
// looks complete and no earlier result is replaced by a broken one.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace cpgi {

class OutputDir {
 public:
  /// Creates `dir` (and parents) if needed, checks that it is writable and locks it for this run;
  /// removes what killed runs left in and beside it. Throws InputError(DIR, ...) with the reason when it
  /// cannot create, write or lock it (another run holds it).
  /// @param resultNames  names of files an earlier run of the same command may have left in `dir`
  ///   ("view-*" ends in a star: every name with that prefix that an earlier run wrote, as the hidden
  ///   manifest `.cpgi-results` it left says). Those this run does not write are removed on commit();
  ///   files of any other name, or matching a pattern but not written by cpgi, are the user's and kept.
  explicit OutputDir(std::filesystem::path dir, std::vector<std::string> resultNames = {});
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  /// The path to write `name` to (inside the staging folder); it becomes `dir/name` on commit().
  std::filesystem::path file(const std::string& name);
  /// The staged path of `name`, given earlier by file() (to read back a file written before commit).
  /// Throws std::logic_error when `name` was not staged.
  std::filesystem::path staged(const std::string& name) const;
  /// Puts the staged files in place of the earlier result set. Files not written are skipped.
  void commit();
  const std::filesystem::path& dir() const { return dir_; }

  /// Tests only: called between the steps of commit() with the step's name, to kill a run at each one.
  static inline void (*faultHook)(const char* step) = nullptr;

 private:
  bool isResultName(const std::string& name) const;
  bool swapIn();  // the atomic commit; false when it cannot be done here (then moveIn())
  void moveIn();  // file by file
  void step(const char* name) const;

  std::filesystem::path dir_;      // as the user gave it, for messages
  std::filesystem::path real_;     // the folder itself, symbolic links resolved
  std::filesystem::path staging_;  // where file() puts the results
  bool besideTarget_ = false;      // staging_ is a sibling of real_ (a swap is possible)
  std::vector<std::string> resultNames_;
  std::vector<std::string> staged_;   // names given to file()
  std::set<std::string> earlierSet_;  // what the committed run before this one wrote (its manifest)
  bool committed_ = false;
  int lock_ = -1;         // the folder, open and flock()ed while this object lives
  int stagingLock_ = -1;  // the staging folder likewise: after a swap it is the folder
};

/// Writes `bytes` to `path` through a temporary file and a rename (one file, atomically).
void writeFileAtomically(const std::filesystem::path& path, const std::string& bytes);

}  // namespace cpgi
