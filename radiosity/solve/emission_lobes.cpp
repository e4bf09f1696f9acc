#include "radiosity/solve/emission_lobes.h"

#include <algorithm>
#include <cmath>

namespace cpgi {

glm::vec4 arrivalMoment(const glm::vec3& omega, const glm::vec3& nFar, float weight) {
  const glm::vec3 u = omega - glm::dot(omega, nFar) * nFar;
  return glm::vec4(weight * (u + glm::dot(u, u) * nFar), weight);
}

glm::vec4 fitEmissionLobe(const glm::vec4& moments, const glm::vec3& n, float minWidth) {
  if (!(moments.w > 0.0f)) return glm::vec4(0.0f);
  const glm::vec3 v = glm::vec3(moments) / moments.w;
  const glm::vec3 m = v - glm::dot(v, n) * n;  // E[u]
  const float mm = glm::dot(m, m);
  const float m2 = std::clamp(glm::dot(v, n), mm, 1.0f);  // E|u|², at least |E[u]|²
  // τ²: the lobe's variance in u summed over both axes; below ½ (a Lambertian's) or the fit degenerates.
  const float tauMin2 = std::min(2.0f * minWidth * minWidth, 0.45f);
  // a² (1 − 2τ²) − a (1 − 2 M2) − 2|m|² = 0, the root in [0, ∞).
  const double A = 1.0 - 2.0 * tauMin2, B = 1.0 - 2.0 * m2, C = 2.0 * mm;
  double a = (B + std::sqrt(B * B + 4.0 * A * C)) / (2.0 * A);
  glm::vec3 u0;
  float tau2 = tauMin2;
  if (a >= 1.0) {
    a = 1.0;  // all of it in the lobe, and the lobe wider than the narrowest
    u0 = m;
    tau2 = std::max(m2 - mm, tauMin2);
  } else {
    if (!(a > 1e-6)) return glm::vec4(0.0f);
    u0 = m / float(a);
  }
  float r2 = glm::dot(u0, u0);
  if (r2 > 0.98f) u0 *= std::sqrt(0.98f / r2), r2 = 0.98f;  // keep the centre off the horizon
  // To gnomonic coordinates: s = u / √(1 − |u|²); the Jacobian's radial and tangential stretches are
  // (1 − r²)^(−3/2) and (1 − r²)^(−1/2), so an isotropic width scales by their geometric mean (1 − r²)^(−1).
  const float k = 1.0f - r2;
  const glm::vec3 s0 = u0 / std::sqrt(k);
  const float sigma2 = std::min(0.5f * tau2 / (k * k), 1e4f);
  return glm::vec4(s0 + float(a) * n, sigma2);
}

float emissionLobeFactor(const glm::vec4& lobe, const glm::vec3& n, const glm::vec3& omega, float blur2) {
  const float c = glm::dot(omega, n);
  if (c <= 0.0f) return 0.0f;
  const float a = glm::dot(glm::vec3(lobe), n);
  if (!(a > 0.0f) || !(lobe.w > 0.0f)) return 1.0f;
  const glm::vec3 s0 = glm::vec3(lobe) - a * n;
  const glm::vec3 s = omega / c - n;
  const glm::vec3 d = s - s0;
  const float c2 = c * c, sigma2 = lobe.w + blur2;
  return (1.0f - a) + a * std::exp(-glm::dot(d, d) / (2.0f * sigma2)) / (2.0f * sigma2 * c2 * c2);
}

std::vector<glm::vec4> fitEmissionLobes(const std::vector<glm::vec4>& moments, const LightmapAtlas& atlas,
                                        float minWidth) {
  std::vector<glm::vec4> lobes(atlas.texelCount(), glm::vec4(0.0f));
  if (moments.empty()) return lobes;
  for (size_t i = 0; i < lobes.size(); ++i)
    if (atlas.patch[i] >= 0) lobes[i] = fitEmissionLobe(moments[i], atlas.normal[i], minWidth);
  return lobes;
}

}  // namespace cpgi
