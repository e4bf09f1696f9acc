// Outputs that appear whole or not at all. Every file a command writes goes to a hidden temporary name
// in the target folder; commit() renames them all at the end. If the command fails first, the
// destructor removes the temporaries, so no half-written lightmap ever looks complete and no earlier
// result in the folder is replaced by a broken one.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cpgi {

class OutputDir {
 public:
  /// Creates `dir` (and parents) if needed, checks that it is writable and locks it for this run;
  /// removes temporaries that killed runs left there. Throws InputError(DIR, ...) with the reason when
  /// it cannot create, write or lock it (another run holds it).
  explicit OutputDir(std::filesystem::path dir);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  /// The temporary path to write `name` to; the file becomes `dir/name` on commit().
  std::filesystem::path file(const std::string& name);
  /// The temporary path of `name`, staged earlier by file() (to read back a file written before commit).
  /// Throws std::logic_error when `name` was not staged.
  std::filesystem::path staged(const std::string& name) const;
  /// Renames every staged file into place. Files not written are skipped.
  void commit();
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // temp -> final
  bool committed_ = false;
  int lock_ = -1;  // the folder, open and flock()ed while this object lives
};

/// Writes `bytes` to `path` through a temporary file and a rename (one file, atomically).
void writeFileAtomically(const std::filesystem::path& path, const std::string& bytes);

}  // namespace cpgi
