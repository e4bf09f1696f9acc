#include "core/output_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "core/error.h"

namespace fs = std::filesystem;

namespace cpgi {
namespace {
// ".STEM.partial-PID.EXT": hidden, never mistaken for a finished result, and with the final extension
// kept, because writers choose the format by it (writeGltf: .glb or .gltf).
fs::path temporaryName(const fs::path& dir, const std::string& name) {
  const fs::path file(name);
  // (An ostringstream rather than string operator+: GCC 12 warns falsely on the latter, PR 105329.)
  std::ostringstream temp;
  temp << '.' << file.stem().string() << ".partial-" << ::getpid() << file.extension().string();
  return dir / temp.str();
}

// The PID in ".STEM.partial-PID.EXT", or 0 when `name` is not such a temporary.
pid_t partialOwner(const std::string& name) {
  const size_t at = name.rfind(".partial-");
  if (name.empty() || name[0] != '.' || at == std::string::npos) return 0;
  pid_t pid = 0;
  for (size_t i = at + 9; i < name.size() && name[i] != '.'; ++i) {
    if (name[i] < '0' || name[i] > '9' || pid > 99999999) return 0;
    pid = pid * 10 + (name[i] - '0');
  }
  return pid;
}

// Temporaries left by runs that were killed: their process no longer exists. Called with the folder's
// lock held, so no live run of cpgi is writing here.
void removeStaleTemporaries(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const pid_t owner = partialOwner(entry.path().filename().string());
    if (owner > 0 && owner != ::getpid() && ::kill(owner, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

}  // namespace

OutputDir::OutputDir(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_))
    throw InputError(dir_.string(),
                     "cannot create output folder" + (ec ? ": " + ec.message() : std::string()));
  // Writable now, before any work: otherwise a bake would find out only after its solve.
  const fs::path probe = temporaryName(dir_, "write-test");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw InputError(dir_.string(), std::string("cannot write into output folder: ") + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  // One run per folder: two bakes into one folder would mix their files. The lock is on the folder
  // itself (no lock file left behind) and ends with the process, however it ends.
  lock_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_ < 0 || ::flock(lock_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    if (lock_ >= 0) ::close(lock_);
    throw InputError(dir_.string(), error == EWOULDBLOCK
                                        ? "another cpgi run is writing into this output folder"
                                        : std::string("cannot lock output folder: ") + std::strerror(error));
  }
  removeStaleTemporaries(dir_);
}

OutputDir::~OutputDir() {
  if (!committed_) {
    std::error_code ec;
    for (const auto& [temp, final] : staged_) fs::remove(temp, ec);
  }
  ::close(lock_);
}

fs::path OutputDir::file(const std::string& name) {
  fs::path final = dir_ / name;
  fs::path temp = temporaryName(dir_, name);
  staged_.emplace_back(temp, final);
  return temp;
}

fs::path OutputDir::staged(const std::string& name) const {
  for (const auto& [temp, final] : staged_)
    if (final == dir_ / name) return temp;
  throw std::logic_error("OutputDir: " + name + " was not staged");
}

void OutputDir::commit() {
  for (const auto& [temp, final] : staged_) {
    std::error_code ec;
    if (!fs::exists(temp, ec)) continue;
    fs::rename(temp, final, ec);
    if (ec) throw SystemError(final.string() + ": cannot move result into place: " + ec.message());
  }
  committed_ = true;
}

void writeFileAtomically(const fs::path& path, const std::string& bytes) {
  const fs::path temp = temporaryName(path.parent_path(), path.filename().string());
  {
    std::ofstream out(temp, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::error_code ec;
      fs::remove(temp, ec);
      throw SystemError(path.string() + ": cannot write");
    }
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) throw SystemError(path.string() + ": cannot move result into place: " + ec.message());
}

}  // namespace cpgi
