#include "radiosity/metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cpgi {

namespace {

double ratio(double num, double den) {
  if (den > 0.0) return num / den;
  return num == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

}  // namespace

LightmapError compareLightmaps(std::span<const glm::vec3> test, std::span<const glm::vec3> reference,
                               std::span<const float> area) {
  if (test.size() != reference.size() || test.size() != area.size())
    throw std::invalid_argument("compareLightmaps: lightmaps and area differ in size");
  LightmapError e;
  double squaredError = 0.0, squaredReference = 0.0, sumDifference = 0.0, sumReference = 0.0;
  for (size_t i = 0; i < test.size(); ++i) {
    const double a = area[i];
    if (!(a > 0.0)) continue;
    const glm::dvec3 b(test[i]), r(reference[i]);
    const glm::dvec3 d = b - r;
    squaredError += a * glm::dot(d, d);
    squaredReference += a * glm::dot(r, r);
    sumDifference += a * (d.x + d.y + d.z);
    sumReference += a * (r.x + r.y + r.z);
    e.maxAbs = std::max(e.maxAbs, glm::length(d));
    ++e.texels;
  }
  e.relRmse = std::sqrt(ratio(squaredError, squaredReference));
  e.relMeanError = sumDifference == 0.0 ? 0.0 : ratio(sumDifference, std::abs(sumReference));
  return e;
}

}  // namespace cpgi
