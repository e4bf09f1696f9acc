// Scene (+ cells, + lightmap) → glTF 2.0. The JSON is built directly: the file layout (node names of
// design.md §3, one node per cell, portals as quads) is the contract, and writing it by hand keeps
// every byte under our control.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/lights.h"
#include "core/output_dir.h"
#include "core/scene_io.h"
#include "core/scene_io_detail.h"

namespace cpgi {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

std::string base64(const std::string& in) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (size_t i = 0; i < in.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(in[i])) << 16;
    if (i + 1 < in.size()) n |= uint32_t(uint8_t(in[i + 1])) << 8;
    if (i + 2 < in.size()) n |= uint32_t(uint8_t(in[i + 2]));
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < in.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? table[n & 63] : '=';
  }
  return out;
}

std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (start <= path.size()) {
    const size_t slash = path.find('/', start);
    const size_t end = slash == std::string::npos ? path.size() : slash;
    if (end > start) parts.push_back(path.substr(start, end - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return parts;
}

bool isTagged(const std::string& name) {
  return name.rfind("cell:", 0) == 0 || name.rfind("portal:", 0) == 0 || name.rfind("cellvolume:", 0) == 0;
}

class GltfBuilder {
 public:
  json doc = json::object();
  std::string bin;

  GltfBuilder() {
    doc["asset"] = {{"version", "2.0"}, {"generator", "cpgi 0.1.0"}};
    for (const char* key : {"bufferViews", "accessors", "meshes", "nodes", "materials", "cameras"})
      doc[key] = json::array();
  }

  int addView(const void* data, size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back('\0');
    json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (target) view["target"] = target;
    bin.append(static_cast<const char*>(data), bytes);
    return push("bufferViews", view);
  }

  int addVec3(const std::vector<glm::vec3>& v, bool withBounds) {
    json a = {{"bufferView", addView(v.data(), v.size() * sizeof(glm::vec3), kArrayBuffer)},
              {"componentType", kFloat},
              {"count", v.size()},
              {"type", "VEC3"}};
    if (withBounds) {  // required on POSITION
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (const glm::vec3& q : v) lo = glm::min(lo, q), hi = glm::max(hi, q);
      a["min"] = {lo.x, lo.y, lo.z};
      a["max"] = {hi.x, hi.y, hi.z};
    }
    return push("accessors", a);
  }

  int addVec2(const std::vector<glm::vec2>& v) {
    return push("accessors", {{"bufferView", addView(v.data(), v.size() * sizeof(glm::vec2), kArrayBuffer)},
                              {"componentType", kFloat},
                              {"count", v.size()},
                              {"type", "VEC2"}});
  }

  int addIndices(const std::vector<uint32_t>& v) {
    return push("accessors", {{"bufferView", addView(v.data(), v.size() * 4, kElementArrayBuffer)},
                              {"componentType", kUnsignedInt},
                              {"count", v.size()},
                              {"type", "SCALAR"}});
  }

  int push(const char* key, json value) {
    doc[key].push_back(std::move(value));
    return static_cast<int>(doc[key].size() - 1);
  }

  void useExtension(const std::string& name) { extensions_.insert(name); }

  std::string finish(bool binary) {
    if (!extensions_.empty()) doc["extensionsUsed"] = extensions_;
    for (auto it = doc.begin(); it != doc.end();)
      it = it->is_array() && it->empty() ? doc.erase(it) : std::next(it);
    while (bin.size() % 4) bin.push_back('\0');
    if (!bin.empty()) {
      json buffer = {{"byteLength", bin.size()}};
      if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(bin);
      doc["buffers"] = json::array({buffer});
    }
    std::string text = doc.dump();
    if (!binary) return text;
    while (text.size() % 4) text.push_back(' ');
    const uint32_t total = 12 + 8 + uint32_t(text.size()) + (bin.empty() ? 0 : 8 + uint32_t(bin.size()));
    std::string out;
    auto u32 = [&out](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    out += "glTF";
    u32(2);
    u32(total);
    u32(uint32_t(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += text;
    if (!bin.empty()) {
      u32(uint32_t(bin.size()));
      u32(0x004E4942u);  // "BIN\0"
      out += bin;
    }
    return out;
  }

 private:
  std::set<std::string> extensions_;
};

// The writer's node tree: named by path components, each may carry triangles.
struct TreeNode {
  std::string name;
  std::vector<int> children;
  std::vector<uint32_t> triangles;
  std::map<std::string, int> childByName;
};

class Tree {
 public:
  std::vector<TreeNode> nodes;
  std::vector<int> roots;

  int ensure(const std::vector<std::string>& parts) {
    int parent = -1;
    for (const std::string& name : parts) {
      std::map<std::string, int>& byName = parent < 0 ? rootByName_ : nodes[parent].childByName;
      const auto [it, fresh] = byName.emplace(name, static_cast<int>(nodes.size()));
      const int index = it->second;  // read before nodes grows and moves the maps
      if (fresh) {
        (parent < 0 ? roots : nodes[parent].children).push_back(index);
        nodes.push_back(TreeNode{name, {}, {}, {}});
      }
      parent = index;
    }
    return parent;
  }

 private:
  std::map<std::string, int> rootByName_;
};

json vec(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

class SceneWriter {
 public:
  SceneWriter(const Scene& scene, const GltfWriteOptions& options) : scene_(scene), options_(options) {}

  std::string write(bool binary) {
    if (options_.lightmapUVs && options_.lightmapUVs->size() != scene_.triangles.size())
      throw std::invalid_argument("writeGltf: lightmapUVs must have one entry per triangle");
    if (options_.lightmapOfTriangle &&
        (options_.lightmapOfTriangle->size() != scene_.triangles.size() ||
         options_.objectLightmapNames.size() != options_.objectLightmapPngs.size()))
      throw std::invalid_argument("writeGltf: one lightmap per triangle, one name per object lightmap");
    for (const Triangle& t : scene_.triangles)
      if (t.material >= scene_.materials.size())
        throw std::invalid_argument("writeGltf: material index out of range");
    if (options_.forEngines)
      writeEngineMaterials();
    else
      writeMaterials();
    buildTree();
    for (int r : tree_.roots) sceneRoots_.push_back(emitTreeNode(r));
    if (options_.cells && options_.keepHelpers) writeCellExtras();
    if (options_.keepSeal) writeSeal();
    writeCameras();
    if (options_.keepHelpers) writeLights();
    b_.doc["scenes"] = json::array({{{"nodes", sceneRoots_}}});
    b_.doc["scene"] = 0;
    return b_.finish(binary);
  }

 private:
  void writeMaterials() {
    const bool baked = options_.lightmapUVs && !options_.lightmapPng.empty();
    int texture = -1;
    if (baked) {
      const int view = b_.addView(options_.lightmapPng.data(), options_.lightmapPng.size(), 0);
      b_.push("images", {{"bufferView", view}, {"mimeType", "image/png"}, {"name", "lightmap"}});
      b_.push("samplers", {{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}});
      texture = b_.push("textures", {{"source", 0}, {"sampler", 0}});
      b_.useExtension("KHR_materials_unlit");
    }
    for (const Material& m : scene_.materials) {
      json mat = {{"name", m.name}};
      if (baked) {
        // Viewers show the baked light as is; the material it was baked with stays in extras.
        mat["pbrMetallicRoughness"] = {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}},
                                       {"baseColorTexture", {{"index", texture}, {"texCoord", 1}}},
                                       {"metallicFactor", 0.0},
                                       {"roughnessFactor", 1.0}};
        mat["extensions"]["KHR_materials_unlit"] = json::object();
        mat["extras"] = {{"cpgi_albedo", vec(m.albedo)}, {"cpgi_emission", vec(m.emission)}};
      } else {
        mat["pbrMetallicRoughness"] = {{"baseColorFactor", {m.albedo.r, m.albedo.g, m.albedo.b, 1.0}},
                                       {"metallicFactor", 0.0},
                                       {"roughnessFactor", 1.0}};
        setEmission(mat, m);
      }
      b_.push("materials", mat);
    }
  }

  // glTF's emissive factor is limited to [0,1]; the rest goes into KHR_materials_emissive_strength.
  void setEmission(json& mat, const Material& m) {
    if (!m.isEmitter()) return;
    const double strength = std::max({double(m.emission.r), double(m.emission.g), double(m.emission.b)});
    if (strength > 1.0) {
      mat["emissiveFactor"] = {m.emission.r / strength, m.emission.g / strength, m.emission.b / strength};
      mat["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", strength}};
      b_.useExtension("KHR_materials_emissive_strength");
    } else {
      mat["emissiveFactor"] = vec(m.emission);
    }
  }

  // A scene texture as a texture of the file written: its image and sampler, each once.
  int engineTexture(int index) {
    const SceneLooks& looks = scene_.looks;
    if (index < 0 || index >= int(looks.textures.size()) ||
        looks.textures[index].image >= looks.images.size())
      return -1;
    if (auto it = textureIndex_.find(index); it != textureIndex_.end()) return it->second;
    const SurfaceTexture& t = looks.textures[index];
    auto image = imageIndex_.find(t.image);
    if (image == imageIndex_.end()) {
      const SurfaceImage& si = looks.images[t.image];
      const int view = b_.addView(si.bytes.data(), si.bytes.size(), 0);
      json img = {{"bufferView", view}, {"mimeType", si.mimeType}};
      if (!si.name.empty()) img["name"] = si.name;
      image = imageIndex_.emplace(t.image, b_.push("images", img)).first;
    }
    json sampler = {{"wrapS", t.wrapS}, {"wrapT", t.wrapT}};
    if (t.magFilter > 0) sampler["magFilter"] = t.magFilter;
    if (t.minFilter > 0) sampler["minFilter"] = t.minFilter;
    const int samplerIndex = b_.push("samplers", sampler);
    return textureIndex_[index] = b_.push("textures", {{"source", image->second}, {"sampler", samplerIndex}});
  }

  // A lightmap PNG as a texture of the file written (linear filtering, clamped).
  int lightmapTexture(const std::string& png, const std::string& name) {
    if (lightmapSampler_ < 0)
      lightmapSampler_ =
          b_.push("samplers", {{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}});
    const int view = b_.addView(png.data(), png.size(), 0);
    const int image = b_.push("images", {{"bufferView", view}, {"mimeType", "image/png"}, {"name", name}});
    return b_.push("textures", {{"source", image}, {"sampler", lightmapSampler_}, {"name", name}});
  }

  // The scene's own materials, as the file gave them, with the irradiance lightmap referenced by each: the
  // one lightmap's, or with per-object lightmaps one copy of a material per object lightmap that uses it
  // (MOZ_lightmap, like three.js's lightMap, belongs to the material), made when a mesh first needs it.
  void writeEngineMaterials() {
    if (!options_.lightmapUVs) {
      for (size_t k = 0; k < scene_.materials.size(); ++k) b_.push("materials", engineMaterial(k, -1));
      return;
    }
    json extras =
        options_.lightmapExtrasJson.empty() ? json::object() : json::parse(options_.lightmapExtrasJson);
    extras.update({{"texCoord", 1},
                   {"intensity", options_.lightmapIntensity},
                   {"colorSpace", "srgb"},
                   {"quantity", "irradiance W/m2 (light arriving, without albedo)"}});
    if (perObject()) {
      json textures = json::array();
      for (size_t k = 0; k < options_.objectLightmapPngs.size(); ++k) {
        objectTextures_.push_back(
            lightmapTexture(options_.objectLightmapPngs[k], options_.objectLightmapNames.at(k)));
        textures.push_back(
            {{"object", options_.objectLightmapNames[k]}, {"texture", objectTextures_.back()}});
      }
      extras["object_textures"] = textures;
    } else if (!options_.lightmapPng.empty()) {
      lightmap_ = lightmapTexture(options_.lightmapPng, "lightmap");
      extras["texture"] = lightmap_;
    } else {
      for (size_t k = 0; k < scene_.materials.size(); ++k) b_.push("materials", engineMaterial(k, -1));
      return;
    }
    b_.doc["extras"]["cpgi_lightmap"] = extras;
    b_.useExtension("MOZ_lightmap");
    if (!perObject())
      for (size_t k = 0; k < scene_.materials.size(); ++k) b_.push("materials", engineMaterial(k, lightmap_));
  }

  bool perObject() const {
    return options_.forEngines && options_.lightmapOfTriangle && options_.lightmapUVs;
  }

  // The material written for scene material `material` on triangle `triangle`'s lightmap.
  int materialFor(uint32_t material, uint32_t triangle) {
    if (!perObject()) return int(material);
    const int object = (*options_.lightmapOfTriangle)[triangle];
    const auto key = std::make_pair(material, object);
    if (auto it = objectMaterials_.find(key); it != objectMaterials_.end()) return it->second;
    const int texture = object >= 0 ? objectTextures_.at(size_t(object)) : -1;
    json mat = engineMaterial(material, texture);
    if (object >= 0) mat["extras"]["cpgi_lightmap"] = options_.objectLightmapNames[size_t(object)];
    return objectMaterials_[key] = b_.push("materials", mat);
  }

  json engineMaterial(size_t k, int lightmap) {
    const Material& m = scene_.materials[k];
    const SceneLooks& looks = scene_.looks;
    MaterialLook look;
    if (k < looks.materials.size())
      look = looks.materials[k];
    else
      look.baseColorFactor = glm::vec4(m.albedo, 1.0f);
    const glm::vec4& f = look.baseColorFactor;
    json pbr = {{"baseColorFactor", {f.r, f.g, f.b, f.a}},
                {"metallicFactor", look.metallicFactor},
                {"roughnessFactor", look.roughnessFactor}};
    if (const int t = engineTexture(look.baseColorTexture); t >= 0) pbr["baseColorTexture"] = {{"index", t}};
    json mat = {{"name", m.name}, {"pbrMetallicRoughness", pbr}};
    if (const int t = engineTexture(look.normalTexture); t >= 0)
      mat["normalTexture"] = {{"index", t}, {"scale", look.normalScale}};
    setEmission(mat, m);
    if (const int t = engineTexture(look.emissiveTexture); t >= 0 && m.isEmitter())
      mat["emissiveTexture"] = {{"index", t}};
    if (look.doubleSided) mat["doubleSided"] = true;
    if (lightmap >= 0) {
      mat["extensions"]["MOZ_lightmap"] = {
          {"index", lightmap}, {"texCoord", 1}, {"intensity", options_.lightmapIntensity}};
      // The albedo and emission baked with, which a texture's mean gave: read back as they were.
      mat["extras"] = {{"cpgi_albedo", vec(m.albedo)}, {"cpgi_emission", vec(m.emission)}};
    }
    return mat;
  }

  void buildTree() {
    std::vector<int> cellOf;
    if (options_.cells) cellOf = options_.cells->cellOfTriangle(scene_.triangles.size());
    // Triangles keep their node path; with cells, `cell:` components are replaced by the triangle's cell.
    std::map<std::pair<int, uint32_t>, int> group;  // (cell, node path) -> tree node
    for (uint32_t i = 0; i < scene_.triangles.size(); ++i) {
      const Triangle& t = scene_.triangles[i];
      const int cell = options_.cells ? cellOf[i] : -1;
      auto [it, fresh] = group.emplace(std::make_pair(cell, t.node), -1);
      if (fresh) {
        std::vector<std::string> parts;
        if (cell >= 0) parts.push_back("cell:" + options_.cells->cells[cell].name);
        const std::string path = t.node < scene_.nodePaths.size() ? scene_.nodePaths[t.node] : std::string();
        for (const std::string& part : splitPath(path))
          if (!options_.cells || !isTagged(part)) parts.push_back(part);
        if (parts.empty() || (cell >= 0 && parts.size() == 1)) parts.push_back("mesh");
        it->second = tree_.ensure(parts);
      }
      tree_.nodes[it->second].triangles.push_back(i);
    }
  }

  // One primitive per material, unindexed (three vertices per triangle).
  int emitTriangleMesh(const std::string& name, const std::vector<uint32_t>& triangles) {
    std::map<uint32_t, std::vector<uint32_t>> byMaterial;
    for (uint32_t i : triangles) byMaterial[scene_.triangles[i].material].push_back(i);
    json primitives = json::array();
    for (const auto& [material, tris] : byMaterial) {
      std::vector<glm::vec3> pos, nrm;
      std::vector<glm::vec2> uv, uv0;
      for (uint32_t i : tris) {
        const Triangle& t = scene_.triangles[i];
        const SurfaceUV* own = t.uv < scene_.looks.uvs.size() ? &scene_.looks.uvs[t.uv] : nullptr;
        for (int k = 0; k < 3; ++k) {
          pos.push_back(t.p[k]);
          nrm.push_back(t.n[k]);
          if (options_.lightmapUVs) uv.push_back((*options_.lightmapUVs)[i][k]);
          if (options_.forEngines) uv0.push_back(own && own->has(0) ? own->at(t.p[k], 0) : glm::vec2(0.0f));
        }
      }
      json attributes = {{"POSITION", b_.addVec3(pos, true)}, {"NORMAL", b_.addVec3(nrm, false)}};
      if (options_.forEngines) {
        // The material's own coordinates first, the lightmap's second (three.js's uv1, Godot's UV2,
        // Blender's second UV map).
        attributes["TEXCOORD_0"] = b_.addVec2(uv0);
        if (options_.lightmapUVs) attributes["TEXCOORD_1"] = b_.addVec2(uv);
      } else if (options_.lightmapUVs) {
        // The lightmap is the second UV set, where engines look for one (Godot's UV2, Blender's second
        // map, three.js's uv1). glTF wants sets numbered from 0 and the scene keeps no texture
        // coordinates of its own, so TEXCOORD_0 shares the same accessor.
        const int lightmapUVs = b_.addVec2(uv);
        attributes["TEXCOORD_0"] = lightmapUVs;
        attributes["TEXCOORD_1"] = lightmapUVs;
      }
      primitives.push_back(
          {{"attributes", attributes}, {"material", materialFor(material, tris.front())}, {"mode", 4}});
    }
    return b_.push("meshes", {{"name", name}, {"primitives", primitives}});
  }

  int emitTreeNode(int index) {
    const TreeNode& tn = tree_.nodes[index];
    json node = {{"name", tn.name}};
    if (!tn.triangles.empty()) node["mesh"] = emitTriangleMesh(tn.name, tn.triangles);
    json children = json::array();
    for (int c : tn.children) children.push_back(emitTreeNode(c));
    if (!children.empty()) node["children"] = children;
    return b_.push("nodes", node);
  }

  int helperMaterial(const char* name, glm::vec4 colour) {
    json mat = {{"name", name},
                {"pbrMetallicRoughness",
                 {{"baseColorFactor", {colour.r, colour.g, colour.b, colour.a}},
                  {"metallicFactor", 0.0},
                  {"roughnessFactor", 1.0}}},
                {"alphaMode", "BLEND"},
                {"doubleSided", true}};
    return b_.push("materials", mat);
  }

  // Portals as quads wound so that their normal points from cell A into cell B; cell volumes as meshes.
  // Both get a translucent material of their own so that viewers show them as what they are.
  void writeCellExtras() {
    const CellGraph& g = *options_.cells;
    std::set<std::string> used;
    int portalMaterial = -1;
    for (const PortalQuad& p : g.portals) {
      if (p.cellA < 0 || p.cellB < 0 || p.cellA >= int(g.cells.size()) || p.cellB >= int(g.cells.size()))
        throw std::invalid_argument("writeGltf: portal " + p.name + " names a cell that does not exist");
      if (portalMaterial < 0) portalMaterial = helperMaterial("cpgi_portal", {0.2f, 0.6f, 1.0f, 0.3f});
      std::string name = "portal:" + g.cells[p.cellA].name + ":" + g.cells[p.cellB].name;
      for (int n = 1; used.count(name); ++n) {  // the reader ignores Blender's ".001" suffix
        char suffix[8];
        std::snprintf(suffix, sizeof suffix, ".%03d", n % 1000);
        name = "portal:" + g.cells[p.cellA].name + ":" + g.cells[p.cellB].name + suffix;
      }
      used.insert(name);
      std::array<glm::vec3, 4> c = p.corners;
      glm::vec3 newell(0.0f);
      for (int i = 0; i < 4; ++i) newell += glm::cross(c[i], c[(i + 1) % 4]);
      if (glm::dot(newell, p.normal) < 0.0f) std::swap(c[1], c[3]), newell = -newell;
      const glm::vec3 n = glm::length(newell) > 0.0f ? glm::normalize(newell) : p.normal;
      const std::vector<glm::vec3> pos(c.begin(), c.end());
      const std::vector<glm::vec3> nrm(4, n);
      json attributes = {{"POSITION", b_.addVec3(pos, true)}, {"NORMAL", b_.addVec3(nrm, false)}};
      json prim = {{"attributes", attributes},
                   {"indices", b_.addIndices({0, 1, 2, 0, 2, 3})},
                   {"material", portalMaterial},
                   {"mode", 4}};
      const int mesh = b_.push("meshes", {{"name", name}, {"primitives", json::array({prim})}});
      sceneRoots_.push_back(b_.push("nodes", {{"name", name}, {"mesh", mesh}}));
    }
    int volumeMaterial = -1;
    for (const Cell& cell : g.cells) {
      if (cell.volume.empty()) continue;
      if (volumeMaterial < 0) volumeMaterial = helperMaterial("cpgi_cellvolume", {1.0f, 0.8f, 0.2f, 0.1f});
      std::vector<glm::vec3> pos, nrm;
      for (const Triangle& t : cell.volume)
        for (int k = 0; k < 3; ++k) pos.push_back(t.p[k]), nrm.push_back(t.geometricNormal());
      json attributes = {{"POSITION", b_.addVec3(pos, true)}, {"NORMAL", b_.addVec3(nrm, false)}};
      json prim = {{"attributes", attributes}, {"material", volumeMaterial}, {"mode", 4}};
      const std::string name = "cellvolume:" + cell.name;
      const int mesh = b_.push("meshes", {{"name", name}, {"primitives", json::array({prim})}});
      sceneRoots_.push_back(b_.push("nodes", {{"name", name}, {"mesh", mesh}}));
    }
  }

  // The scene's seal (Scene::seal) as one `seal:` mesh, so that the decomposition of the file written finds
  // the same walls; translucent like the other helpers.
  void writeSeal() {
    if (scene_.seal.empty()) return;
    std::vector<glm::vec3> pos, nrm;
    for (const Triangle& t : scene_.seal)
      for (int k = 0; k < 3; ++k) pos.push_back(t.p[k]), nrm.push_back(t.geometricNormal());
    json attributes = {{"POSITION", b_.addVec3(pos, true)}, {"NORMAL", b_.addVec3(nrm, false)}};
    json prim = {{"attributes", attributes},
                 {"material", helperMaterial("cpgi_seal", {0.5f, 0.5f, 0.5f, 0.1f})},
                 {"mode", 4}};
    const std::string name = "seal:solids";
    const int mesh = b_.push("meshes", {{"name", name}, {"primitives", json::array({prim})}});
    sceneRoots_.push_back(b_.push("nodes", {{"name", name}, {"mesh", mesh}}));
  }

  void writeCameras() {
    for (const Camera& cam : scene_.cameras) {
      const glm::vec3 forward = glm::normalize(cam.forward);
      glm::vec3 right = glm::cross(forward, cam.up);
      if (!(glm::length(right) > 1e-6f))  // up along forward: any perpendicular will do
        right = glm::cross(forward, std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
      right = glm::normalize(right);
      const glm::vec3 up = glm::cross(right, forward);
      // The camera looks down its -Z with +Y up.
      const glm::quat q = glm::normalize(glm::quat_cast(glm::mat3(right, up, -forward)));
      const int camera = b_.push(
          "cameras", {{"name", cam.name},
                      {"type", "perspective"},
                      {"perspective", {{"yfov", cam.yfov}, {"aspectRatio", cam.aspect}, {"znear", 0.01}}}});
      sceneRoots_.push_back(b_.push("nodes", {{"name", cam.name.empty() ? "camera" : cam.name},
                                              {"camera", camera},
                                              {"translation", vec(cam.position)},
                                              {"rotation", {q.x, q.y, q.z, q.w}}}));
    }
  }

  // KHR_lights_punctual back in the file's units (candela, lux): colour × intensity with the brightest
  // channel as the intensity, so loadScene reads the same light back.
  void writeLights() {
    if (scene_.lights.empty()) return;
    json lights = json::array();
    for (const PunctualLight& l : scene_.lights) {
      const float peak = std::max({l.intensity.r, l.intensity.g, l.intensity.b});
      const glm::vec3 colour = peak > 0.0f ? l.intensity / peak : glm::vec3(1.0f);
      json light = {{"name", l.name}, {"color", vec(colour)}, {"intensity", double(peak) * kLumensPerWatt}};
      if (l.range > 0.0f) light["range"] = l.range;
      switch (l.kind) {
        case PunctualLight::Kind::Point:
          light["type"] = "point";
          break;
        case PunctualLight::Kind::Spot:
          light["type"] = "spot";
          light["spot"] = {{"innerConeAngle", l.innerCone}, {"outerConeAngle", l.outerCone}};
          break;
        case PunctualLight::Kind::Directional:
          light["type"] = "directional";
          break;
      }
      const int index = static_cast<int>(lights.size());
      lights.push_back(light);
      // The light shines down its node's -Z: the rotation taking -Z to the direction.
      const glm::quat q = glm::quat(glm::vec3(0, 0, -1), glm::normalize(l.direction));
      sceneRoots_.push_back(
          b_.push("nodes", {{"name", l.name.empty() ? "light" : l.name},
                            {"translation", vec(l.position)},
                            {"rotation", {q.x, q.y, q.z, q.w}},
                            {"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}}));
    }
    b_.doc["extensions"]["KHR_lights_punctual"] = {{"lights", lights}};
    b_.useExtension("KHR_lights_punctual");
  }

  const Scene& scene_;
  const GltfWriteOptions& options_;
  GltfBuilder b_;
  Tree tree_;
  json sceneRoots_ = json::array();
  std::map<int, int> textureIndex_;     // scene texture → texture written
  std::map<uint32_t, int> imageIndex_;  // scene image → image written
  int lightmapSampler_ = -1;
  int lightmap_ = -1;                                        // the one lightmap's texture
  std::vector<int> objectTextures_;                          // per object lightmap, its texture
  std::map<std::pair<uint32_t, int>, int> objectMaterials_;  // (material, object lightmap) → material
};

}  // namespace

void writeGltf(const std::string& path, const Scene& scene, const GltfWriteOptions& options) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".glb" && ext != ".gltf") throw InputError(path, "a glTF output must end in .glb or .gltf");
  writeFileAtomically(path, SceneWriter(scene, options).write(ext == ".glb"));
}

}  // namespace cpgi
