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
  std::array<glm::vec3, 3> p{};
  std::array<glm::vec3, 3> n{};  ///< per-vertex normals; the geometric normal where the file has none
  uint32_t material = 0;         ///< index into Scene::materials
  uint32_t node = 0;             ///< index into Scene::nodePaths

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
  /// Slash-joined glTF node names from the root ("building/cell:A/walls"); OBJ: the object/group name.
  std::vector<std::string> nodePaths;
  std::vector<Camera> cameras;
  std::vector<PunctualLight> lights;  ///< KHR_lights_punctual point, spot and directional lights
  Sky sky;  ///< the surroundings' light (core/sky.h): none unless a command is asked for one (--sky)

  Bounds bounds() const;
  /// Total emitted power, W per channel: Σ emission × area over emissive triangles.
  glm::vec3 emittedPower() const;
  /// Whether anything lights the scene: an emissive triangle, a punctual light with some intensity, or the
  /// sky.
  bool hasLight() const;
};

}  // namespace cpgi
