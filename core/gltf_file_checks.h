// What a glTF file is checked for before tinygltf parses it, and the files it may read beside it.
// tinygltf trusts what it is given: a truncated container, JSON nested deep enough to overflow its
// recursion, an image view past its buffer, a URI that leaves the scene's folder. Each is caught here and
// named in one InputError, so that the parser only ever sees input it handles safely.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/scene_files.h"

namespace cpgi::detail {

/// A URI of a file beside the scene, as the scene spells it (not yet decoded).
struct FileUri {
  std::string uri;
  bool isBuffer = false;  ///< a buffer's (required), else an image's (needed only if a material uses it)
};

/// The .glb container (12-byte header, JSON chunk, optional BIN chunk) checked up front, so that a
/// truncated file gets a message saying so. Returns the JSON chunk text.
std::string checkGlbContainer(const std::string& path, const std::string& bytes);

/// The glTF JSON (`what`: "document" or "chunk") checked for depth, syntax and image views inside their
/// buffers. Returns the URIs of the files the scene refers to.
std::vector<FileUri> checkGltfJson(const std::string& path, const std::string& text, const char* what);

/// tinygltf's file callbacks, so that every buffer and image it loads goes through the scene's reference
/// policy (scene_files.h). tinygltf joins the scene's folder and its decoding of the URI, asks whether
/// that exists, then reads it; it also retries relative to the working directory, which is never allowed.
/// The file read is the one the URI names as a glTF URI is decoded (RFC 3986: '+' is itself).
class ReferencedFiles {
 public:
  ReferencedFiles(ReferencePolicy policy, const std::vector<FileUri>& uris);
  const std::string& folder() const { return folder_; }
  /// Whether an image's file `uri` was looked for and is not there.
  bool missing(const std::string& uri) const { return missing_.count(percentDecode(uri)) > 0; }

  // The four callbacks, `self` this object.
  static bool exists(const std::string& path, void* self);
  static std::string expand(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion
  static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self);
  static bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*);

 private:
  struct Name {
    std::string uri, file;  ///< as the scene spells it; percent-decoded (RFC 3986)
    std::string otherUri;   ///< another URI tinygltf decodes alike that names another file
    bool isBuffer = false;
  };

  std::string fileNamed(const std::string& decoded) const;

  ReferencePolicy policy_;
  std::string folder_, prefix_;
  std::map<std::string, Name> names_;        // by tinygltf's decoding of the URI
  std::set<std::string> missing_;            // files looked for and not found, percent-decoded
  std::map<std::string, std::string> read_;  // checked and read by exists(), handed over by read()
};

}  // namespace cpgi::detail
