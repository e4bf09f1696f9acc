#include "radiosity/solve/ambient.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace cpgi {

std::vector<glm::dvec3> ambientLanded(const std::vector<AmbientRoom>& rooms,
                                      const std::vector<AmbientOpening>& openings) {
  const size_t count = rooms.size();
  std::vector<double> portals(count, 0.0);
  for (const AmbientOpening& o : openings) portals[o.a] += o.area, portals[o.b] += o.area;
  // transfer[c][d]: the share of the power leaving room c's surfaces that lands in room d.
  std::vector<std::vector<double>> transfer(count, std::vector<double>(count, 0.0));
  for (size_t c = 0; c < count; ++c) transfer[c][c] = 1.0;
  for (const AmbientOpening& o : openings)
    for (const auto& [from, to] : {std::pair{o.a, o.b}, std::pair{o.b, o.a}}) {
      const double enclosure = rooms[from].area + portals[from];
      if (!(enclosure > 0.0)) continue;
      transfer[from][to] += o.area / enclosure;
      transfer[from][from] -= o.area / enclosure;
    }
  return ambientLandedByShares(rooms, transfer);
}

std::vector<glm::dvec3> ambientLandedByShares(const std::vector<AmbientRoom>& rooms,
                                              const std::vector<std::vector<double>>& transfer) {
  const size_t count = rooms.size();
  if (transfer.size() != count)
    throw std::invalid_argument("ambientLandedByShares: not one transfer row per room");
  std::vector<glm::dvec3> albedo(count, glm::dvec3(0.0));
  for (size_t c = 0; c < count; ++c) {
    if (transfer[c].size() != count)
      throw std::invalid_argument("ambientLandedByShares: not one share per room");
    if (rooms[c].area > 0.0) albedo[c] = rooms[c].albedoArea / rooms[c].area;
  }
  // The series: what leaves (unshot, then each bounce's reflection) lands by `transfer`, is absorbed or
  // reflected again.
  std::vector<glm::dvec3> leaving(count), landed(count, glm::dvec3(0.0));
  double unshotSum = 0.0;
  for (size_t c = 0; c < count; ++c) {
    leaving[c] = rooms[c].unshot;
    unshotSum += leaving[c].r + leaving[c].g + leaving[c].b;
  }
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
  return landed;
}

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
                        const CellGraph& graph, const AmbientTransfer* measured) {
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
  std::vector<AmbientRoom> rooms(count);
  for (size_t c = 0; c < count; ++c)
    rooms[c] =
        AmbientRoom{area[c], albedo[c], residual.empty() ? unshotPower * (area[c] / total) : unshot[c]};
  std::vector<AmbientOpening> openings;
  if (byCell)
    for (const PortalQuad& p : graph.portals)
      if (p.cellA >= 0 && p.cellB >= 0 && size_t(p.cellA) < k && size_t(p.cellB) < k)
        openings.push_back(AmbientOpening{size_t(p.cellA), size_t(p.cellB), p.area});
  const bool useMeasured = measured && measured->share.size() == count;
  const std::vector<glm::dvec3> landed =
      useMeasured ? ambientLandedByShares(rooms, measured->share) : ambientLanded(rooms, openings);
  for (size_t c = 0; c < count; ++c) {
    if (area[c] > 0.0) out.irradiance[c] = landed[c] / area[c];
    out.mean += landed[c] / total;
  }
  return out;
}

}  // namespace

glm::dvec3 addAmbient(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                      const glm::dvec3& unshotPower, std::span<const float> texelCell, const CellGraph& graph,
                      std::vector<glm::vec3>& radiosity, const AmbientTransfer* measured) {
  if (radiosity.size() != atlas.texelCount())
    throw std::invalid_argument("addAmbient: not one value per atlas texel");
  const CellAmbient a = cellAmbient(atlas, residual, unshotPower, texelCell, graph, measured);
  for (size_t i = 0; i < radiosity.size(); ++i)
    if (atlas.patch[i] >= 0)
      radiosity[i] += glm::vec3(glm::dvec3(atlas.albedo[i]) * a.irradiance[a.texelEntry[i]]);
  return a.mean;
}

std::vector<double> ambientShares(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                                  std::span<const float> texelCell, const CellGraph& graph,
                                  const std::vector<glm::vec3>& radiosity, const AmbientTransfer* measured) {
  if (radiosity.size() != atlas.texelCount() || residual.size() != atlas.texelCount())
    throw std::invalid_argument("ambientShares: not one value per atlas texel");
  const CellAmbient a = cellAmbient(atlas, residual, glm::dvec3(0.0), texelCell, graph, measured);
  const size_t cells = a.irradiance.size();
  std::vector<double> ambient(cells, 0.0), light(cells, 0.0), area(cells, 0.0);
  for (size_t i = 0; i < radiosity.size(); ++i) {
    if (atlas.patch[i] < 0 || atlas.emission[i] != glm::vec3(0.0f)) continue;  // lamps: their own light
    const glm::dvec3 add = glm::dvec3(atlas.albedo[i]) * a.irradiance[a.texelEntry[i]];
    const double w = atlas.area[i];
    ambient[a.texelEntry[i]] += w * (add.r + add.g + add.b);
    light[a.texelEntry[i]] += w * (add.r + add.g + add.b + radiosity[i].r + radiosity[i].g + radiosity[i].b);
    area[a.texelEntry[i]] += w;
  }
  return ambientShareOfLitCells(ambient, light, area);
}

std::vector<double> ambientShareOfLitCells(const std::vector<double>& ambient,
                                           const std::vector<double>& light,
                                           const std::vector<double>& area) {
  if (light.size() != ambient.size() || area.size() != ambient.size())
    throw std::invalid_argument("ambientShareOfLitCells: not one value per cell");
  double allLight = 0.0, allArea = 0.0;
  for (size_t c = 0; c < light.size(); ++c)
    if (area[c] > 0.0) allLight += light[c], allArea += area[c];
  std::vector<double> share(ambient.size(), 0.0);
  if (!(allLight > 0.0)) return share;
  const double litPerArea = kNegligibleCellLight * allLight / allArea;
  for (size_t c = 0; c < share.size(); ++c)
    if (area[c] > 0.0 && light[c] > litPerArea * area[c]) share[c] = ambient[c] / light[c];
  return share;
}

std::string roomsAboveShare(const std::vector<double>& shares, const std::vector<std::string>& names,
                            double target) {
  std::vector<std::pair<double, std::string>> above;
  for (size_t c = 0; c < shares.size(); ++c)
    if (shares[c] > target) above.emplace_back(shares[c], c < names.size() ? names[c] : "(no cell)");
  if (above.empty()) return {};
  std::sort(above.begin(), above.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string line = "stop per room: the solve stopped at its bound with " + std::to_string(above.size()) +
                     " room" + (above.size() > 1 ? "s" : "") + " above the ambient share of " +
                     std::to_string(int(std::lround(100.0 * target))) + " %:";
  for (size_t i = 0; i < above.size(); ++i) {
    char part[96];
    std::snprintf(part, sizeof part, "%s %s %.1f %%", i ? "," : "", above[i].second.c_str(),
                  100.0 * above[i].first);
    line += part;
  }
  return line;
}

}  // namespace cpgi
