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

namespace cpgi {

void SurfaceUV::fit(const std::array<glm::vec3, 3>& p, const std::array<glm::vec2, 3>& uv, int set) {
  if (sets == 0) origin = p[0];
  // Over the plane, p = p0 + a·e1 + b·e2: a and b by the Gram matrix of the edges, whose gradients
  // carry each coordinate's change along the two edges. Relative to `origin`, which another set may
  // have placed at this same corner.
  const glm::dvec3 e1 = glm::dvec3(p[1]) - glm::dvec3(p[0]), e2 = glm::dvec3(p[2]) - glm::dvec3(p[0]);
  const double g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  glm::dvec3 gradA(0.0), gradB(0.0);
  if (det > 0.0) gradA = (g22 * e1 - g12 * e2) / det, gradB = (g11 * e2 - g12 * e1) / det;
  const glm::dvec3 fromOrigin = glm::dvec3(p[0]) - glm::dvec3(origin);
  for (int c = 0; c < 2; ++c) {
    const double d1 = double(uv[1][c]) - uv[0][c], d2 = double(uv[2][c]) - uv[0][c];
    const glm::dvec3 g = d1 * gradA + d2 * gradB;
    gradient[size_t(2 * set + c)] = glm::vec3(g);
    atOrigin[2 * set + c] = float(double(uv[0][c]) - glm::dot(g, fromOrigin));
  }
  sets = uint8_t(sets | (1u << set));
}

glm::vec2 SurfaceUV::at(const glm::vec3& q, int set) const {
  const glm::vec3 d = q - origin;
  return {atOrigin[2 * set] + glm::dot(gradient[size_t(2 * set)], d),
          atOrigin[2 * set + 1] + glm::dot(gradient[size_t(2 * set + 1)], d)};
}

}  // namespace cpgi
