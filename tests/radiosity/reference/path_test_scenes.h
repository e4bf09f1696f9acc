// Closed boxes with a material per face, and sample points laid on them, for the reference tracer tests.
#pragma once

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/reference/reference_tracer.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi::pathtest {

struct Face {
  glm::vec3 origin, u, v;  ///< u × v is the face's normal
  uint32_t material;
};

/// The six inward-facing faces of the box [0, size]³; `materials[k]` for face k
/// (floor z=0, ceiling z=size, x=0, x=size, y=0, y=size).
inline std::vector<Face> boxFaces(float s, const std::array<uint32_t, 6>& materials) {
  return {{{0, 0, 0}, {s, 0, 0}, {0, s, 0}, materials[0]}, {{0, 0, s}, {0, s, 0}, {s, 0, 0}, materials[1]},
          {{0, 0, 0}, {0, s, 0}, {0, 0, s}, materials[2]}, {{s, 0, 0}, {0, 0, s}, {0, s, 0}, materials[3]},
          {{0, 0, 0}, {0, 0, s}, {s, 0, 0}, materials[4]}, {{0, s, 0}, {s, 0, 0}, {0, 0, s}, materials[5]}};
}

inline void addFaces(Scene& scene, const std::vector<Face>& faces) {
  for (const Face& f : faces) testing::addRect(scene, f.origin, f.u, f.v, f.material);
}

/// k × k sample points at cell centres of each face, with the face's material.
inline std::vector<SamplePoint> facePoints(const Scene& scene, const std::vector<Face>& faces, int k) {
  std::vector<SamplePoint> points;
  for (const Face& f : faces)
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        const Material& m = scene.materials[f.material];
        points.push_back({f.origin + (i + 0.5f) / k * f.u + (j + 0.5f) / k * f.v,
                          glm::normalize(glm::cross(f.u, f.v)), m.albedo, m.emission});
      }
  return points;
}

/// Points on a grey (albedo 0.5) floor at y = 0 facing +y (Y up), at every (x, z) of the two lists.
inline std::vector<SamplePoint> floorPoints(std::initializer_list<float> xs,
                                            std::initializer_list<float> zs) {
  std::vector<SamplePoint> points;
  for (float x : xs)
    for (float z : zs) points.push_back({{x, 0.0f, z}, {0, 1, 0}, glm::vec3(0.5f), glm::vec3(0.0f)});
  return points;
}

}  // namespace cpgi::pathtest
