#include "radiosity/lightmap/spherical_harmonics.h"

#include <numbers>

namespace cpgi {

std::array<float, 9> shBasis(const glm::vec3& w) {
  const float x = w.x, y = w.y, z = w.z;
  return {kShY00,
          kShY1 * y,
          kShY1 * z,
          kShY1 * x,
          1.092548f * x * y,
          1.092548f * y * z,
          0.315392f * (3.0f * z * z - 1.0f),
          1.092548f * x * z,
          0.546274f * (x * x - y * y)};
}

glm::vec3 shIrradiance(std::span<const glm::vec3> coefficients, const glm::vec3& n) {
  constexpr float pi = std::numbers::pi_v<float>;
  constexpr std::array<float, 9> convolution{pi,     2 * pi / 3, 2 * pi / 3, 2 * pi / 3, pi / 4,
                                             pi / 4, pi / 4,     pi / 4,     pi / 4};
  const std::array<float, 9> y = shBasis(n);
  glm::vec3 e(0.0f);
  for (size_t k = 0; k < coefficients.size() && k < 9; ++k) e += convolution[k] * y[k] * coefficients[k];
  return e;
}

std::array<float, 9> shBasisBand4(const glm::vec3& w) {
  const float x = w.x, y = w.y, z = w.z, x2 = x * x, y2 = y * y, z2 = z * z;
  return {2.503343f * x * y * (x2 - y2),
          1.770131f * y * z * (3.0f * x2 - y2),
          0.946175f * x * y * (7.0f * z2 - 1.0f),
          0.669046f * y * z * (7.0f * z2 - 3.0f),
          0.105786f * (35.0f * z2 * z2 - 30.0f * z2 + 3.0f),
          0.669046f * x * z * (7.0f * z2 - 3.0f),
          0.473087f * (x2 - y2) * (7.0f * z2 - 1.0f),
          1.770131f * x * z * (x2 - 3.0f * y2),
          0.625836f * (x2 * (x2 - 3.0f * y2) - y2 * (3.0f * x2 - y2))};
}

glm::vec3 shIrradianceBand4(std::span<const glm::vec3> band4, const glm::vec3& n) {
  constexpr float a4 = -std::numbers::pi_v<float> / 24.0f;
  const std::array<float, 9> y = shBasisBand4(n);
  glm::vec3 e(0.0f);
  for (size_t k = 0; k < band4.size() && k < 9; ++k) e += a4 * y[k] * band4[k];
  return e;
}

glm::vec3 shIrradianceVector(std::span<const glm::vec3> coefficients, int channel) {
  const auto c = [&](size_t k) { return coefficients[k][channel]; };
  return glm::vec3(c(3), c(1), c(2)) / kShY1;
}

}  // namespace cpgi
