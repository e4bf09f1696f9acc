// Builds glTF files byte by byte for tests, independently of cpgi's writer, so that the reader is
// checked against files it did not produce (and broken files can be made on purpose).
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cpgi::test {

class GlbBuilder {
 public:
  nlohmann::json doc;
  std::string bin;

  GlbBuilder() {
    doc["asset"] = {{"version", "2.0"}};
    doc["scene"] = 0;
    doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
    doc["nodes"] = nlohmann::json::array();
    doc["meshes"] = nlohmann::json::array();
    doc["accessors"] = nlohmann::json::array();
    doc["bufferViews"] = nlohmann::json::array();
  }

  int addView(const void* data, size_t bytes) {
    while (bin.size() % 4) bin.push_back('\0');
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    bin.append(static_cast<const char*>(data), bytes);
    return static_cast<int>(doc["bufferViews"].size() - 1);
  }
  /// Float VEC3 accessor (POSITION / NORMAL).
  int addVec3(const std::vector<float>& xyz) {
    return addAccessor(addView(xyz.data(), xyz.size() * 4), 5126, xyz.size() / 3, "VEC3");
  }
  /// Index accessor with componentType 5121 (u8), 5123 (u16) or 5125 (u32).
  int addIndices(const std::vector<uint32_t>& idx, int componentType = 5125) {
    std::string bytes;
    for (uint32_t i : idx) {
      const size_t size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4;
      bytes.append(reinterpret_cast<const char*>(&i), size);  // little-endian low bytes
    }
    return addAccessor(addView(bytes.data(), bytes.size()), componentType, idx.size(), "SCALAR");
  }
  int addAccessor(int view, int componentType, size_t count, const char* type) {
    doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return static_cast<int>(doc["accessors"].size() - 1);
  }
  /// A mesh of one primitive; returns the mesh index.
  int addMesh(const std::vector<float>& positions, const std::vector<uint32_t>& indices = {},
              int material = -1, int mode = 4, int indexType = 5125) {
    nlohmann::json prim = {{"attributes", {{"POSITION", addVec3(positions)}}}, {"mode", mode}};
    if (!indices.empty()) prim["indices"] = addIndices(indices, indexType);
    if (material >= 0) prim["material"] = material;
    doc["meshes"].push_back({{"primitives", nlohmann::json::array({prim})}});
    return static_cast<int>(doc["meshes"].size() - 1);
  }
  /// A node; root nodes are listed in scene 0.
  int addNode(nlohmann::json node, bool root = true) {
    doc["nodes"].push_back(std::move(node));
    const int index = static_cast<int>(doc["nodes"].size() - 1);
    if (root) doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  int addMaterial(nlohmann::json material) {
    doc["materials"].push_back(std::move(material));
    return static_cast<int>(doc["materials"].size() - 1);
  }

  std::string glb() const { return container(jsonWithBuffer().dump(), paddedBin()); }
  /// The document as the .glb will carry it (with its buffer declared).
  nlohmann::json jsonWithBuffer() const {
    nlohmann::json d = doc;
    if (!bin.empty()) d["buffers"] = nlohmann::json::array({{{"byteLength", paddedBin().size()}}});
    return d;
  }
  /// A .glb whose JSON chunk is the given text (valid or not).
  std::string glbWithJson(const std::string& json) const { return container(json, paddedBin()); }
  std::string gltf() const;

  void writeGlb(const std::filesystem::path& path) const { writeBytes(path, glb()); }
  static void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }

 private:
  std::string paddedBin() const {
    std::string b = bin;
    while (b.size() % 4) b.push_back('\0');
    return b;
  }
  std::string container(std::string json, const std::string& b) const {
    while (json.size() % 4) json.push_back(' ');
    std::string out = "glTF";
    auto u32 = [&out](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + json.size() + (b.empty() ? 0 : 8 + b.size())));
    u32(static_cast<uint32_t>(json.size()));
    u32(0x4E4F534Au);
    out += json;
    if (!b.empty()) {
      u32(static_cast<uint32_t>(b.size()));
      u32(0x004E4942u);
      out += b;
    }
    return out;
  }
};

inline std::string GlbBuilder::gltf() const {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string encoded;
  for (size_t i = 0; i < bin.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bin[i])) << 16;
    if (i + 1 < bin.size()) n |= uint32_t(uint8_t(bin[i + 1])) << 8;
    if (i + 2 < bin.size()) n |= uint32_t(uint8_t(bin[i + 2]));
    encoded += table[(n >> 18) & 63];
    encoded += table[(n >> 12) & 63];
    encoded += i + 1 < bin.size() ? table[(n >> 6) & 63] : '=';
    encoded += i + 2 < bin.size() ? table[n & 63] : '=';
  }
  nlohmann::json d = doc;
  d["buffers"] = nlohmann::json::array(
      {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + encoded}}});
  return d.dump();
}

}  // namespace cpgi::test
