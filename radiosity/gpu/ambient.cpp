#include "radiosity/gpu/ambient.h"

#include <stdexcept>

namespace cpgi {

namespace {

// The ambient irradiance per cell (the last entry: texels in no cell, or every texel without cells), each
// texel's entry, and the mean over the scene.
struct CellAmbient {
  std::vector<glm::dvec3> irradiance;
  std::vector<size_t> texelEntry;
  glm::dvec3 mean{0.0};
};

CellAmbient cellAmbient(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                        const glm::dvec3& unshotPower, std::span<const float> texelCell,
                        const CellGraph& graph) {
  const size_t n = atlas.texelCount();
  if (!residual.empty() && residual.size() != n)
    throw std::invalid_argument("ambient: not one residual per atlas texel");
  const bool byCell = !graph.cells.empty() && texelCell.size() == n;
  // Cells 0..K-1, and K for texels in no cell (or every texel without cells).
  const size_t k = byCell ? graph.cells.size() : 0, count = k + 1;
  auto cellOf = [&](size_t i) {
    if (!byCell) return k;
    const float c = texelCell[i];
    return c >= 0.0f && size_t(c) < k ? size_t(c) : k;
  };
  std::vector<double> area(count, 0.0);
  std::vector<glm::dvec3> albedo(count, glm::dvec3(0.0)), unshot(count, glm::dvec3(0.0));
  double total = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (atlas.patch[i] < 0) continue;
    const size_t c = cellOf(i);
    const double a = atlas.area[i];
    area[c] += a;
    albedo[c] += a * glm::dvec3(atlas.albedo[i]);
    if (!residual.empty()) unshot[c] += a * glm::dvec3(residual[i]);
    total += a;
  }
  CellAmbient out;
  out.irradiance.assign(count, glm::dvec3(0.0));
  out.texelEntry.resize(n);
  for (size_t i = 0; i < n; ++i) out.texelEntry[i] = cellOf(i);
  if (!(total > 0.0)) return out;
  for (size_t c = 0; c < count; ++c) {
    if (area[c] > 0.0) albedo[c] /= area[c];
    if (residual.empty()) unshot[c] = unshotPower * (area[c] / total);
  }
  // transfer[c][d]: the share of the power leaving cell c's surfaces that lands in cell d.
  std::vector<std::vector<double>> transfer(count, std::vector<double>(count, 0.0));
  std::vector<double> portals(count, 0.0);
  if (byCell)
    for (const PortalQuad& p : graph.portals)
      if (p.cellA >= 0 && p.cellB >= 0 && size_t(p.cellA) < k && size_t(p.cellB) < k)
        portals[p.cellA] += p.area, portals[p.cellB] += p.area;
  for (size_t c = 0; c < count; ++c) transfer[c][c] = 1.0;
  if (byCell)
    for (const PortalQuad& p : graph.portals) {
      if (p.cellA < 0 || p.cellB < 0 || size_t(p.cellA) >= k || size_t(p.cellB) >= k) continue;
      for (const auto& [from, to] : {std::pair{p.cellA, p.cellB}, std::pair{p.cellB, p.cellA}}) {
        const double enclosure = area[from] + portals[from];
        if (!(enclosure > 0.0)) continue;
        transfer[from][to] += p.area / enclosure;
        transfer[from][from] -= p.area / enclosure;
      }
    }
  // The series: what leaves (unshot, then each bounce's reflection) lands by `transfer`, is absorbed or
  // reflected again. `landed` sums the power each cell's surfaces receive, all bounces.
  std::vector<glm::dvec3> leaving = unshot, landed(count, glm::dvec3(0.0));
  double unshotSum = 0.0;
  for (const glm::dvec3& u : unshot) unshotSum += u.r + u.g + u.b;
  for (int bounce = 0; bounce < 1000; ++bounce) {
    std::vector<glm::dvec3> arriving(count, glm::dvec3(0.0));
    double left = 0.0;
    for (size_t c = 0; c < count; ++c)
      for (size_t d = 0; d < count; ++d) arriving[d] += leaving[c] * transfer[c][d];
    for (size_t c = 0; c < count; ++c) {
      landed[c] += arriving[c];
      leaving[c] = albedo[c] * arriving[c];
      left += leaving[c].r + leaving[c].g + leaving[c].b;
    }
    if (left <= 1e-9 * (unshotSum + 1e-30)) break;
  }
  for (size_t c = 0; c < count; ++c) {
    if (area[c] > 0.0) out.irradiance[c] = landed[c] / area[c];
    out.mean += landed[c] / total;
  }
  return out;
}

}  // namespace

glm::dvec3 addAmbient(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                      const glm::dvec3& unshotPower, std::span<const float> texelCell, const CellGraph& graph,
                      std::vector<glm::vec3>& radiosity) {
  if (radiosity.size() != atlas.texelCount())
    throw std::invalid_argument("addAmbient: not one value per atlas texel");
  const CellAmbient a = cellAmbient(atlas, residual, unshotPower, texelCell, graph);
  for (size_t i = 0; i < radiosity.size(); ++i)
    if (atlas.patch[i] >= 0)
      radiosity[i] += glm::vec3(glm::dvec3(atlas.albedo[i]) * a.irradiance[a.texelEntry[i]]);
  return a.mean;
}

std::vector<double> ambientShares(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                                  std::span<const float> texelCell, const CellGraph& graph,
                                  const std::vector<glm::vec3>& radiosity) {
  if (radiosity.size() != atlas.texelCount() || residual.size() != atlas.texelCount())
    throw std::invalid_argument("ambientShares: not one value per atlas texel");
  const CellAmbient a = cellAmbient(atlas, residual, glm::dvec3(0.0), texelCell, graph);
  std::vector<double> ambient(a.irradiance.size(), 0.0), light(a.irradiance.size(), 0.0);
  for (size_t i = 0; i < radiosity.size(); ++i) {
    if (atlas.patch[i] < 0 || atlas.emission[i] != glm::vec3(0.0f)) continue;  // lamps: their own light
    const glm::dvec3 add = glm::dvec3(atlas.albedo[i]) * a.irradiance[a.texelEntry[i]];
    const double w = atlas.area[i];
    ambient[a.texelEntry[i]] += w * (add.r + add.g + add.b);
    light[a.texelEntry[i]] += w * (add.r + add.g + add.b + radiosity[i].r + radiosity[i].g + radiosity[i].b);
  }
  std::vector<double> share(ambient.size(), 0.0);
  for (size_t c = 0; c < share.size(); ++c) share[c] = light[c] > 0.0 ? ambient[c] / light[c] : 0.0;
  return share;
}

}  // namespace cpgi
