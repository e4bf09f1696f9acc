#include "core/scene_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace fs = std::filesystem;

namespace cpgi::detail {
namespace {

// Closes the descriptor on every path out, exceptions included.
struct FileDescriptor {
  int fd = -1;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Opened without following the file's kind: O_NONBLOCK so that opening a FIFO returns at once (it is
// refused right after by fstat) instead of waiting for a writer forever.
int openForReading(const fs::path& path) {
  return ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
}

std::string kindOf(const struct stat& st) {
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

// Reads exactly `size` bytes (a file that shrinks meanwhile is a read error; growth is not read).
std::string readAll(int fd, uint64_t size, const std::string& where, const std::string& what) {
  std::string bytes(size, '\0');
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, bytes.data() + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(where, what + "read error: " + std::strerror(errno));
    if (n == 0) throw InputError(where, what + "the file shrank while it was read");
    done += size_t(n);
  }
  return bytes;
}

// Where the open descriptor really is, symlinks and `..` resolved by the kernel, so that no path
// swapped in between a check and the open can escape.
fs::path realPathOf(int fd) {
  std::error_code ec;
  const fs::path real = fs::read_symlink("/proc/self/fd/" + std::to_string(fd), ec);
  return ec ? fs::path() : real;
}

bool isInside(const fs::path& file, const fs::path& folder) {
  auto f = file.begin();
  for (auto d = folder.begin(); d != folder.end(); ++d, ++f) {
    if (d->empty()) continue;  // a trailing separator
    if (f == file.end() || *f != *d) return false;
  }
  return f != file.end();
}

std::string sizeText(uint64_t bytes) {
  return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string percentDecode(const std::string& uri) {
  auto hexValue = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hexValue(uri[i + 1]) >= 0 && hexValue(uri[i + 2]) >= 0) {
      out += static_cast<char>(hexValue(uri[i + 1]) * 16 + hexValue(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

ReferencePolicy referencePolicy(const std::string& sceneFile, const LoadOptions& options) {
  ReferencePolicy policy;
  policy.sceneFile = sceneFile;
  fs::path folder = fs::path(sceneFile).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  policy.folder = fs::canonical(folder, ec);
  if (ec) throw InputError(sceneFile, "cannot resolve the scene's folder: " + ec.message());
  policy.allowOutsideFiles = options.allowOutsideFiles;
  policy.maxFileBytes = options.maxFileBytes;
  return policy;
}

std::optional<std::string> readReferencedFile(ReferencePolicy& policy, const std::string& reference) {
  const std::string what = "referenced file '" + printable(reference) + "': ";
  const std::string hint = " (`outside files` reads it anyway)";
  if (reference.empty()) throw InputError(policy.sceneFile, "a referenced file name is empty");
  if (reference.find('\0') != std::string::npos)
    throw InputError(policy.sceneFile, what + "the name holds a NUL character");
  const fs::path relative(reference);
  if (relative.is_absolute() && !policy.allowOutsideFiles)
    throw InputError(policy.sceneFile, what + "is an absolute path, outside the scene's folder" + hint);
  // Where the name leads, symlinks and `..` resolved, is checked before anything is opened: opening
  // has effects of its own on some files (a device, a FIFO), and a file outside the folder is no business
  // of the scene's. The check after opening (realPathOf) still catches a path swapped in between.
  std::error_code ec;
  const fs::path resolved = fs::canonical(policy.folder / relative, ec);
  if (ec) {
    if (ec == std::errc::no_such_file_or_directory || ec == std::errc::not_a_directory) return std::nullopt;
    throw InputError(policy.sceneFile, what + "cannot resolve: " + ec.message());
  }
  if (!policy.allowOutsideFiles && resolved != policy.folder && !isInside(resolved, policy.folder))
    throw InputError(policy.sceneFile, what + "resolves outside the scene's folder" + hint);
  struct stat st {};
  if (::stat(resolved.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw InputError(policy.sceneFile, what + "is " + kindOf(st) + ", not a regular file");
  FileDescriptor file;
  file.fd = openForReading(resolved);
  if (file.fd < 0) {
    if (errno == ENOENT || errno == ENOTDIR) return std::nullopt;
    throw InputError(policy.sceneFile, what + "cannot open: " + std::strerror(errno));
  }
  if (!policy.allowOutsideFiles && !isInside(realPathOf(file.fd), policy.folder))
    throw InputError(policy.sceneFile, what + "resolves outside the scene's folder" + hint);
  if (::fstat(file.fd, &st) != 0)
    throw InputError(policy.sceneFile, what + "cannot stat: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw InputError(policy.sceneFile, what + "is " + kindOf(st) + ", not a regular file");
  if (uint64_t(st.st_size) > policy.maxFileBytes)
    throw InputError(policy.sceneFile, what + "is " + sizeText(st.st_size) + ", more than the " +
                                           sizeText(policy.maxFileBytes) + " a scene file may have");
  if (uint64_t(st.st_size) > policy.maxFileBytes - policy.bytesRead)
    throw InputError(policy.sceneFile, what + "with the files read before it, more than the " +
                                           sizeText(policy.maxFileBytes) + " a scene may refer to");
  policy.bytesRead += uint64_t(st.st_size);
  return readAll(file.fd, uint64_t(st.st_size), policy.sceneFile, what);
}

std::string readSceneFile(const std::string& path, uint64_t maxFileBytes) {
  // A device or FIFO is refused before it is opened (opening one may block or act).
  struct stat before {};
  if (::stat(path.c_str(), &before) == 0 && !S_ISREG(before.st_mode))
    throw InputError(path, S_ISDIR(before.st_mode) ? std::string("is a directory, not a scene file")
                                                   : "is " + kindOf(before) + ", not a regular file");
  FileDescriptor file;
  file.fd = openForReading(path);
  if (file.fd < 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw InputError(path, "no such file");
    throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw InputError(path, std::string("cannot stat: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw InputError(path, "is a directory, not a scene file");
  if (!S_ISREG(st.st_mode)) throw InputError(path, "is " + kindOf(st) + ", not a regular file");
  if (uint64_t(st.st_size) > maxFileBytes)
    throw InputError(path, "is " + sizeText(st.st_size) + ", more than the " + sizeText(maxFileBytes) +
                               " a scene file may have");
  return readAll(file.fd, uint64_t(st.st_size), path, "");
}

}  // namespace cpgi::detail
