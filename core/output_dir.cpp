#include "core/output_dir.h"

#include <unistd.h>
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
}  // namespace

OutputDir::OutputDir(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) throw InputError(dir_.string(), "cannot create output folder");
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& [temp, final] : staged_) fs::remove(temp, ec);
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
