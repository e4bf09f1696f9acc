#pragma once

#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace cpgi {

/// Distance along `d` from `o` to triangle `t`, from either side (Möller–Trumbore), +inf when the ray misses
/// it, runs parallel to it or starts on or past it. For the few rays a stage casts on the CPU without a
/// ray scene (the units' ceilings, the passages' widths); many rays go through Embree (RayScene).
inline float rayTriangleDistance(const glm::vec3& o, const glm::vec3& d, const Triangle& t) {
  constexpr float kMiss = std::numeric_limits<float>::infinity();
  const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
  const glm::vec3 p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-20f) return kMiss;
  const glm::vec3 s = o - t.p[0];
  const float u = glm::dot(s, p) / det;
  if (u < 0.0f || u > 1.0f) return kMiss;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) / det;
  if (v < 0.0f || u + v > 1.0f) return kMiss;
  const float dist = glm::dot(e2, q) / det;
  return dist > 0.0f ? dist : kMiss;
}

}  // namespace cpgi
