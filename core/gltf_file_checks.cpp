#include "core/gltf_file_checks.h"

#include <climits>
#include <cstdint>
#include <cstring>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace cpgi::detail {
namespace {

uint32_t readU32(const std::string& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;  // glb is little-endian, as is every machine cpgi builds on
}

}  // namespace

std::string checkGlbContainer(const std::string& path, const std::string& b) {
  if (b.size() < 12)
    throw InputError(path,
                     "truncated .glb: " + std::to_string(b.size()) + " bytes, the header alone needs 12");
  if (b.compare(0, 4, "glTF") != 0) throw InputError(path, "not a binary glTF file (no 'glTF' magic)");
  if (readU32(b, 4) != 2)
    throw InputError(path, "glTF container version " + std::to_string(readU32(b, 4)) + ", expected 2");
  const uint64_t declared = readU32(b, 8);
  if (declared > b.size())
    throw InputError(path, "truncated .glb: the header says " + std::to_string(declared) +
                               " bytes, the file has " + std::to_string(b.size()));
  if (declared < 20) throw InputError(path, "invalid .glb: no JSON chunk");
  const uint64_t jsonLength = readU32(b, 12);
  if (readU32(b, 16) != 0x4E4F534Au) throw InputError(path, "invalid .glb: the first chunk is not JSON");
  if (20 + jsonLength > declared)
    throw InputError(path, "truncated .glb: the JSON chunk runs past the end of the file");
  uint64_t at = 20 + ((jsonLength + 3) & ~uint64_t(3));
  if (at + 8 <= declared) {
    const uint64_t binLength = readU32(b, at);
    if (readU32(b, at + 4) == 0x004E4942u && at + 8 + binLength > declared)
      throw InputError(path, "truncated .glb: the BIN chunk runs past the end of the file");
  }
  return b.substr(20, jsonLength);
}

namespace {

// glTF itself nests about 6 levels deep (asset → meshes → primitive → attributes …); extras and
// extensions may add some. tinygltf converts the JSON recursively, so a file of 16,000 nested arrays
// would overflow the stack there: the depth is counted first, in one pass without recursion.
constexpr int kMaxJsonDepth = 64;

void checkJsonDepth(const std::string& path, const std::string& text, const char* what) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;  // skips the escaped character, which may be a quote
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(path, std::string("invalid JSON ") + what + ": nested deeper than " +
                                   std::to_string(kMaxJsonDepth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// tinygltf hands an image's bufferView to the image loader without checking that it lies inside its
// buffer (a heap over-read). A buffer's data has exactly its declared byteLength once tinygltf accepts
// it, so the declared numbers are checked here, before tinygltf runs.
void checkImageViews(const std::string& path, const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("images") || !doc["images"].is_array()) return;
  auto unsignedAt = [](const nlohmann::json& object, const char* key,
                       uint64_t fallback) -> std::optional<uint64_t> {
    if (!object.is_object() || !object.contains(key)) return fallback;
    const nlohmann::json& v = object[key];
    if (v.is_number_unsigned()) return v.get<uint64_t>();
    if (v.is_number_integer() && v.get<int64_t>() >= 0) return uint64_t(v.get<int64_t>());
    return std::nullopt;
  };
  const nlohmann::json none;
  auto element = [&](const char* array, uint64_t i) -> const nlohmann::json& {
    if (!doc.contains(array) || !doc[array].is_array() || i >= doc[array].size()) return none;
    return doc[array][i];
  };
  for (size_t i = 0; i < doc["images"].size(); ++i) {
    const nlohmann::json& image = doc["images"][i];
    if (!image.is_object() || !image.contains("bufferView")) continue;
    const std::string what = "image " + std::to_string(i) + ": ";
    const auto viewIndex = unsignedAt(image, "bufferView", 0);
    if (!viewIndex) throw InputError(path, what + "bufferView is not an index");
    const nlohmann::json& view = element("bufferViews", *viewIndex);
    const auto bufferIndex = unsignedAt(view, "buffer", uint64_t(-1));
    const auto offset = unsignedAt(view, "byteOffset", 0),
               length = unsignedAt(view, "byteLength", uint64_t(-1));
    if (!view.is_object() || !bufferIndex || !offset || !length)
      throw InputError(path, what + "its bufferView does not exist or is malformed");
    const auto bufferLength = unsignedAt(element("buffers", *bufferIndex), "byteLength", uint64_t(-1));
    if (!bufferLength || *bufferLength == uint64_t(-1) || *length == uint64_t(-1) ||
        *offset > *bufferLength || *length > *bufferLength - *offset || *length > uint64_t(INT32_MAX))
      throw InputError(
          path, what + "bufferView " + std::to_string(*viewIndex) + " runs past the end of its buffer");
  }
}

// The URIs of the files the buffers and images name (data: URIs hold their bytes and name none).
std::vector<FileUri> fileUris(const nlohmann::json& doc) {
  std::vector<FileUri> uris;
  if (!doc.is_object()) return uris;
  for (const char* array : {"buffers", "images"}) {
    if (!doc.contains(array) || !doc[array].is_array()) continue;
    for (const nlohmann::json& element : doc[array])
      if (element.is_object() && element.contains("uri") && element["uri"].is_string()) {
        const std::string& uri = element["uri"].get_ref<const std::string&>();
        if (uri.rfind("data:", 0) != 0) uris.push_back({uri, std::string(array) == "buffers"});
      }
  }
  return uris;
}

// tinygltf (2.7, Debian 12's) decodes a URI as HTML form data before it asks for the file: '+' becomes a
// space and a '%' not followed by two hex digits takes 0 for each, so `a+b.png` names `a b.png` and
// `a%zzb.png` names `a\0b.png`. Its decoding, reproduced here, is how a name it asks for is traced back
// to the URI it came from.
std::string formDecoded(const std::string& uri) {
  auto hex = [](unsigned char c) -> unsigned char {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      out += static_cast<char>((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

std::vector<FileUri> checkGltfJson(const std::string& path, const std::string& text, const char* what) {
  checkJsonDepth(path, text, what);
  try {
    const nlohmann::json parsed = nlohmann::json::parse(text);
    checkImageViews(path, parsed);
    return fileUris(parsed);
  } catch (const nlohmann::json::exception& e) {
    // nlohmann's messages start with "[json.exception.parse_error.101] "; the user needs the rest.
    std::string msg = e.what();
    const size_t close = msg.find("] ");
    if (close != std::string::npos) msg = msg.substr(close + 2);
    throw InputError(path, std::string("invalid JSON ") + what + ": " + msg);
  }
}

ReferencedFiles::ReferencedFiles(ReferencePolicy policy, const std::vector<FileUri>& uris)
    : policy_(std::move(policy)), folder_(policy_.folder.string()) {
  prefix_ = folder_.back() == '/' ? folder_ : folder_ + "/";
  for (const FileUri& u : uris) {
    auto [named, added] =
        names_.try_emplace(formDecoded(u.uri), Name{u.uri, percentDecode(u.uri), "", false});
    if (!added && named->second.file != percentDecode(u.uri)) named->second.otherUri = u.uri;
    named->second.isBuffer = named->second.isBuffer || u.isBuffer;
  }
}

bool ReferencedFiles::exists(const std::string& path, void* self) {
  auto& files = *static_cast<ReferencedFiles*>(self);
  if (path.compare(0, files.prefix_.size(), files.prefix_) != 0) return false;
  const std::string file = files.fileNamed(path.substr(files.prefix_.size()));
  std::optional<std::string> bytes = readReferencedFile(files.policy_, file);
  if (!bytes) {
    const auto named = files.names_.find(path.substr(files.prefix_.size()));
    if (named != files.names_.end() && named->second.isBuffer)
      throw InputError(files.policy_.sceneFile, "buffer file '" + printable(file) + "': no such file");
    files.missing_.insert(file);
    return false;
  }
  files.read_[path] = std::move(*bytes);
  return true;
}

bool ReferencedFiles::read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                           void* self) {
  auto& files = *static_cast<ReferencedFiles*>(self);
  auto it = files.read_.find(path);
  if (it == files.read_.end()) {
    if (err) *err += "not checked before reading";
    return false;
  }
  out->assign(it->second.begin(), it->second.end());
  files.read_.erase(it);
  return true;
}

bool ReferencedFiles::refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&,
                                  void*) {
  if (err) *err += "the reader never writes";
  return false;
}

// The file behind tinygltf's decoding `decoded` of a URI. Two URIs it decodes alike (`a+b.png` and
// `a%20b.png`) cannot be told apart from here: refused rather than one read for the other.
std::string ReferencedFiles::fileNamed(const std::string& decoded) const {
  const auto named = names_.find(decoded);
  if (named == names_.end()) return decoded;
  if (!named->second.otherUri.empty())
    throw InputError(policy_.sceneFile, "the URIs '" + printable(named->second.uri) + "' and '" +
                                            printable(named->second.otherUri) +
                                            "' name two files, which cpgi's glTF parser cannot tell apart");
  return named->second.file;
}

}  // namespace cpgi::detail
