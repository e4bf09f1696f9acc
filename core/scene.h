// The passive scene description every back end builds from (pbrt-v4's split of description and solver):
// a triangle soup in metres with materials, the glTF node each triangle came from, and cameras.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/sky.h"

namespace cpgi {

/// A diffuse material. Units follow design.md §3.
struct Material {
  std::string name;
  glm::vec3 albedo{0.5f};    ///< reflectance per channel, in [0, 1]
  glm::vec3 emission{0.0f};  ///< emitted radiosity, W/m² per channel (the thesis's "100 units")
  bool isEmitter() const { return emission.r > 0.0f || emission.g > 0.0f || emission.b > 0.0f; }
};

/// One triangle, positions and shading normals already in world space (node transforms applied).
struct Triangle {
  static constexpr uint32_t kNoUV = 0xFFFFFFFFu;
  std::array<glm::vec3, 3> p{};
  std::array<glm::vec3, 3> n{};  ///< per-vertex normals; the geometric normal where the file has none
  uint32_t material = 0;         ///< index into Scene::materials
  uint32_t node = 0;             ///< index into Scene::nodePaths
  /// Index into SceneLooks::uvs: the file's texture coordinates over this triangle; kNoUV: none. Pieces of
  /// a triangle split on a portal's plane keep their source's, which holds for any point of its plane.
  uint32_t uv = kNoUV;

  glm::vec3 geometricNormal() const;  ///< unit normal by the winding order; zero for a degenerate triangle
  float area() const;
  glm::vec3 centroid() const { return (p[0] + p[1] + p[2]) / 3.0f; }
};

/// A pinhole camera taken from the scene file (glTF perspective cameras) or made up by a tool.
struct Camera {
  std::string name;
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  ///< unit view direction
  glm::vec3 up{0.0f, 1.0f, 0.0f};        ///< unit, orthogonal to forward
  float yfov = 1.0f;                     ///< vertical field of view, radians
  float aspect = 4.0f / 3.0f;            ///< width / height
};

/// A KHR_lights_punctual light in world space, in cpgi's radiometric units: the file's candela and lux are
/// divided by 683 lm/W (README, "Light units"; core/lights.h evaluates it).
struct PunctualLight {
  enum class Kind { Point, Spot, Directional };
  Kind kind = Kind::Point;
  std::string name;
  glm::vec3 position{0.0f};                ///< metres (point, spot)
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< unit; where the light travels (spot axis, directional rays)
  /// Point and spot: radiant intensity, W/sr per channel (a spot's, on its axis). Directional: irradiance on
  /// a surface facing the light, W/m² per channel.
  glm::vec3 intensity{0.0f};
  float innerCone = 0.0f;       ///< spot: full intensity within this angle of the axis, radians
  float outerCone = 0.785398f;  ///< spot: no light beyond this angle, radians; inner < outer ≤ π/2
  float range = 0.0f;  ///< point and spot: metres where glTF's smooth window reaches 0; 0 = unlimited
};

/// An image a material's texture shows, as the file holds it (PNG or JPEG bytes), kept for the glb written
/// for engines; the solve uses only its mean colour (Material::albedo).
struct SurfaceImage {
  std::string name;
  std::string mimeType;  ///< "image/png" or "image/jpeg"
  std::string bytes;
};

/// A glTF texture: its image and its sampler in glTF's codes (filters −1: unset).
struct SurfaceTexture {
  uint32_t image = 0;  ///< index into SceneLooks::images
  int magFilter = -1, minFilter = -1, wrapS = 10497, wrapT = 10497;
};

/// How a material looks to an engine beyond the albedo the solve uses (that is baseColorFactor times its
/// texture's mean): the file's own factors and textures (indices into SceneLooks::textures, −1: none, each
/// read through TEXCOORD_0).
struct MaterialLook {
  glm::vec4 baseColorFactor{1.0f};
  int baseColorTexture = -1;
  int normalTexture = -1;
  float normalScale = 1.0f;
  int emissiveTexture = -1;
  float metallicFactor = 0.0f, roughnessFactor = 1.0f;
  bool doubleSided = false;
};

/// A triangle's texture coordinates as affine maps of the world position over its plane, so that any piece
/// of it has them: uv(p) = atOrigin + (gradient · (p − origin)) per coordinate. Set 0 is glTF's TEXCOORD_0
/// (the material's textures), set 1 its TEXCOORD_1 (an artist's lightmap coordinates).
struct SurfaceUV {
  glm::vec3 origin{0.0f};
  std::array<glm::vec3, 4> gradient{};  ///< of u0, v0, u1, v1 per metre
  glm::vec4 atOrigin{0.0f};             ///< u0, v0, u1, v1 at origin
  uint8_t sets = 0;                     ///< bit 0: set 0 given; bit 1: set 1 given

  /// The map through the corners `p` with coordinates `uv` in `set` (added to the sets already held).
  void fit(const std::array<glm::vec3, 3>& p, const std::array<glm::vec2, 3>& uv, int set);
  glm::vec2 at(const glm::vec3& q, int set) const;
  bool has(int set) const { return (sets >> set) & 1; }
};

/// What the scene's file gives for engines beyond what the solve reads: images, textures, each material's
/// look and the triangles' texture coordinates. Empty for a file without them (an OBJ, a raw model).
struct SceneLooks {
  std::vector<SurfaceImage> images;
  std::vector<SurfaceTexture> textures;
  std::vector<MaterialLook> materials;  ///< per Scene::materials entry, or empty
  std::vector<SurfaceUV> uvs;           ///< Triangle::uv indexes it
};

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};
  void extend(const glm::vec3& q) { lo = glm::min(lo, q), hi = glm::max(hi, q); }
  bool empty() const { return lo.x > hi.x; }
  glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
};

struct Scene {
  std::vector<Material> materials;
  std::vector<Triangle> triangles;
  /// The pieces of faces the contact cuts dropped as lying inside a solid (core/contact_cuts.h): neither
  /// drawn nor lit, yet where the solid's surface runs. The decomposition voxelizes them with `triangles`, so
  /// that its empty space is that of the faces whole: a piece judged buried next to a room would otherwise
  /// open a hole in the voxels' walls.
  std::vector<Triangle> buriedPieces;
  /// The solid matter that closes the scene where no face is drawn (`seal:` meshes, design.md §3: a game
  /// level's brushes as closed solids): voxelized by the decomposition as walls, never drawn nor lit.
  std::vector<Triangle> seal;
  /// Slash-joined glTF node names from the root ("building/cell:A/walls"); OBJ: the object/group name.
  std::vector<std::string> nodePaths;
  std::vector<Camera> cameras;
  std::vector<PunctualLight> lights;  ///< KHR_lights_punctual point, spot and directional lights
  Sky sky;           ///< the surroundings' light (core/sky.h): none unless a command is asked for one (--sky)
  SceneLooks looks;  ///< the file's textures and texture coordinates, for the glb written for engines

  Bounds bounds() const;
  /// Total emitted power, W per channel: Σ emission × area over emissive triangles.
  glm::vec3 emittedPower() const;
  /// Whether anything lights the scene: an emissive triangle, a punctual light with some intensity, or the
  /// sky.
  bool hasLight() const;
};

}  // namespace cpgi
