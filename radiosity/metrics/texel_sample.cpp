#include "radiosity/metrics/texel_sample.h"

#include <cmath>
#include <stdexcept>

namespace cpgi {

namespace {

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

TexelSample sampleTexels(size_t validCount, size_t count, uint64_t seed) {
  if (count == 0) throw std::invalid_argument("sampleTexels: count must be at least 1");
  TexelSample sample;
  const size_t n = std::min(count, validCount);
  sample.ranks.reserve(n);
  sample.weights.reserve(n);
  // Salted, so that which texels are chosen is unrelated to the paths the tracer draws from the same seed.
  const uint64_t base = splitmix64(seed ^ 0x7e7e15a3b1e5ull);
  for (size_t k = 0; k < n; ++k) {
    const size_t begin = validCount * k / n, end = validCount * (k + 1) / n;
    const size_t size = end - begin;
    // A 64-bit hash modulo a stratum size below 2³² is uniform to within 2⁻³²: no measurable bias.
    sample.ranks.push_back(begin + size_t(splitmix64(base + k) % size));
    sample.weights.push_back(float(size));
  }
  return sample;
}

double sampledRelRmseError(std::span<const glm::vec3> test, std::span<const glm::vec3> reference,
                           std::span<const float> area, std::span<const float> weight, size_t validTexels) {
  if (test.size() != reference.size() || test.size() != area.size() || test.size() != weight.size())
    throw std::invalid_argument("sampledRelRmseError: lightmaps, area and weight differ in size");
  double squaredError = 0.0, squaredReference = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < test.size(); ++i) {
    if (!(weight[i] > 0.0f)) continue;
    ++n;
    if (!(area[i] > 0.0f)) continue;
    const glm::dvec3 d = glm::dvec3(test[i]) - glm::dvec3(reference[i]), r(reference[i]);
    squaredError += double(weight[i]) * area[i] * glm::dot(d, d);
    squaredReference += double(weight[i]) * area[i] * glm::dot(r, r);
  }
  if (n < 2 || n >= validTexels || !(squaredReference > 0.0) || !(squaredError > 0.0)) return 0.0;
  const double ratio = squaredError / squaredReference;
  // Sample variance of u over the chosen texels (those of area 0 count, with u = 0).
  double sumU = 0.0, sumU2 = 0.0;
  for (size_t i = 0; i < test.size(); ++i) {
    if (!(weight[i] > 0.0f) || !(area[i] > 0.0f)) continue;
    const glm::dvec3 d = glm::dvec3(test[i]) - glm::dvec3(reference[i]), r(reference[i]);
    const double u = area[i] * (glm::dot(d, d) - ratio * glm::dot(r, r));
    sumU += u;
    sumU2 += u * u;
  }
  const double count = double(n), population = double(validTexels);
  const double varianceU = std::max(0.0, (sumU2 - sumU * sumU / count) / (count - 1.0));
  const double varianceRatio = population * population * (1.0 - count / population) * varianceU / count /
                               (squaredReference * squaredReference);
  return std::sqrt(varianceRatio) / (2.0 * std::sqrt(ratio));
}

}  // namespace cpgi
