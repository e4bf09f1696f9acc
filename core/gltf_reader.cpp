// glTF 2.0 (.glb, .gltf) → RawScene. tinygltf parses; everything it hands back is bounds-checked here
// before use, because a fuzzed file must end in an InputError, never in a crash.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

// Texture images are decoded by core/texture_image.h, never by tinygltf's stb_image (keepImageEncoded).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gltf_file_checks.h"
#include "core/lights.h"
#include "core/scene_files.h"
#include "core/scene_io_detail.h"
#include "core/texture_image.h"

namespace cpgi::detail {
namespace {

std::string firstLine(std::string s) {
  while (!s.empty() && (s.front() == '\n' || s.front() == ' ')) s.erase(s.begin());
  const size_t nl = s.find('\n');
  if (nl != std::string::npos) s.resize(nl);
  while (!s.empty() && (s.back() == '.' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
  return s;
}

std::string modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    default:
      return std::to_string(mode);
  }
}

// Images stay encoded until a material uses them (textureMean): an unused 16k² PNG costs its file
// size, not gigabytes. width < 0 marks the bytes as encoded.
bool keepImageEncoded(tinygltf::Image* image, const int, std::string* err, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (size <= 0) {
    if (err) *err += "an image has no bytes";
    return false;
  }
  image->image.assign(bytes, bytes + size);
  image->width = image->height = image->component = -1;
  return true;
}

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model, const ReferencedFiles& files,
             const LoadOptions& options)
      : path_(path), m_(model), files_(files), maxTriangles_(options.maxTriangles), options_(options) {}

  RawScene read() {
    for (const std::string& ext : m_.extensionsRequired)
      if (ext != "KHR_materials_emissive_strength" && ext != "KHR_materials_unlit" &&
          ext != "KHR_lights_punctual")
        fail("requires the glTF extension " + ext + ", which cpgi does not support");
    materialIndex_.assign(m_.materials.size(), -1);

    std::vector<int> roots;
    if (m_.defaultScene >= 0 && m_.defaultScene < static_cast<int>(m_.scenes.size())) {
      roots = m_.scenes[m_.defaultScene].nodes;
    } else if (!m_.scenes.empty()) {
      roots = m_.scenes[0].nodes;
    } else {
      std::vector<char> isChild(m_.nodes.size(), 0);
      for (const tinygltf::Node& n : m_.nodes)
        for (int c : n.children)
          if (c >= 0 && c < static_cast<int>(m_.nodes.size())) isChild[c] = 1;
      for (size_t i = 0; i < m_.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    visited_.assign(m_.nodes.size(), 0);
    for (int r : roots) visit(r, glm::dmat4(1.0), "", -1, nullptr);
    return std::move(raw_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path_, problem); }

  std::string nodeName(int i) const {
    const std::string& n = m_.nodes[i].name;
    return n.empty() ? "node" + std::to_string(i) : n;
  }

  glm::dmat4 localMatrix(const tinygltf::Node& n, const std::string& name) const {
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) fail("node '" + name + "': matrix must have 16 numbers");
      glm::dmat4 m;
      std::memcpy(glm::value_ptr(m), n.matrix.data(), sizeof(double) * 16);  // both column-major
      return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) fail("node '" + name + "': translation must have 3 numbers");
      t = glm::translate(glm::dmat4(1.0), glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) fail("node '" + name + "': rotation must have 4 numbers");
      glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      const double len = glm::length(q);
      if (!(len > 0.0) || !std::isfinite(len)) fail("node '" + name + "': rotation is not a unit quaternion");
      r = glm::mat4_cast(q / len);
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) fail("node '" + name + "': scale must have 3 numbers");
      s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    }
    return t * r * s;
  }

  // The recursion is bounded by kMaxNodeDepth (a fuzzed file may nest 100,000 nodes), and every node
  // path by kMaxNodePath: each mesh node keeps its whole path, so deep nesting would otherwise cost
  // memory quadratic in the depth.
  static constexpr int kMaxNodeDepth = 256;
  static constexpr size_t kMaxNodePath = 4096;

  void visit(int index, const glm::dmat4& parent, const std::string& parentPath, int cell,
             RawScene::TaggedMesh* tagged, int depth = 0) {
    if (index < 0 || index >= static_cast<int>(m_.nodes.size()))
      fail("a scene or node refers to node " + std::to_string(index) + ", which does not exist");
    if (visited_[index]) fail("node '" + nodeName(index) + "' appears twice in the node hierarchy");
    if (depth >= kMaxNodeDepth)
      fail("node '" + nodeName(index) + "': the node hierarchy is deeper than " +
           std::to_string(kMaxNodeDepth) + " levels");
    visited_[index] = 1;
    const tinygltf::Node& node = m_.nodes[index];
    const std::string name = nodeName(index);
    if (parentPath.size() + 1 + name.size() > kMaxNodePath)
      fail("node '" + name + "': its path from the scene root is longer than " +
           std::to_string(kMaxNodePath) + " characters");
    const std::string path = parentPath.empty() ? name : parentPath + "/" + name;
    const glm::dmat4 world = parent * localMatrix(node, name);

    const CellTag tag = parseCellTag(path_, name);
    std::vector<RawScene::TaggedMesh>* taggedList = nullptr;
    switch (tag.kind) {
      case CellTag::Kind::Cell:
        if (cell >= 0) fail(name + ": is inside cell:" + raw_.cellNames[cell] + " (cells cannot nest)");
        if (tagged) fail(name + ": is inside " + tagged->node);
        if (std::find(raw_.cellNames.begin(), raw_.cellNames.end(), tag.a) != raw_.cellNames.end())
          fail(name + ": two nodes define the same cell");
        cell = raw_.cellIndex(tag.a);
        break;
      case CellTag::Kind::Portal:
        taggedList = &raw_.portals;
        break;
      case CellTag::Kind::CellVolume:
        taggedList = &raw_.volumes;
        break;
      case CellTag::Kind::Seal:
        taggedList = &raw_.seals;
        break;
      case CellTag::Kind::None:
        break;
    }
    if (taggedList) {
      if (tagged) fail(name + ": is inside " + tagged->node);
      taggedList->push_back({name, tag, {}});
      tagged = &taggedList->back();
    }

    if (node.camera >= 0) addCamera(node.camera, world, name);
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end())
      addLight(it->second, world, name);
    if (node.mesh >= 0) {
      if (node.mesh >= static_cast<int>(m_.meshes.size()))
        fail("node '" + name + "': mesh index out of range");
      requireReadingTime(path_, options_, std::to_string(meshesRead_) + " meshes read");
      ++meshesRead_;
      addMesh(m_.meshes[node.mesh], world, path, cell, tagged);
    }
    // Nothing below a tagged node can add another tagged node, so `tagged` stays valid.
    for (int child : node.children) visit(child, world, path, cell, tagged, depth + 1);
  }

  void addCamera(int index, const glm::dmat4& world, const std::string& nodeName) {
    if (index >= static_cast<int>(m_.cameras.size()))
      fail("node '" + nodeName + "': camera index out of range");
    const tinygltf::Camera& c = m_.cameras[index];
    if (c.type != "perspective") {
      raw_.warnings.push_back("camera of node '" + nodeName + "' is not perspective; ignored");
      return;
    }
    Camera cam;
    cam.name = c.name.empty() ? nodeName : c.name;
    cam.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
    const glm::vec3 forward(world * glm::dvec4(0, 0, -1, 0));
    const glm::vec3 up(world * glm::dvec4(0, 1, 0, 0));
    if (!(glm::length(forward) > 0.0f) || !std::isfinite(glm::length(forward)) ||
        !std::isfinite(glm::length(cam.position)))
      fail("node '" + nodeName + "': camera transform is degenerate");
    cam.forward = glm::normalize(forward);
    // A scale of 0 along y (or a shear onto the view axis) leaves no up direction: the camera's rays
    // would be NaN, which the renderers (Embree) assert on. Refused here with the node named.
    const glm::vec3 upAcross = up - glm::dot(up, cam.forward) * cam.forward;
    if (!(glm::length(upAcross) > 1e-6f * glm::length(forward)) || !std::isfinite(glm::length(upAcross)))
      fail("node '" + nodeName + "': camera transform is degenerate (its up axis is null or along the view)");
    cam.up = glm::normalize(upAcross);
    cam.yfov = static_cast<float>(c.perspective.yfov);
    cam.aspect =
        c.perspective.aspectRatio > 0.0 ? static_cast<float>(c.perspective.aspectRatio) : 4.0f / 3.0f;
    if (!(cam.yfov > 0.0f && cam.yfov < 3.14159f)) fail("camera '" + cam.name + "': yfov must be in (0, pi)");
    if (!(cam.aspect >= 1e-3f && cam.aspect <= 1e3f))
      fail("camera '" + cam.name + "': aspectRatio must be within [0.001, 1000]");
    raw_.scene.cameras.push_back(cam);
  }

  static std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  // A KHR_lights_punctual light placed by its node: at the node's origin, shining down its -Z. The file's
  // candela (point, spot) and lux (directional) become W/sr and W/m² (core/lights.h, kLumensPerWatt).
  void addLight(const tinygltf::Value& reference, const glm::dmat4& world, const std::string& nodeName) {
    const std::string what = "node '" + nodeName + "'";
    const tinygltf::Value& index = member(reference, "light");
    if (!index.IsNumber()) fail(what + ": KHR_lights_punctual without a light index");
    const double i = index.GetNumberAsDouble();
    if (!(i >= 0.0 && i < double(m_.lights.size())) || i != std::floor(i))
      fail(what + ": light " + number(i) + " does not exist");
    const tinygltf::Light& gl = m_.lights[size_t(i)];
    PunctualLight light;
    light.name = gl.name.empty() ? nodeName : gl.name;
    const std::string lightWhat = "light '" + printable(light.name) + "'";
    if (gl.type == "point")
      light.kind = PunctualLight::Kind::Point;
    else if (gl.type == "spot")
      light.kind = PunctualLight::Kind::Spot;
    else if (gl.type == "directional")
      light.kind = PunctualLight::Kind::Directional;
    else
      fail(lightWhat + ": unknown type '" + printable(gl.type) + "' (expected point, spot or directional)");
    glm::dvec3 colour(1.0);
    if (!gl.color.empty()) {
      if (gl.color.size() != 3) fail(lightWhat + ": color must have 3 numbers");
      colour = glm::dvec3(gl.color[0], gl.color[1], gl.color[2]);
    }
    for (int c = 0; c < 3; ++c)
      if (!(colour[c] >= 0.0) || !std::isfinite(colour[c]))
        fail(lightWhat + ": color is negative or not finite");
    if (!(gl.intensity >= 0.0) || !std::isfinite(gl.intensity))
      fail(lightWhat + ": intensity " + number(gl.intensity) + " is negative or not finite");
    light.intensity = glm::vec3(colour * gl.intensity / kLumensPerWatt);
    if (!(gl.range >= 0.0) || !std::isfinite(gl.range)) fail(lightWhat + ": range must be a positive number");
    light.range = float(gl.range);
    if (light.kind == PunctualLight::Kind::Spot) {
      const double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle;
      if (!(inner >= 0.0 && inner < outer && outer <= std::acos(-1.0) / 2.0))
        fail(lightWhat + ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
      light.innerCone = float(inner), light.outerCone = float(outer);
    }
    light.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 axis(world * glm::dvec4(0, 0, -1, 0));
    const double length = glm::length(axis);
    if (!std::isfinite(glm::length(light.position)) || !(length > 0.0) || !std::isfinite(length))
      fail(what + ": the transform of " + lightWhat + " is degenerate or not finite");
    light.direction = glm::vec3(axis / length);
    raw_.scene.lights.push_back(light);
  }

  // A checked view of an accessor's bytes.
  struct View {
    const unsigned char* data = nullptr;  // null: all zeros (accessor without bufferView)
    size_t count = 0, stride = 0;
    int componentType = 0, components = 0;
  };

  static constexpr uint64_t kMaxZeroElements = 65536;

  View view(int index, const std::string& what) const {
    if (index < 0 || index >= static_cast<int>(m_.accessors.size()))
      fail(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = m_.accessors[index];
    if (a.sparse.isSparse) fail(what + ": sparse accessors are not supported");
    View v;
    v.count = a.count;
    v.componentType = a.componentType;
    const int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    v.components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    if (componentSize <= 0 || v.components <= 0)
      fail(what + ": accessor " + std::to_string(index) + " has an invalid type");
    const uint64_t elemSize = uint64_t(componentSize) * v.components;
    if (a.bufferView < 0) {
      // All zeros, with no bytes in the file to back them: a 1 KB file could ask for gigabytes.
      if (v.count > kMaxZeroElements)
        fail(what + ": accessor " + std::to_string(index) + " has no bufferView and " +
             std::to_string(v.count) + " elements (all zeros); at most " + std::to_string(kMaxZeroElements) +
             " are accepted");
      return v;
    }
    if (a.bufferView >= static_cast<int>(m_.bufferViews.size()))
      fail(what + ": accessor " + std::to_string(index) + " refers to a bufferView that does not exist");
    const tinygltf::BufferView& bv = m_.bufferViews[a.bufferView];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(m_.buffers.size()))
      fail(what + ": bufferView " + std::to_string(a.bufferView) + " refers to a buffer that does not exist");
    const std::vector<unsigned char>& data = m_.buffers[bv.buffer].data;
    // Every bound is compared against what remains, never added up first: a file may hold offsets and
    // lengths near 2^64 whose sum wraps around to a small number.
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
      fail(what + ": bufferView " + std::to_string(a.bufferView) + " runs past the end of its buffer");
    v.stride = bv.byteStride ? bv.byteStride : elemSize;
    if (v.stride < elemSize)
      fail(what + ": bufferView " + std::to_string(a.bufferView) + " has a stride smaller than its elements");
    if (v.count > 0) {
      const bool fits = a.byteOffset <= bv.byteLength && elemSize <= bv.byteLength - a.byteOffset &&
                        v.count - 1 <= (bv.byteLength - a.byteOffset - elemSize) / v.stride;
      if (!fits) fail(what + ": accessor " + std::to_string(index) + " runs past the end of its bufferView");
    }
    v.data = data.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  std::vector<glm::vec3> readVec3(int index, const std::string& what) const {
    const View v = view(index, what);
    if (v.components != 3 || v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      fail(what + ": expected float VEC3 data");
    std::vector<glm::vec3> out(v.count, glm::vec3(0.0f));
    if (v.data)
      for (size_t i = 0; i < v.count; ++i) std::memcpy(&out[i], v.data + i * v.stride, sizeof(glm::vec3));
    return out;
  }

  /// Float VEC2 data; empty for any other type.
  std::vector<glm::vec2> readFloatVec2(int index, const std::string& what) const {
    const View v = view(index, what);
    if (v.components != 2 || v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) return {};
    std::vector<glm::vec2> out(v.count, glm::vec2(0.0f));
    if (v.data)
      for (size_t i = 0; i < v.count; ++i) std::memcpy(&out[i], v.data + i * v.stride, sizeof(glm::vec2));
    return out;
  }

  /// Texture coordinates: float, or normalized unsigned byte or short (glTF's three kinds); empty for
  /// anything else.
  std::vector<glm::vec2> readTexcoords(int index, const std::string& what) const {
    const View v = view(index, what);
    if (v.components != 2) return {};
    if (v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return readFloatVec2(index, what);
    const bool bytes = v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    if (!bytes && v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) return {};
    if (!m_.accessors[index].normalized) return {};
    std::vector<glm::vec2> out(v.count, glm::vec2(0.0f));
    for (size_t i = 0; v.data && i < v.count; ++i)
      for (int c = 0; c < 2; ++c) {
        const unsigned char* p = v.data + i * v.stride + c * (bytes ? 1 : 2);
        uint16_t s = *p;
        if (!bytes) std::memcpy(&s, p, 2);
        out[i][c] = float(s) / (bytes ? 255.0f : 65535.0f);
      }
    return out;
  }

  std::vector<uint32_t> readIndices(int index, const std::string& what) const {
    const View v = view(index, what);
    if (v.components != 1) fail(what + ": indices must be scalars");
    std::vector<uint32_t> out(v.count, 0);
    if (!v.data) return out;
    for (size_t i = 0; i < v.count; ++i) {
      const unsigned char* p = v.data + i * v.stride;
      switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          out[i] = *p;
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          uint16_t s;
          std::memcpy(&s, p, 2);
          out[i] = s;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
          std::memcpy(&out[i], p, 4);
          break;
        default:
          fail(what + ": indices must be unsigned byte, short or int");
      }
    }
    return out;
  }

  // Linear mean colour of a texture (glTF colour textures are sRGB-encoded), or 1 without one. The image
  // is still encoded (keepImageEncoded); it is decoded here once per image, however many materials use it
  // (a scene may give a hundred materials one 8192² texture).
  glm::vec3 textureMean(int textureIndex, const std::string& what) {
    if (textureIndex < 0) return glm::vec3(1.0f);
    if (textureIndex >= static_cast<int>(m_.textures.size())) fail(what + ": texture index out of range");
    const int source = m_.textures[textureIndex].source;
    if (source < 0 || source >= static_cast<int>(m_.images.size()))
      fail(what + ": texture has no valid image");
    if (auto known = imageMeans_.find(source); known != imageMeans_.end()) return known->second;
    const tinygltf::Image& image = m_.images[source];
    const std::string which = what + ": texture image " + std::to_string(source);
    // tinygltf keeps an image whose file is missing or empty, without bytes, as a glTF may name images
    // no material uses; this one is used.
    if (image.image.empty() && image.bufferView < 0 && files_.missing(image.uri))
      fail(which + " '" + percentDecode(image.uri) + "': no such file");
    if (image.image.empty()) fail(which + " is empty");
    requireReadingTime(path_, options_, std::to_string(imageMeans_.size()) + " texture images decoded");
    const glm::vec3 mean = meanTextureColour(image.image.data(), image.image.size(), path_, which);
    imageMeans_.emplace(source, mean);
    return mean;
  }

  // tinygltf::Value::Get asserts on a value of the wrong type; a file may hold anything there.
  static const tinygltf::Value& member(const tinygltf::Value& object, const std::string& key) {
    static const tinygltf::Value none;
    return object.IsObject() && object.Has(key) ? object.Get(key) : none;
  }

  static bool readNumbers(const tinygltf::Value& v, glm::vec3& out) {
    if (!v.IsArray() || v.ArrayLen() != 3) return false;
    for (int i = 0; i < 3; ++i) {
      if (!v.Get(i).IsNumber()) return false;
      out[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
    }
    return true;
  }

  // A glTF texture read through TEXCOORD_0, as SceneLooks::textures index (−1: none, or one the engine
  // glb cannot carry: another coordinate set, an image neither PNG nor JPEG).
  int lookTexture(int textureIndex, int texCoord, const std::string& what) {
    if (textureIndex < 0 || texCoord != 0) return -1;
    if (textureIndex >= static_cast<int>(m_.textures.size())) fail(what + ": texture index out of range");
    if (auto known = lookTextures_.find(textureIndex); known != lookTextures_.end()) return known->second;
    const tinygltf::Texture& gt = m_.textures[textureIndex];
    if (gt.source < 0 || gt.source >= static_cast<int>(m_.images.size())) return -1;
    SceneLooks& looks = raw_.scene.looks;
    auto image = lookImages_.find(gt.source);
    if (image == lookImages_.end()) {
      const std::vector<unsigned char>& encoded = m_.images[gt.source].image;
      const ImageFormat format = imageFormat(encoded.data(), encoded.size());
      if (format == ImageFormat::Other) return lookTextures_[textureIndex] = -1;
      looks.images.push_back({m_.images[gt.source].name,
                              format == ImageFormat::Png ? "image/png" : "image/jpeg",
                              std::string(encoded.begin(), encoded.end())});
      image = lookImages_.emplace(gt.source, int(looks.images.size() - 1)).first;
    }
    SurfaceTexture texture{uint32_t(image->second)};
    if (gt.sampler >= 0 && gt.sampler < static_cast<int>(m_.samplers.size())) {
      const tinygltf::Sampler& s = m_.samplers[gt.sampler];
      texture.magFilter = s.magFilter, texture.minFilter = s.minFilter;
      texture.wrapS = s.wrapS, texture.wrapT = s.wrapT;
    }
    looks.textures.push_back(texture);
    return lookTextures_[textureIndex] = int(looks.textures.size() - 1);
  }

  // The material as an engine shows it (SceneLooks::materials), beside the albedo the solve reads.
  void addLook(const tinygltf::Material& gm, const Material& mat, const std::string& what) {
    std::vector<MaterialLook>& looks = raw_.scene.looks.materials;
    // A material cpgi made up (the default one) looks as its albedo.
    while (looks.size() + 1 < raw_.scene.materials.size()) {
      MaterialLook plain;
      plain.baseColorFactor = glm::vec4(raw_.scene.materials[looks.size()].albedo, 1.0f);
      looks.push_back(plain);
    }
    MaterialLook look;
    const auto& pbr = gm.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4)
      look.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                                       pbr.baseColorFactor[3]);
    look.baseColorTexture = lookTexture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, what);
    // Without its texture, the base colour is the albedo baked with (the texture's mean folded in).
    if (look.baseColorTexture < 0)
      look.baseColorFactor = glm::vec4(mat.albedo, look.baseColorFactor.a), look.baseColorTexture = -1;
    look.normalTexture = lookTexture(gm.normalTexture.index, gm.normalTexture.texCoord, what);
    look.normalScale = float(gm.normalTexture.scale);
    look.emissiveTexture = lookTexture(gm.emissiveTexture.index, gm.emissiveTexture.texCoord, what);
    look.metallicFactor = float(std::clamp(pbr.metallicFactor, 0.0, 1.0));
    look.roughnessFactor = float(std::clamp(pbr.roughnessFactor, 0.0, 1.0));
    look.doubleSided = gm.doubleSided;
    looks.push_back(look);
  }

  uint32_t materialFor(int index) {
    if (index < 0) {
      if (defaultMaterial_ < 0) {
        defaultMaterial_ = static_cast<int>(raw_.scene.materials.size());
        raw_.scene.materials.push_back(Material{"default", glm::vec3(0.5f), glm::vec3(0.0f)});
      }
      return static_cast<uint32_t>(defaultMaterial_);
    }
    if (index >= static_cast<int>(m_.materials.size()))
      fail("material " + std::to_string(index) + " does not exist");
    if (materialIndex_[index] >= 0) return static_cast<uint32_t>(materialIndex_[index]);
    const tinygltf::Material& gm = m_.materials[index];
    Material mat;
    mat.name = gm.name.empty() ? "material" + std::to_string(index) : gm.name;
    const std::string what = "material '" + mat.name + "'";
    const auto& pbr = gm.pbrMetallicRoughness;
    glm::vec3 factor(1.0f);
    if (pbr.baseColorFactor.size() >= 3)
      factor = glm::vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
    mat.albedo = factor * textureMean(pbr.baseColorTexture.index, what);
    glm::vec3 emissive(0.0f);
    if (gm.emissiveFactor.size() >= 3)
      emissive = glm::vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
    if (gm.emissiveTexture.index >= 0) emissive *= textureMean(gm.emissiveTexture.index, what);
    float strength = 1.0f;
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end()) {
      const tinygltf::Value& s = member(it->second, "emissiveStrength");
      if (s.IsNumber()) strength = static_cast<float>(s.GetNumberAsDouble());
    }
    mat.emission = emissive * strength;
    // A baked file (writeGltf with a lightmap) shows light through an unlit texture; the material it
    // was baked with is kept in extras.
    glm::vec3 v;
    if (readNumbers(member(gm.extras, "cpgi_albedo"), v)) mat.albedo = v;
    if (readNumbers(member(gm.extras, "cpgi_emission"), v)) mat.emission = v;
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(mat.albedo[i]) || mat.albedo[i] < 0.0f)
        fail(what + ": base colour is negative or not finite");
      if (!std::isfinite(mat.emission[i]) || mat.emission[i] < 0.0f)
        fail(what + ": emission is negative or not finite");
    }
    materialIndex_[index] = static_cast<int>(raw_.scene.materials.size());
    raw_.scene.materials.push_back(mat);
    addLook(gm, mat, what);
    return static_cast<uint32_t>(materialIndex_[index]);
  }

  void addMesh(const tinygltf::Mesh& mesh, const glm::dmat4& world, const std::string& path, int cell,
               RawScene::TaggedMesh* tagged) {
    const std::string meshName = mesh.name.empty() ? path : mesh.name;
    const glm::mat4 toWorld(world);
    const glm::mat3 normalMatrix(glm::inverseTranspose(glm::dmat3(world)));
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;  // reverses the winding (glTF spec)
    const uint32_t nodeIdx = tagged ? 0 : raw_.nodeIndex(path);
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const tinygltf::Primitive& prim = mesh.primitives[pi];
      const std::string what = "mesh '" + meshName + "' primitive " + std::to_string(pi);
      const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          mode != TINYGLTF_MODE_TRIANGLE_FAN)
        fail(what + ": primitive mode " + modeName(mode) + " is not supported (only triangles)");
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) fail(what + ": has no POSITION attribute");
      const std::vector<glm::vec3> positions = readVec3(pos->second, what + " POSITION");
      std::vector<glm::vec3> normals;
      if (auto nrm = prim.attributes.find("NORMAL"); nrm != prim.attributes.end()) {
        normals = readVec3(nrm->second, what + " NORMAL");
        if (normals.size() != positions.size()) fail(what + ": NORMAL and POSITION counts differ");
      }
      // A baked lightmap's atlas coordinates (our own baked.glb), for `cpgi view`. Other files may store
      // them as normalized integers or not at all: then the scene simply has none.
      std::vector<glm::vec2> lightmapUVs, textureUVs;
      if (auto uv = prim.attributes.find("TEXCOORD_1"); uv != prim.attributes.end() && !tagged) {
        lightmapUVs = readTexcoords(uv->second, what + " TEXCOORD_1");
        if (lightmapUVs.size() != positions.size()) lightmapUVs.clear();
      }
      // The material's texture coordinates, kept for the glb written for engines.
      if (auto uv = prim.attributes.find("TEXCOORD_0"); uv != prim.attributes.end() && !tagged) {
        textureUVs = readTexcoords(uv->second, what + " TEXCOORD_0");
        if (textureUVs.size() != positions.size()) textureUVs.clear();
      }
      std::vector<uint32_t> indices;
      if (prim.indices >= 0) {
        indices = readIndices(prim.indices, what + " indices");
        for (uint32_t i : indices)
          if (i >= positions.size()) fail(what + ": index " + std::to_string(i) + " is out of range");
      } else {
        indices.resize(positions.size());
        for (uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
      }
      // Strips and fans become triangle lists, alternating strip winding kept consistent.
      std::vector<std::array<uint32_t, 3>> corners;
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (size_t i = 0; i + 2 < indices.size(); i += 3)
          corners.push_back({indices[i], indices[i + 1], indices[i + 2]});
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < indices.size(); ++i)
          corners.push_back(i % 2 ? std::array<uint32_t, 3>{indices[i + 1], indices[i], indices[i + 2]}
                                  : std::array<uint32_t, 3>{indices[i], indices[i + 1], indices[i + 2]});
      } else {
        for (size_t i = 1; i + 1 < indices.size(); ++i)
          corners.push_back({indices[0], indices[i], indices[i + 1]});
      }
      const uint32_t material = tagged ? 0 : materialFor(prim.material);
      // Before placing them: each node that instances a mesh places all of its triangles again.
      placed_ += corners.size();
      if (placed_ > maxTriangles_)
        fail("nodes place more than " + std::to_string(maxTriangles_) + " triangles (at " + what +
             "; a mesh instanced by many nodes counts once per node)");
      for (const auto& c : corners) {
        Triangle t;
        for (int k = 0; k < 3; ++k) {
          const int src = mirrored && k > 0 ? 3 - k : k;
          t.p[k] = glm::vec3(toWorld * glm::vec4(positions[c[src]], 1.0f));
          t.n[k] = normals.empty() ? glm::vec3(0.0f) : normalMatrix * normals[c[src]];
        }
        t.material = material;
        t.node = nodeIdx;
        if (tagged) {
          tagged->triangles.push_back(t);
        } else {
          raw_.scene.triangles.push_back(t);
          raw_.cellOfTriangle.push_back(cell);
          std::array<glm::vec2, 3> uv{}, uv0{};
          for (int k = 0; k < 3 && !lightmapUVs.empty(); ++k)
            uv[k] = lightmapUVs[c[mirrored && k > 0 ? 3 - k : k]];
          for (int k = 0; k < 3 && !textureUVs.empty(); ++k)
            uv0[k] = textureUVs[c[mirrored && k > 0 ? 3 - k : k]];
          raw_.lightmapUVs.push_back(uv);
          raw_.textureUVs.push_back(uv0);
          raw_.uvSets.push_back(uint8_t((textureUVs.empty() ? 0 : 1) | (lightmapUVs.empty() ? 0 : 2)));
          raw_.everyLightmapUV = raw_.everyLightmapUV && !lightmapUVs.empty();
        }
      }
    }
  }

  const std::string& path_;
  const tinygltf::Model& m_;
  const ReferencedFiles& files_;
  size_t maxTriangles_;
  const LoadOptions& options_;
  size_t meshesRead_ = 0;  // mesh nodes read so far, for a time limit passing while they are
  size_t placed_ = 0;      // triangles placed so far, tagged meshes included
  RawScene raw_;
  std::vector<int> materialIndex_;
  std::map<int, glm::vec3> imageMeans_;           // by image index: each image is decoded once
  std::map<int, int> lookTextures_, lookImages_;  // glTF texture and image → SceneLooks index
  int defaultMaterial_ = -1;
  std::vector<char> visited_;
};

}  // namespace

RawScene readGltf(const std::string& path, const LoadOptions& options) {
  const std::string bytes = readSceneFile(path, options.maxFileBytes);
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  const bool glbName =
      std::filesystem::path(path).extension() == ".glb" || std::filesystem::path(path).extension() == ".GLB";
  const std::vector<FileUri> uris = glbName || binary
                                        ? checkGltfJson(path, checkGlbContainer(path, bytes), "chunk")
                                        : checkGltfJson(path, bytes, "document");
  if (bytes.size() > 0xFFFFFFFFu) throw InputError(path, "larger than 4 GiB");

  ReferencedFiles files(referencePolicy(path, options), uris);
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&ReferencedFiles::exists, &ReferencedFiles::expand, &ReferencedFiles::read,
                         &ReferencedFiles::refuseWrite, &files});
  loader.SetImageLoader(&keepImageEncoded, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    ok = glbName || binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                         reinterpret_cast<const unsigned char*>(bytes.data()),
                                                         static_cast<unsigned>(bytes.size()), files.folder())
                           : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                                        static_cast<unsigned>(bytes.size()), files.folder());
  } catch (const InputError&) {
    throw;  // a referenced file refused by the policy, already named
  } catch (const std::exception& e) {
    throw InputError(path, std::string("invalid glTF: ") + printable(firstLine(e.what()), 200));
  }
  if (!ok)
    throw InputError(path, "invalid glTF: " + (err.empty() ? std::string("rejected by the parser")
                                                           : printable(firstLine(err), 200)));
  requireReadingTime(path, options, "parsed, no mesh read yet");
  return GltfReader(path, model, files, options).read();
}

}  // namespace cpgi::detail
