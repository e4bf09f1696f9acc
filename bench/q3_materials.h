// The materials of a converted Quake III level (bench/q3bsp_to_obj.cpp): one per shader the level's faces
// use, named by the shader's path, with its texture's mean colour and its light when the game's data
// (.pk3 archives: zip files of textures and shader scripts) is at hand. A closed level has no sky to
// light it; its lamps are its light shaders (q3map_surfacelight), and `cpgi bake --emit NAME=W` can only
// light them when each shader is its own material (issue 46). Header only, standard C++ and
// stb_image (Debian's libstb-dev) alone: its implementation is compiled by whoever includes this first
// with STB_IMAGE_IMPLEMENTATION defined (the converter, the test).
#pragma once

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "q3bsp.h"

namespace q3materials {

/// A material name from a shader's path ("textures/base_light/ceil1_39"): letters, digits and
/// `_ - . /` kept, anything else (spaces, `=`, which --emit splits on) made `_`; empty gives "noshader".
inline std::string materialName(const std::string& shader) {
  std::string out;
  for (const char c : shader) {
    if (c == '\0') break;
    const bool keep =
        std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == '/';
    out += keep ? c : '_';
  }
  return out.empty() ? "noshader" : out;
}

inline std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// What a shader script says of one shader: the image it shows (qer_editorimage, else its first `map`
/// stage that is a file) and its light (q3map_surfacelight, 0 when it gives none).
struct ShaderScript {
  std::string image;
  double surfaceLight = 0.0;
};

/// The shaders of one .shader script by their lower-case name. Comments (//) are skipped; stages are the
/// nested braces.
inline std::map<std::string, ShaderScript> parseShaderScript(const std::string& text) {
  std::map<std::string, ShaderScript> out;
  std::istringstream lines(text);
  std::string line, current;
  int depth = 0;
  while (std::getline(lines, line)) {
    if (const size_t c = line.find("//"); c != std::string::npos) line.erase(c);
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      if (word == "{") {
        ++depth;
      } else if (word == "}") {
        depth = std::max(0, depth - 1);
      } else if (depth == 0) {
        current = lower(word);
        out[current];
      } else if (!current.empty()) {
        const std::string key = lower(word);
        std::string value;
        if (key == "q3map_surfacelight" && words >> value) {
          out[current].surfaceLight = std::atof(value.c_str());
        } else if (key == "qer_editorimage" && words >> value) {
          out[current].image = lower(value);
        } else if ((key == "map" || key == "clampmap") && depth == 2 && words >> value && value[0] != '$' &&
                   out[current].image.empty()) {
          out[current].image = lower(value);
        }
      }
    }
  }
  return out;
}

/// One file in a zip archive (a .pk3).
struct ZipEntry {
  uint32_t localHeader = 0, compressedSize = 0, size = 0;
  uint16_t method = 0;  ///< 0 stored, 8 deflated
};

/// A zip archive's files by lower-case name, read from its central directory; empty when `bytes` is no zip.
inline std::map<std::string, ZipEntry> zipEntries(const std::string& bytes) {
  auto u16 = [&](size_t at) { return uint16_t(uint8_t(bytes[at]) | uint8_t(bytes[at + 1]) << 8); };
  auto u32 = [&](size_t at) { return uint32_t(u16(at)) | uint32_t(u16(at + 2)) << 16; };
  std::map<std::string, ZipEntry> out;
  if (bytes.size() < 22) return out;
  size_t end = bytes.size() - 22;  // the end of central directory record, before an archive comment
  while (end > 0 && u32(end) != 0x06054b50) --end;
  if (u32(end) != 0x06054b50) return out;
  size_t at = u32(end + 16);
  for (uint16_t n = u16(end + 10); n > 0 && at + 46 <= bytes.size() && u32(at) == 0x02014b50; --n) {
    ZipEntry e;
    e.method = u16(at + 10), e.compressedSize = u32(at + 20), e.size = u32(at + 24);
    e.localHeader = u32(at + 42);
    const size_t nameLength = u16(at + 28);
    if (at + 46 + nameLength > bytes.size()) break;
    out[lower(bytes.substr(at + 46, nameLength))] = e;
    at += 46 + nameLength + u16(at + 30) + u16(at + 32);
  }
  return out;
}

/// The bytes of one entry; nullopt when it is cut short or neither stored nor deflated.
inline std::optional<std::string> zipRead(const std::string& bytes, const ZipEntry& e) {
  const size_t h = e.localHeader;
  if (h + 30 > bytes.size()) return std::nullopt;
  auto u16 = [&](size_t at) { return size_t(uint8_t(bytes[at]) | uint8_t(bytes[at + 1]) << 8); };
  const size_t data = h + 30 + u16(h + 26) + u16(h + 28);
  if (data + e.compressedSize > bytes.size()) return std::nullopt;
  if (e.method == 0) return bytes.substr(data, e.compressedSize);
  if (e.method != 8) return std::nullopt;
  // stb_image's inflater reads past a stream that ends at the buffer's end and calls it a bad code:
  // the entry is given with zero bytes after it.
  std::string padded = bytes.substr(data, e.compressedSize) + std::string(8, '\0');
  int length = 0;
  char* out = stbi_zlib_decode_noheader_malloc(padded.data(), int(padded.size()), &length);
  if (!out) return std::nullopt;
  std::string result(out, size_t(length));
  std::free(out);
  return result;
}

/// An image's mean colour as linear reflectance (the sRGB texels decoded, then averaged); nullopt when
/// stb_image cannot read it.
inline std::optional<std::array<double, 3>> meanColour(const std::string& image) {
  int w = 0, h = 0, channels = 0;
  unsigned char* texels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(image.data()),
                                                int(image.size()), &w, &h, &channels, 3);
  if (!texels) return std::nullopt;
  std::array<double, 3> sum{0, 0, 0};
  for (size_t k = 0; k < size_t(w) * size_t(h) * 3; ++k) {
    const double c = texels[k] / 255.0;
    sum[k % 3] += c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  }
  stbi_image_free(texels);
  for (double& c : sum) c /= std::max(1.0, double(w) * double(h));
  return sum;
}

/// The game's data: every archive's files and every shader script's shaders (a later archive's win, as
/// the game loads pak0, pak1, ... in order).
class GameData {
 public:
  /// Reads each archive whole; an unreadable one is skipped and named in `unread`.
  explicit GameData(const std::vector<std::string>& archives) {
    for (const std::string& path : archives) {
      std::ifstream in(path, std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      auto entries = zipEntries(bytes);
      if (entries.empty()) {
        unread.push_back(path);
        continue;
      }
      const size_t index = archives_.size();
      archives_.push_back(std::move(bytes));
      for (const auto& [name, entry] : entries) {
        files_[name] = {index, entry};
        if (name.rfind("scripts/", 0) == 0 && name.size() > 7 && name.substr(name.size() - 7) == ".shader")
          if (const auto text = zipRead(archives_.back(), entry))
            for (auto& [shader, script] : parseShaderScript(*text)) shaders_[shader] = script;
      }
    }
  }
  std::vector<std::string> unread;

  const ShaderScript* script(const std::string& shader) const {
    const auto it = shaders_.find(lower(shader));
    return it == shaders_.end() ? nullptr : &it->second;
  }
  /// The mean colour of the image a shader shows: its script's image, else the file named as the shader;
  /// as the game does, NAME.tga and NAME.jpg are both tried whatever the extension given.
  std::optional<std::array<double, 3>> shaderColour(const std::string& shader) const {
    std::string image = lower(shader);
    if (const ShaderScript* s = script(shader); s && !s->image.empty()) image = s->image;
    if (const size_t dot = image.rfind('.'); dot != std::string::npos && image.size() - dot <= 4)
      image.erase(dot);
    for (const char* ext : {".tga", ".jpg", ".png"}) {
      const auto it = files_.find(image + ext);
      if (it == files_.end()) continue;
      if (const auto bytes = zipRead(archives_[it->second.first], it->second.second))
        if (auto colour = meanColour(*bytes)) return colour;
    }
    return std::nullopt;
  }

 private:
  std::vector<std::string> archives_;
  std::map<std::string, std::pair<size_t, ZipEntry>> files_;
  std::map<std::string, ShaderScript> shaders_;
};

/// One material of the converted level.
struct Material {
  std::string name;                         ///< materialName(shader)
  std::string shader;                       ///< as the BSP names it
  std::array<double, 3> kd{0.5, 0.5, 0.5};  ///< the texture's mean colour, grey when not at hand
  bool colourFound = false;
  double surfaceLight = 0.0;  ///< q3map_surfacelight: a light shader when > 0
};

/// The materials of the shaders `used`, in their order, from `data` (null: no game data, every one grey).
inline std::vector<Material> levelMaterials(const std::vector<std::string>& used, const GameData* data) {
  std::vector<Material> out;
  for (const std::string& shader : used) {
    Material m;
    m.shader = shader, m.name = materialName(shader);
    if (data) {
      if (const ShaderScript* s = data->script(shader)) m.surfaceLight = s->surfaceLight;
      if (const auto colour = data->shaderColour(shader)) m.kd = *colour, m.colourFound = true;
    }
    out.push_back(m);
  }
  return out;
}

/// The MTL file of `materials`: Kd per material, and a comment naming the light shaders' surfacelight.
inline std::string mtlText(const std::vector<Material>& materials) {
  std::ostringstream out;
  out << "# one material per Quake III shader; Kd = its texture's mean colour (grey: not found)\n";
  char line[160];
  for (const Material& m : materials) {
    out << "newmtl " << m.name << "\n";
    if (m.surfaceLight > 0.0) out << "# light shader: q3map_surfacelight " << m.surfaceLight << "\n";
    std::snprintf(line, sizeof line, "Kd %.4f %.4f %.4f\n", m.kd[0], m.kd[1], m.kd[2]);
    out << line;
  }
  return out.str();
}

/// `--emit` flags that light a closed level by its own light shaders, W/m² = surfacelight / 10 (a
/// starting point: q3map's values are the compiler's, not physical; 1 000, a common lamp, gives the
/// thesis's 100 W/m²). Empty when the level has no light shader.
inline std::string emitFlags(const std::vector<Material>& materials) {
  std::string out;
  char flag[200];
  for (const Material& m : materials)
    if (m.surfaceLight > 0.0) {
      std::snprintf(flag, sizeof flag, "%s--emit %s=%g", out.empty() ? "" : " ", m.name.c_str(),
                    m.surfaceLight / 10.0);
      out += flag;
    }
  return out;
}

/// The shaders the triangles use, each once in order of first use (−1: none), and per triangle the index
/// of its material in that list.
inline std::vector<int32_t> usedShaders(const q3bsp::Mesh& mesh, std::vector<size_t>& material) {
  std::vector<int32_t> used;
  material.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int32_t s = t < mesh.triangleShader.size() ? mesh.triangleShader[t] : -1;
    const auto it = std::find(used.begin(), used.end(), s);
    material[t] = size_t(it - used.begin());
    if (it == used.end()) used.push_back(s);
  }
  return used;
}

/// A converted level's files: the OBJ (faces grouped by material, one usemtl each) and its MTL.
struct Level {
  std::string obj, mtl;
  std::vector<Material> materials;
};

/// The OBJ and MTL of `mesh`, its materials from `data` (null: grey); `header` is the OBJ's first comment,
/// `mtlName` the MTL's file name as the OBJ's mtllib gives it.
inline Level levelFiles(const q3bsp::Mesh& mesh, const GameData* data, const std::string& header,
                        const std::string& mtlName) {
  std::vector<size_t> material;
  std::vector<std::string> names;
  for (const int32_t s : usedShaders(mesh, material))
    names.push_back(s >= 0 && size_t(s) < mesh.shaders.size() ? mesh.shaders[size_t(s)] : "");
  Level level;
  level.materials = levelMaterials(names, data);
  level.mtl = mtlText(level.materials);
  std::ostringstream out;
  out << "# " << header << "\nmtllib " << mtlName << "\no world\n";
  char line[128];
  for (const q3bsp::V3& p : mesh.points) {
    std::snprintf(line, sizeof(line), "v %.5f %.5f %.5f\n", p[0], p[1], p[2]);
    out << line;
  }
  std::vector<size_t> order(mesh.triangles.size());
  for (size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return material[a] < material[b]; });
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t t = order[k];
    if (k == 0 || material[t] != material[order[k - 1]])
      out << "usemtl " << level.materials[material[t]].name << "\n";
    const auto& tri = mesh.triangles[t];
    out << "f " << tri[0] + 1 << " " << tri[1] + 1 << " " << tri[2] + 1 << "\n";
  }
  level.obj = out.str();
  return level;
}

}  // namespace q3materials
