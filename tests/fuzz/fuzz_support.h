// Shared by the libFuzzer targets: the loaders read files, so each input is written to a private folder
// (in /dev/shm when there is one) and loaded from there. Only InputError is an acceptable outcome; any
// other exception escapes and aborts, so the fuzzer reports it like a crash ("internal error" in the CLI).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/scene_io.h"

namespace cpgi::fuzz {

inline const std::filesystem::path& folder() {
  static const std::filesystem::path path = [] {
    const std::filesystem::path base =
        access("/dev/shm", W_OK) == 0 ? "/dev/shm" : std::filesystem::temp_directory_path();
    std::string pattern = (base / "cpgi-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    return std::filesystem::path(pattern);
  }();
  static const bool removeAtExit = [] {
    return std::atexit([] {
             std::error_code ec;
             std::filesystem::remove_all(folder(), ec);
           }) == 0;
  }();
  (void)removeAtExit;
  return path;
}

inline std::string write(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = (folder() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
  return path;
}

/// Loads `path` with and without --strict; an InputError is the expected answer to a bad file.
inline void load(const std::string& path) {
  for (bool repair : {false, true}) {
    try {
      loadScene(path, LoadOptions{.strict = !repair, .maxFileBytes = 1 << 20});
    } catch (const InputError&) {
    }
  }
}

}  // namespace cpgi::fuzz
