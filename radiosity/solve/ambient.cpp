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

// The atlas's texels by cell: each valid texel's entry (cells 0..K-1, K for texels in no cell, or every
// texel without cells), per entry its surfaces (area, Σ ρ × area; unshot 0) and the openings between cells.
struct CellSurfaces {
  std::vector<size_t> texelEntry;
  std::vector<AmbientRoom> rooms;
  std::vector<AmbientOpening> openings;
  double area = 0.0;
};

CellSurfaces cellSurfaces(const LightmapAtlas& atlas, std::span<const float> texelCell,
                          const CellGraph& graph) {
  const size_t n = atlas.texelCount();
  const bool byCell = !graph.cells.empty() && texelCell.size() == n;
  const size_t k = byCell ? graph.cells.size() : 0;
  CellSurfaces out;
  out.rooms.resize(k + 1);
  out.texelEntry.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const float c = byCell ? texelCell[i] : -1.0f;
    const size_t entry = c >= 0.0f && size_t(c) < k ? size_t(c) : k;
    out.texelEntry[i] = entry;
    if (atlas.patch[i] < 0) continue;
    const double a = atlas.area[i];
    out.rooms[entry].area += a;
    out.rooms[entry].albedoArea += a * glm::dvec3(atlas.albedo[i]);
    out.area += a;
  }
  if (byCell)
    for (const PortalQuad& p : graph.portals)
      if (p.cellA >= 0 && p.cellB >= 0 && size_t(p.cellA) < k && size_t(p.cellB) < k)
        out.openings.push_back(AmbientOpening{size_t(p.cellA), size_t(p.cellB), p.area});
  return out;
}

// Per entry, the ambient irradiance (W/m², RGB) of the unshot power in `rooms` (each entry's own), and
// the power landed in all (W, RGB).
struct Irradiance {
  std::vector<glm::dvec3> perEntry;
  glm::dvec3 landed{0.0};
};
// `texelUnshot` (per atlas texel, W; or empty) and `texelArea` (m²): where the unshot power leaves from,
// with measured arrivals (ambientLandedByArrivals).
Irradiance ambientIrradiance(const std::vector<AmbientRoom>& rooms,
                             const std::vector<AmbientOpening>& openings, const AmbientTransfer* measured,
                             std::span<const double> texelUnshot, std::span<const float> texelArea) {
  std::vector<glm::dvec3> landed;
  if (measured && !measured->arrivals.empty()) {
    std::vector<glm::dvec3> unshot(rooms.size());
    for (size_t c = 0; c < rooms.size(); ++c) unshot[c] = rooms[c].unshot;
    landed = ambientLandedByArrivals(unshot, *measured, texelUnshot, texelArea);
  } else {
    landed = measured ? ambientLandedByShares(rooms, measured->share) : ambientLanded(rooms, openings);
  }
  Irradiance out;
  out.perEntry.assign(rooms.size(), glm::dvec3(0.0));
  for (size_t c = 0; c < rooms.size(); ++c) {
    if (rooms[c].area > 0.0) out.perEntry[c] = landed[c] / rooms[c].area;
    out.landed += landed[c];
  }
  return out;
}

const AmbientTransfer* measuredShares(const AmbientTransfer* measured, size_t entries) {
  return measured && measured->share.size() == entries ? measured : nullptr;
}

}  // namespace

glm::dvec3 addAmbient(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                      const glm::dvec3& unshotPower, std::span<const float> texelCell, const CellGraph& graph,
                      std::vector<glm::vec3>& radiosity, const AmbientTransfer* measured) {
  if (radiosity.size() != atlas.texelCount())
    throw std::invalid_argument("addAmbient: not one value per atlas texel");
  if (!residual.empty() && residual.size() != atlas.texelCount())
    throw std::invalid_argument("ambient: not one residual per atlas texel");
  CellSurfaces s = cellSurfaces(atlas, texelCell, graph);
  if (!(s.area > 0.0)) return glm::dvec3(0.0);
  for (AmbientRoom& room : s.rooms) room.unshot = unshotPower * (room.area / s.area);
  std::vector<double> texelUnshot;
  if (!residual.empty()) {
    for (AmbientRoom& room : s.rooms) room.unshot = glm::dvec3(0.0);
    texelUnshot.assign(residual.size(), 0.0);
    for (size_t i = 0; i < residual.size(); ++i)
      if (atlas.patch[i] >= 0) {
        const glm::dvec3 power = double(atlas.area[i]) * glm::dvec3(residual[i]);
        s.rooms[s.texelEntry[i]].unshot += power;
        texelUnshot[i] = power.r + power.g + power.b;
      }
  }
  const Irradiance e = ambientIrradiance(s.rooms, s.openings, measuredShares(measured, s.rooms.size()),
                                         texelUnshot, atlas.area);
  for (size_t i = 0; i < radiosity.size(); ++i)
    if (atlas.patch[i] >= 0)
      radiosity[i] += glm::vec3(glm::dvec3(atlas.albedo[i]) * e.perEntry[s.texelEntry[i]]);
  return e.landed / s.area;
}

RoomStop::RoomStop(const LightmapAtlas& atlas, std::span<const float> texelCell, const CellGraph& graph,
                   const AmbientTransfer* measured, double share)
    : atlas_(atlas), share_(share) {
  CellSurfaces s = cellSurfaces(atlas, texelCell, graph);
  texelEntry_ = std::move(s.texelEntry);
  rooms_ = std::move(s.rooms);
  openings_ = std::move(s.openings);
  if (const AmbientTransfer* m = measuredShares(measured, rooms_.size())) transfer_ = *m;
  reflectorAlbedoArea_.assign(rooms_.size(), glm::dvec3(0.0));
  reflectorArea_.assign(rooms_.size(), 0.0);
  for (size_t i = 0; i < texelEntry_.size(); ++i) {
    if (atlas.patch[i] < 0 || atlas.emission[i] != glm::vec3(0.0f)) continue;  // lamps: their own light
    const double a = atlas.area[i];
    reflectorAlbedoArea_[texelEntry_[i]] += a * glm::dvec3(atlas.albedo[i]);
    reflectorArea_[texelEntry_[i]] += a;
  }
}

std::vector<int> RoomStop::texelCells() const {
  std::vector<int> cells(texelEntry_.size());
  for (size_t i = 0; i < cells.size(); ++i) cells[i] = int(texelEntry_[i]);
  return cells;
}

CellLight RoomStop::cellLight(const std::vector<glm::vec3>& radiosity,
                              const std::vector<glm::vec3>& residual) const {
  if (radiosity.size() != texelEntry_.size() || residual.size() != texelEntry_.size())
    throw std::invalid_argument("ambientShares: not one value per atlas texel");
  CellLight out;
  out.unshot.assign(rooms_.size(), glm::dvec3(0.0));
  out.light.assign(rooms_.size(), 0.0);
  out.texelUnshot.assign(texelEntry_.size(), 0.0);
  for (size_t i = 0; i < texelEntry_.size(); ++i) {
    if (atlas_.patch[i] < 0) continue;
    const double a = atlas_.area[i];
    out.unshot[texelEntry_[i]] += a * glm::dvec3(residual[i]);
    out.texelUnshot[i] = a * (double(residual[i].r) + residual[i].g + residual[i].b);
    if (atlas_.emission[i] == glm::vec3(0.0f))
      out.light[texelEntry_[i]] += a * (double(radiosity[i].r) + radiosity[i].g + radiosity[i].b);
  }
  return out;
}

std::vector<double> RoomStop::shares(const CellLight& cells) const {
  if (cells.unshot.size() != rooms_.size() || cells.light.size() != rooms_.size())
    throw std::invalid_argument("RoomStop: not one light per cell");
  std::vector<AmbientRoom> rooms = rooms_;
  for (size_t c = 0; c < rooms.size(); ++c) rooms[c].unshot = cells.unshot[c];
  const std::vector<glm::dvec3> irradiance =
      ambientIrradiance(rooms, openings_, transfer_.share.empty() ? nullptr : &transfer_, cells.texelUnshot,
                        atlas_.area)
          .perEntry;
  std::vector<double> ambient(rooms.size(), 0.0), light(rooms.size(), 0.0);
  for (size_t c = 0; c < rooms.size(); ++c) {
    ambient[c] = glm::dot(reflectorAlbedoArea_[c], irradiance[c]);
    light[c] = ambient[c] + cells.light[c];
  }
  return ambientShareOfLitCells(ambient, light, reflectorArea_);
}

bool RoomStop::accepts(const CellLight& cells) const {
  const std::vector<double> s = shares(cells);
  return s.empty() || *std::max_element(s.begin(), s.end()) <= share_;
}

std::vector<double> ambientShares(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                                  std::span<const float> texelCell, const CellGraph& graph,
                                  const std::vector<glm::vec3>& radiosity, const AmbientTransfer* measured) {
  if (radiosity.size() != atlas.texelCount() || residual.size() != atlas.texelCount())
    throw std::invalid_argument("ambientShares: not one value per atlas texel");
  const RoomStop stop(atlas, texelCell, graph, measured, 0.0);
  return stop.shares(stop.cellLight(radiosity, residual));
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
