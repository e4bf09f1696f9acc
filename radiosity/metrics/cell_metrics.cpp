#include "radiosity/metrics/cell_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cpgi {

std::vector<CellError> compareCells(std::span<const glm::vec3> test, std::span<const glm::vec3> reference,
                                    std::span<const float> weight, std::span<const float> sigma,
                                    std::span<const float> cell, std::span<const float> sampleWeight,
                                    size_t validTexels, const std::vector<std::string>& names) {
  const size_t n = test.size();
  if (reference.size() != n || weight.size() != n || cell.size() != n ||
      (!sigma.empty() && sigma.size() != n) || (!sampleWeight.empty() && sampleWeight.size() != n))
    throw std::invalid_argument("compareCells: lightmaps and channels differ in size");
  const size_t count = names.size();
  struct Sums {
    double b = 0, r = 0, weight = 0, squaredError = 0, squaredReference = 0, noise = 0, meanNoise = 0;
    glm::dvec3 bColour{0.0}, rColour{0.0};
    size_t texels = 0;
  };
  std::vector<Sums> s(count);
  auto indexOf = [&](size_t i) -> long {
    const float c = cell[i];
    return std::isfinite(c) && c >= 0.0f && size_t(c) < count ? long(c) : -1;
  };
  for (size_t i = 0; i < n; ++i) {
    const long c = indexOf(i);
    const double w = weight[i];
    if (c < 0 || !(w > 0.0)) continue;
    const glm::dvec3 b(test[i]), r(reference[i]), d = b - r;
    Sums& x = s[size_t(c)];
    x.b += w * (b.x + b.y + b.z);
    x.r += w * (r.x + r.y + r.z);
    x.weight += w;
    x.bColour += w * b;
    x.rColour += w * r;
    x.squaredError += w * glm::dot(d, d);
    x.squaredReference += w * glm::dot(r, r);
    if (!sigma.empty()) {
      const double sd = sigma[i];
      x.noise += w * sd * sd;
      x.meanNoise += 3.0 * (w * sd) * (w * sd);  // √3 |σ| per texel, squared
    }
    ++x.texels;
  }
  // Texel sampling (sparse reference): the ratio estimator linearised, u_i = a_i (B_i − r R_i), with the
  // Horvitz–Thompson variance of a texel drawn with probability 1/m (m = its sample weight):
  // Var(Σ m u) ≈ Σ (1 − 1/m) m² u², relative to the denominator Σ m a R.
  std::vector<double> sampling(count, 0.0);
  const bool sparse = !sampleWeight.empty() && validTexels > 0;
  std::vector<CellError> out(count);
  for (size_t c = 0; c < count; ++c) {
    out[c].name = names[c];
    out[c].texels = s[c].texels;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (s[c].texels == 0 || !(s[c].r > 0.0)) {
      out[c].ratioOfMeans = out[c].relRmse = out[c].referenceNoise = out[c].ratioError = nan;
      out[c].referenceMean = s[c].weight > 0.0 ? s[c].r / (3.0 * s[c].weight) : nan;
      out[c].relRmseWithoutNoise = out[c].redGreenRatio = out[c].blueGreenRatio = nan;
      continue;
    }
    out[c].ratioOfMeans = s[c].b / s[c].r;
    out[c].referenceMean = s[c].r / (3.0 * s[c].weight);
    out[c].relRmse = std::sqrt(s[c].squaredError / s[c].squaredReference);
    out[c].referenceNoise = std::sqrt(s[c].noise / s[c].squaredReference);
    out[c].relRmseWithoutNoise =
        std::sqrt(std::max(s[c].squaredError - s[c].noise, 0.0) / s[c].squaredReference);
    const glm::dvec3 bc = s[c].bColour, rc = s[c].rColour;
    const bool green = bc.y > 0.0 && rc.y > 0.0 && rc.x > 0.0 && rc.z > 0.0;
    out[c].redGreenRatio = green ? (bc.x / bc.y) / (rc.x / rc.y) : nan;
    out[c].blueGreenRatio = green ? (bc.z / bc.y) / (rc.z / rc.y) : nan;
  }
  if (sparse)
    for (size_t i = 0; i < n; ++i) {
      const long c = indexOf(i);
      const double m = sampleWeight[i];
      if (c < 0 || !(weight[i] > 0.0) || !(m > 0.0) || !std::isfinite(out[size_t(c)].ratioOfMeans)) continue;
      const double a = weight[i] / m;  // the area alone
      const glm::dvec3 b(test[i]), r(reference[i]);
      const double u = a * ((b.x + b.y + b.z) - out[size_t(c)].ratioOfMeans * (r.x + r.y + r.z));
      sampling[size_t(c)] += std::max(0.0, 1.0 - 1.0 / m) * m * m * u * u;
    }
  for (size_t c = 0; c < count; ++c) {
    if (!std::isfinite(out[c].ratioOfMeans)) continue;
    const double fromNoise = out[c].ratioOfMeans * std::sqrt(s[c].meanNoise) / s[c].r;
    out[c].ratioError = std::sqrt(fromNoise * fromNoise + sampling[c] / (s[c].r * s[c].r));
  }
  return out;
}

std::vector<CellNoise> referenceCellNoise(std::span<const glm::vec3> reference, std::span<const float> sigma,
                                          std::span<const float> weight, std::span<const float> cell,
                                          const std::vector<std::string>& names) {
  const size_t n = reference.size();
  if (sigma.size() != n || weight.size() != n || cell.size() != n)
    throw std::invalid_argument("referenceCellNoise: lightmap and channels differ in size");
  struct Sums {
    double sum = 0, squares = 0, noise = 0, meanNoise = 0;
  };
  std::vector<Sums> s(names.size());
  std::vector<CellNoise> out(names.size());
  for (size_t i = 0; i < n; ++i) {
    const float c = cell[i];
    const double w = weight[i], sd = sigma[i];
    if (!std::isfinite(c) || c < 0.0f || size_t(c) >= names.size() || !(w > 0.0)) continue;
    const glm::dvec3 r(reference[i]);
    Sums& x = s[size_t(c)];
    x.sum += w * (r.x + r.y + r.z);
    x.squares += w * glm::dot(r, r);
    x.noise += w * sd * sd;
    x.meanNoise += 3.0 * (w * sd) * (w * sd);
    ++out[size_t(c)].texels;
  }
  for (size_t c = 0; c < names.size(); ++c) {
    out[c].name = names[c];
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const bool lit = out[c].texels > 0 && s[c].sum > 0.0;
    out[c].meanNoise = lit ? std::sqrt(s[c].meanNoise) / s[c].sum : nan;
    out[c].texelNoise = lit ? std::sqrt(s[c].noise / s[c].squares) : nan;
  }
  return out;
}

std::optional<size_t> worstCell(const std::vector<CellError>& cells) {
  std::optional<size_t> worst;
  double most = -1.0;
  for (size_t c = 0; c < cells.size(); ++c) {
    const double r = cells[c].ratioOfMeans;
    if (cells[c].texels == 0 || !std::isfinite(r)) continue;
    // A cell left black (ratio 0) is the worst there is.
    const double off = r > 0.0 ? std::abs(std::log(r)) : std::numeric_limits<double>::infinity();
    if (off > most) most = off, worst = c;
  }
  return worst;
}

}  // namespace cpgi
