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

glm::vec3 shIrradianceVector(std::span<const glm::vec3> coefficients, int channel) {
  const auto c = [&](size_t k) { return coefficients[k][channel]; };
  return glm::vec3(c(3), c(1), c(2)) / kShY1;
}

}  // namespace cpgi
