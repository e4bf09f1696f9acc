// Embree 3 ray casting over every scene triangle, for the CPU reference path tracer and the view renderer.
// Nothing here is shared with the GPU solver's item buffer: it is the independent visibility that
// design.md §5 asks the reference to have.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

struct RTCDeviceTy;
struct RTCSceneTy;

namespace cpgi {

class RayScene {
 public:
  /// Builds a robust, high-quality BVH of all triangles (degenerate ones never hit). Throws SystemError
  /// when Embree cannot start. The Scene must outlive nothing: the triangles are copied.
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  struct Hit {
    int32_t triangle = -1;     ///< index into Scene::triangles, -1 for a miss
    float t = 0.0f;            ///< distance along the (unit) direction
    float u = 0.0f, v = 0.0f;  ///< barycentrics: p = (1−u−v)·p0 + u·p1 + v·p2
    explicit operator bool() const { return triangle >= 0; }
  };

  /// Nearest hit on (tnear, tfar); where a triangle seen from behind and one seen from the front lie at
  /// the same distance (within 1e-4 of it), the front one. Thread-safe.
  Hit intersect(const glm::vec3& origin, const glm::vec3& direction, float tnear = 0.0f,
                float tfar = 3.0e38f) const;
  /// True when anything lies on (tnear, tfar). Thread-safe.
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar) const;

  /// A segment to test: from `origin` along the unit `direction` over (0, length).
  struct Segment {
    glm::vec3 origin{0.0f};
    float length = 0.0f;
    glm::vec3 direction{0.0f};
  };
  /// For every segment, whether anything lies on it (hidden[i] = 1), traced as one coherent stream: Embree
  /// packs segments that start near each other into packets, which costs less than one call per segment
  /// (radiosity/cpu/ray_shot.cpp). Thread-safe; hidden.size() == segments.size().
  void occluded(std::span<const Segment> segments, std::span<uint8_t> hidden) const;

  /// Length of the scene's bounding-box diagonal (metres); ray offsets scale with it.
  float diagonal() const { return diagonal_; }

 private:
  RTCDeviceTy* device_ = nullptr;
  RTCSceneTy* scene_ = nullptr;
  float diagonal_ = 0.0f;
  std::vector<glm::vec3> normals_;  ///< per triangle, by its winding (Triangle::geometricNormal)
};

}  // namespace cpgi
