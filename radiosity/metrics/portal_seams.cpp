#include "radiosity/metrics/portal_seams.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace cpgi {
namespace {

constexpr float kUpCosine = 0.99f;         // a floor texel's normal within about 8° of up
constexpr float kHeightTolerance = 0.02f;  // metres between a floor texel and the portal's lowest edge

// A band's texels as (position along the portal, value, area).
struct BandTexel {
  float along;
  double value, area;
};

struct BandFigures {
  double mean = 0.0, variance = 0.0;
  size_t texels = 0;
};

BandFigures bandFigures(std::vector<BandTexel> band) {
  BandFigures f;
  f.texels = band.size();
  double sum = 0.0, area = 0.0;
  for (const BandTexel& b : band) sum += b.area * b.value, area += b.area;
  f.mean = area > 0.0 ? sum / area : 0.0;
  if (band.size() < 2) return f;
  std::sort(band.begin(), band.end(),
            [](const BandTexel& a, const BandTexel& b) { return a.along < b.along; });
  double squares = 0.0;
  for (size_t k = 1; k < band.size(); ++k) {
    const double d = band[k].value - band[k - 1].value;
    squares += d * d;
  }
  f.variance = squares / (2.0 * double(band.size() - 1));
  return f;
}

}  // namespace

std::vector<PortalSeam> measurePortalSeams(const SeamTexels& t, const std::vector<SeamPortal>& portals,
                                           glm::vec3 up) {
  const size_t n = t.position.size();
  if (t.normal.size() != n || t.value.size() != n || t.area.size() != n)
    throw std::invalid_argument("measurePortalSeams: texel spans differ in size");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  up = glm::normalize(up);
  std::vector<PortalSeam> out;
  for (const SeamPortal& p : portals) {
    PortalSeam seam;
    seam.name = p.name;
    seam.step = seam.noise = nan;
    const glm::vec3 normal = glm::cross(p.corners[1] - p.corners[0], p.corners[3] - p.corners[0]);
    // The portal's width runs along its plane, across `up`; a portal lying flat (a hatch) has no floor.
    const glm::vec3 width = glm::cross(up, normal);
    if (glm::length(normal) < 1e-8f || glm::length(width) < 1e-8f) {
      out.push_back(seam);
      continue;
    }
    const glm::vec3 nu = glm::normalize(normal), wu = glm::normalize(width);
    float lowest = std::numeric_limits<float>::max(), w0 = lowest, w1 = -lowest;
    for (const glm::vec3& c : p.corners) {
      lowest = std::min(lowest, glm::dot(c, up));
      w0 = std::min(w0, glm::dot(c, wu));
      w1 = std::max(w1, glm::dot(c, wu));
    }
    const float plane = glm::dot(p.corners[0], nu);
    // The floor texels near the plane, then on each side the row nearest to it: those within 0.4 texel
    // of the nearest one, so that a row of texels thinner across the plane than along it (a thin wall's
    // threshold keeps two texels across each half) gives its first row alone.
    struct Candidate {
      size_t texel;
      float along, distance;
    };
    std::vector<Candidate> near[2];
    float nearest[2] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
    for (size_t i = 0; i < n; ++i) {
      if (!(t.area[i] > 0.0f) || glm::dot(t.normal[i], up) < kUpCosine) continue;
      const glm::vec3 x = t.position[i];
      if (std::abs(glm::dot(x, up) - lowest) > kHeightTolerance) continue;
      const float along = glm::dot(x, wu), d = glm::dot(x, nu) - plane, size = std::sqrt(t.area[i]);
      if (along < w0 || along > w1 || d == 0.0f || std::abs(d) > 2.0f * size) continue;
      const int side = d > 0.0f ? 1 : 0;
      near[side].push_back({i, along, std::abs(d)});
      nearest[side] = std::min(nearest[side], std::abs(d));
    }
    std::vector<BandTexel> sides[2];
    for (int side = 0; side < 2; ++side)
      for (const Candidate& c : near[side]) {
        if (c.distance > nearest[side] + 0.4f * std::sqrt(t.area[c.texel])) continue;
        const glm::dvec3 v(t.value[c.texel]);
        sides[side].push_back({c.along, (v.x + v.y + v.z) / 3.0, double(t.area[c.texel])});
      }
    const BandFigures a = bandFigures(std::move(sides[0])), b = bandFigures(std::move(sides[1]));
    seam.texelsA = a.texels, seam.texelsB = b.texels;
    seam.meanA = a.mean, seam.meanB = b.mean;
    const double mean = 0.5 * (a.mean + b.mean);
    seam.measured = a.texels >= 2 && b.texels >= 2 && mean > 0.0;
    if (seam.measured) {
      seam.step = (b.mean - a.mean) / mean;
      seam.noise = std::sqrt(0.5 * (a.variance + b.variance)) / mean;
    }
    out.push_back(seam);
  }
  return out;
}

}  // namespace cpgi
