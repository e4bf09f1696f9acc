#include "core/scene.h"

namespace cpgi {

glm::vec3 Triangle::geometricNormal() const {
  const glm::vec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
  const float len = glm::length(c);
  return len > 0.0f ? c / len : glm::vec3(0.0f);
}

float Triangle::area() const {
  return 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const Triangle& t : triangles)
    for (const glm::vec3& q : t.p) b.extend(q);
  return b;
}

glm::vec3 Scene::emittedPower() const {
  glm::vec3 power(0.0f);
  for (const Triangle& t : triangles)
    if (t.material < materials.size()) power += materials[t.material].emission * t.area();
  return power;
}

bool Scene::hasLight() const {
  if (sky.lights()) return true;
  const glm::vec3 p = emittedPower();
  if (p.r + p.g + p.b > 0.0f) return true;
  for (const PunctualLight& l : lights)
    if (l.intensity.r + l.intensity.g + l.intensity.b > 0.0f) return true;
  return false;
}

}  // namespace cpgi
