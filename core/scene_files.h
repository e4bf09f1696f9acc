// Reading the files a scene consists of: the scene file itself and the files it refers to (glTF buffers
// and images, OBJ mtllib). A scene is untrusted input, so by default a reference resolves inside the
// scene's folder only (after percent-decoding, through symlinks), names a regular file (never a FIFO,
// a device or a directory) and is size-checked before a byte is read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "core/scene_io.h"

namespace cpgi::detail {

/// How the references of one scene file are read.
struct ReferencePolicy {
  std::string sceneFile;           ///< named in every message
  std::filesystem::path folder;    ///< the scene's folder, canonical (absolute, no symlinks)
  bool allowOutsideFiles = false;  ///< LoadOptions::allowOutsideFiles
  uint64_t maxFileBytes = 0;       ///< LoadOptions::maxFileBytes, also the cap of all references together
  uint64_t bytesRead = 0;          ///< by readReferencedFile so far (one file may be named a thousand times)
};
ReferencePolicy referencePolicy(const std::string& sceneFile, const LoadOptions& options);

/// The bytes of the file `reference` (as written in the scene, already percent-decoded) names, relative
/// to the scene's folder; nullopt when there is no such file. Throws InputError(scene file, ...) naming
/// the reference when it is absolute or resolves outside the folder (unless allowed), is not a regular
/// file, or is larger than what is left of the cap.
std::optional<std::string> readReferencedFile(ReferencePolicy& policy, const std::string& reference);

/// The scene file itself: a regular file of at most `maxFileBytes`; InputError otherwise.
std::string readSceneFile(const std::string& path, uint64_t maxFileBytes);

/// A relative URI (a glTF buffer's or image's) as the file name it stands for, by RFC 3986: each %XX
/// of two hex digits is the byte XX; every other character, '+' included, is itself (HTML form
/// encoding's '+' for a space does not apply to a URI), and so is a '%' not followed by two hex digits,
/// as Blender's importer reads it.
std::string percentDecode(const std::string& uri);

}  // namespace cpgi::detail
