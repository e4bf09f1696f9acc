#include "radiosity/cells/round_stop.h"

#include <algorithm>
#include <stdexcept>

#include "radiosity/solve/progressive_loop.h"

namespace cpgi {

CellStopSurfaces cellStopSurfaces(const CellState& s) {
  CellStopSurfaces out;
  out.written = !s.boundary;
  const std::vector<char> onPortal = portalPatchFlags(s);
  const std::vector<char> reflector = reflectorTexels(s);
  for (size_t t = 0; t < s.atlas.texelCount(); ++t) {
    const int p = s.atlas.patch[t];
    if (p < 0 || onPortal[size_t(p)]) continue;
    const glm::dvec3 albedoArea = glm::dvec3(s.atlas.albedo[t]) * double(s.atlas.area[t]);
    out.area += s.atlas.area[t];
    out.albedoArea += albedoArea;
    if (reflector[t]) out.reflectorAlbedoArea += albedoArea;
  }
  return out;
}

std::vector<AmbientOpening> cellOpenings(const CellGraph& graph) {
  std::vector<AmbientOpening> openings;
  const int cells = int(graph.cells.size());
  for (const PortalQuad& p : graph.portals)
    if (p.cellA >= 0 && p.cellB >= 0 && p.cellA < cells && p.cellB < cells && p.cellA != p.cellB)
      openings.push_back(AmbientOpening{size_t(p.cellA), size_t(p.cellB), p.area});
  return openings;
}

RoundStop roundStop(const std::vector<CellState>& cells, const CellGraph& graph, double target,
                    double maxAmbientShare) {
  std::vector<CellStopSurfaces> surfaces;
  surfaces.reserve(cells.size());
  for (const CellState& s : cells) surfaces.push_back(cellStopSurfaces(s));
  return RoundStop(target, maxAmbientShare, std::move(surfaces), cellOpenings(graph));
}

std::vector<const CellRound*> inGraphOrder(const std::vector<CellRound>& round) {
  std::vector<const CellRound*> out;
  out.reserve(round.size());
  for (const CellRound& r : round) out.push_back(&r);
  return out;
}

RoundStop::RoundStop(double target, double maxAmbientShare, std::vector<CellStopSurfaces> cells,
                     std::vector<AmbientOpening> openings)
    : target_(target),
      maxShare_(maxAmbientShare),
      cells_(std::move(cells)),
      openings_(std::move(openings)),
      light_(cells_.size(), 0.0) {}

void RoundStop::addRound(const std::vector<const CellRound*>& round) {
  if (round.size() != cells_.size()) throw std::invalid_argument("RoundStop: not one round per cell");
  unshot_.assign(cells_.size(), glm::dvec3(0.0));
  for (size_t c = 0; c < round.size(); ++c) {
    light_[c] += round[c]->reflectorGain;
    unshot_[c] += round[c]->keptRgb;
    for (const PortalSend& send : round[c]->sends)
      if (send.to >= 0 && size_t(send.to) < cells_.size()) unshot_[size_t(send.to)] += send.arrivingRgb;
  }
}

std::vector<double> RoundStop::shares() const {
  std::vector<double> share(cells_.size(), 0.0);
  if (unshot_.empty()) return share;
  std::vector<AmbientRoom> rooms(cells_.size());
  for (size_t c = 0; c < cells_.size(); ++c)
    rooms[c] = AmbientRoom{cells_[c].area, cells_[c].albedoArea, unshot_[c]};
  const std::vector<glm::dvec3> landed = ambientLanded(rooms, openings_);
  std::vector<double> ambient(cells_.size(), 0.0), light(cells_.size(), 0.0), area(cells_.size(), 0.0);
  for (size_t c = 0; c < cells_.size(); ++c) {
    if (!(cells_[c].area > 0.0)) continue;
    const glm::dvec3 added = cells_[c].reflectorAlbedoArea * (landed[c] / cells_[c].area);
    ambient[c] = added.r + added.g + added.b;
    light[c] = ambient[c] + light_[c];
    area[c] = cells_[c].area;
  }
  share = ambientShareOfLitCells(ambient, light, area);
  for (size_t c = 0; c < cells_.size(); ++c)
    if (!cells_[c].written) share[c] = 0.0;  // a boundary cell: nobody sees it
  return share;
}

bool RoundStop::another(double unshot) {
  if (unshot > target_) return true;
  if (maxShare_ <= 0.0 || unshot_.empty()) return false;
  ++checks_;
  const std::vector<double> share = shares();
  if (*std::max_element(share.begin(), share.end()) <= maxShare_) return false;
  target_ = unshot * kStopRecheck;
  return true;
}

}  // namespace cpgi
