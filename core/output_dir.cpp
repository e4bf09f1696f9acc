#include "core/output_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>  // renameat2
#include <cstring>
#include <fstream>
#include <set>
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

// The decimal PID that `name` holds from `at` up to the next '.' (or its end); 0 if there is none.
pid_t pidAt(const std::string& name, size_t at) {
  pid_t pid = 0;
  for (size_t i = at; i < name.size() && name[i] != '.'; ++i) {
    if (name[i] < '0' || name[i] > '9' || pid > 99999999) return 0;
    pid = pid * 10 + (name[i] - '0');
  }
  return pid;
}

// The PID in ".STEM.partial-PID.EXT", or 0 when `name` is not such a temporary.
pid_t partialOwner(const std::string& name) {
  const size_t at = name.rfind(".partial-");
  if (name.empty() || name[0] != '.' || at == std::string::npos) return 0;
  return pidAt(name, at + 9);
}

// Staging folders: ".cpgi-new-PID" inside the output folder, ".NAME.cpgi-new-PID" beside it.
const std::string kStagingInside = ".cpgi-new-";
std::string stagingBesidePrefix(const fs::path& real) {
  return "." + real.filename().string() + kStagingInside;
}

// The PID of a staging folder named `prefix`PID, or 0 when `name` is not one.
pid_t stagingOwner(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  const pid_t pid = pidAt(name, prefix.size());
  return std::to_string(pid) == name.substr(prefix.size()) ? pid : 0;
}

// The names the last committed run wrote, one a line, kept in the folder: a name matching a pattern
// ("view-*") is replaced or removed only when that run wrote it; a user's own view-holiday.png stays.
const std::string kManifest = ".cpgi-results";

std::set<std::string> readManifest(const fs::path& folder) {
  std::set<std::string> names;
  std::error_code ec;
  if (fs::file_size(folder / kManifest, ec) > (1u << 20) || ec) return names;
  std::ifstream in(folder / kManifest);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line.find('/') == std::string::npos) names.insert(line);
  return names;
}

bool isDead(pid_t pid) {
  return pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
}

// What runs that were killed left in and beside the folder: their process no longer exists. Called with
// the folder's lock held, so no live run of cpgi is writing here.
void removeLeftovers(const fs::path& real) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(real, ec)) {
    const std::string name = entry.path().filename().string();
    if (isDead(partialOwner(name)) || isDead(stagingOwner(name, kStagingInside))) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }
  const std::string beside = stagingBesidePrefix(real);
  for (const auto& entry : fs::directory_iterator(real.parent_path(), ec))
    if (isDead(stagingOwner(entry.path().filename().string(), beside))) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
}

// Opens `dir` and flock()s it, or throws. The lock ends with the process, however it ends, and leaves no
// lock file behind.
int lockFolder(const fs::path& dir, const fs::path& where) {
  for (int attempt = 0;; ++attempt) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      if (fd >= 0) ::close(fd);
      throw InputError(where.string(),
                       error == EWOULDBLOCK
                           ? "another cpgi run is writing into this output folder"
                           : std::string("cannot lock output folder: ") + std::strerror(error));
    }
    // A run that finished between our open() and flock() swapped a new folder in: lock that one.
    struct stat locked {
    }, now{};
    if (::fstat(fd, &locked) == 0 && ::stat(dir.c_str(), &now) == 0 && locked.st_dev == now.st_dev &&
        locked.st_ino == now.st_ino)
      return fd;
    ::close(fd);
    if (attempt == 100) throw InputError(where.string(), "output folder keeps being replaced by other runs");
  }
}

// Whether the process's working directory is `real` or inside it: swapping it would leave a shell
// sitting there in a deleted folder.
bool holdsWorkingDirectory(const fs::path& real) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return true;
  auto c = cwd.begin();
  for (auto r = real.begin(); r != real.end(); ++r, ++c)
    if (c == cwd.end() || *c != *r) return false;
  return true;
}

}  // namespace

OutputDir::OutputDir(fs::path dir, std::vector<std::string> resultNames)
    : dir_(std::move(dir)), resultNames_(std::move(resultNames)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_))
    throw InputError(dir_.string(),
                     "cannot create output folder" + (ec ? ": " + ec.message() : std::string()));
  real_ = fs::canonical(dir_, ec);
  if (ec) throw InputError(dir_.string(), "cannot resolve output folder: " + ec.message());
  // Writable now, before any work: otherwise a bake would find out only after its solve.
  const fs::path probe = temporaryName(real_, "write-test");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw InputError(dir_.string(), std::string("cannot write into output folder: ") + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  // One run per folder: two bakes into one folder would mix their files.
  lock_ = lockFolder(real_, dir_);
  removeLeftovers(real_);

  // Beside the folder when a swap can keep its promises: same file system, the user's own folder (a
  // swapped-in folder would belong to us), not a working directory, a parent we may write in.
  struct stat self {
  }, parent{};
  if (!real_.filename().empty() && !holdsWorkingDirectory(real_) && ::fstat(lock_, &self) == 0 &&
      ::stat(real_.parent_path().c_str(), &parent) == 0 && self.st_dev == parent.st_dev &&
      self.st_uid == ::geteuid()) {
    staging_ = real_.parent_path() / (stagingBesidePrefix(real_) + std::to_string(::getpid()));
    fs::remove_all(staging_, ec);  // left by an earlier process of the same PID
    besideTarget_ =
        ::mkdir(staging_.c_str(), 0700) == 0 && ::chmod(staging_.c_str(), self.st_mode & 07777) == 0;
  }
  if (!besideTarget_) {
    if (!staging_.empty()) fs::remove_all(staging_, ec);
    staging_ = real_ / (kStagingInside + std::to_string(::getpid()));
    fs::remove_all(staging_, ec);
    if (::mkdir(staging_.c_str(), 0700) != 0)
      throw InputError(dir_.string(),
                       std::string("cannot write into output folder: ") + std::strerror(errno));
  }
  stagingLock_ = ::open(staging_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (stagingLock_ >= 0) ::flock(stagingLock_, LOCK_EX | LOCK_NB);
}

OutputDir::~OutputDir() {
  // Before commit() the staging folder holds the unfinished results; after a swap, the earlier set.
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  if (stagingLock_ >= 0) ::close(stagingLock_);
  ::close(lock_);
}

fs::path OutputDir::file(const std::string& name) {
  staged_.push_back(name);
  return staging_ / name;
}

fs::path OutputDir::staged(const std::string& name) const {
  for (const std::string& s : staged_)
    if (s == name) return staging_ / name;
  throw std::logic_error("OutputDir: " + name + " was not staged");
}

bool OutputDir::isResultName(const std::string& name) const {
  if (name == kManifest) return true;
  for (const std::string& r : resultNames_) {
    if (r.empty()) continue;
    if (r.back() != '*' && name == r) return true;
    // A pattern names a file of the earlier set only if that run wrote it (its manifest says so).
    if (r.back() == '*' && name.compare(0, r.size() - 1, r, 0, r.size() - 1) == 0 && earlierSet_.count(name))
      return true;
  }
  return false;
}

void OutputDir::step(const char* name) const {
  if (faultHook) faultHook(name);
}

void OutputDir::commit() {
  earlierSet_ = readManifest(real_);
  std::string manifest;
  std::set<std::string> listed;
  for (const std::string& name : staged_) {
    std::error_code ec;
    if (listed.insert(name).second && fs::exists(staging_ / name, ec)) manifest += name + "\n";
  }
  writeFileAtomically(staging_ / kManifest, manifest);
  staged_.push_back(kManifest);
  step("staged");
  if (!(besideTarget_ && swapIn())) moveIn();
  committed_ = true;
}

bool OutputDir::swapIn() {
  // The user's files go into the new folder as hard links (the same files, not copies), so they are in
  // the folder at every instant. A folder of theirs cannot be: then the files are moved in one by one.
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(real_, ec)) {
    const std::string name = entry.path().filename().string();
    if (isResultName(name) || fs::exists(fs::symlink_status(staging_ / name))) continue;
    if (entry.symlink_status().type() == fs::file_type::directory) return false;
    if (::link(entry.path().c_str(), (staging_ / name).c_str()) != 0) return false;  // link(2) keeps symlinks
  }
  if (ec) return false;
  step("carried");
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, real_.c_str(), RENAME_EXCHANGE) != 0) return false;
  step("swapped");
  // staging_ now holds the earlier set. Anything the user added to the folder during the swap moves over;
  // the rest goes.
  for (const auto& entry : fs::directory_iterator(staging_, ec)) {
    const std::string name = entry.path().filename().string();
    if (isResultName(name) || fs::exists(fs::symlink_status(real_ / name))) continue;
    std::error_code ignored;
    fs::rename(entry.path(), real_ / name, ignored);
  }
  fs::remove_all(staging_, ec);
  staging_.clear();
  return true;
}

void OutputDir::moveIn() {
  std::set<std::string> written;
  for (const std::string& name : staged_) {
    std::error_code ec;
    if (written.count(name) || !fs::exists(staging_ / name, ec)) continue;
    fs::rename(staging_ / name, real_ / name, ec);
    if (ec) throw SystemError((dir_ / name).string() + ": cannot move result into place: " + ec.message());
    written.insert(name);
    step("moved");
  }
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(real_, ec)) {
    const std::string name = entry.path().filename().string();
    if (isResultName(name) && !written.count(name)) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
      step("removed");
    }
  }
  fs::remove_all(staging_, ec);
  staging_.clear();
}

namespace {

// The name the user will know `path` by: a file in a staging folder is named as it will be once
// committed (DIR/view-a.png, not DIR/.cpgi-new-123/view-a.png or ../.DIR.cpgi-new-123/view-a.png).
fs::path committedName(const fs::path& path) {
  const fs::path folder = path.parent_path();
  const std::string name = folder.filename().string();
  const size_t at = name.rfind(kStagingInside);
  if (at == std::string::npos || stagingOwner(name.substr(at), kStagingInside) != ::getpid()) return path;
  if (at == 0) return folder.parent_path() / path.filename();  // DIR/.cpgi-new-PID
  if (name[0] == '.')
    return folder.parent_path() / name.substr(1, at - 1) / path.filename();  // .DIR.cpgi-new-PID
  return path;
}

// write(2) until every byte is out; the error number of the failure, or 0.
int writeAll(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return EIO;
    done += size_t(n);
  }
  return 0;
}

}  // namespace

void writeFileAtomically(const fs::path& path, const std::string& bytes) {
  const fs::path temp = temporaryName(path.parent_path(), path.filename().string());
  // Every step is checked, close() too: a full disk (or a quota, or NFS) may tell only there, and a file
  // cut short must never be renamed into place as if it were whole.
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  int error = fd < 0 ? errno : writeAll(fd, bytes);
  if (fd >= 0 && ::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    ::unlink(temp.c_str());
    throw SystemError(committedName(path).string() + ": cannot write: " + std::strerror(error));
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    ::unlink(temp.c_str());
    throw SystemError(committedName(path).string() + ": cannot move result into place: " + ec.message());
  }
}

}  // namespace cpgi
