#include "radiosity/cells/portal_transfer.h"

#include "radiosity/solve/emission_bins.h"
#include "radiosity/solve/emission_lobes.h"

namespace cpgi {
namespace {

// A cell's solve, its portals shot through finer visibility regions (ShotShape::openingPatches): each
// sits in its wall's thickness, partly hidden by a jamb from receivers off its axis.
SolveResult solveCell(const CellState& s, const SolverParams& settings, ShotEngine& engine, Context& ctx,
                      const SolveControls& controls, ShotShape shape) {
  const std::vector<char> portal = portalPatchFlags(s);
  const std::vector<uint8_t> openings(portal.begin(), portal.end());
  shape.openingPatches = openings;
  return solveProgressive(s.cs.scene, s.atlas, settings, engine, ctx, controls, shape);
}

}  // namespace

SolveResult DiffusePortals::solve(size_t, const CellState& s, const SolverParams& settings,
                                  const SolveControls& controls, ShotShape shape, ShotEngine& engine,
                                  Context& ctx) const {
  // A cell's atlas emits what arrived at it (its lamps shot first, over the whole scene:
  // cell_first_shot.h), so nothing in it is a lamp to shoot by rays.
  SolverParams own = settings;
  own.lampRays = 0;
  return solveCell(s, own, engine, ctx, controls, shape);
}

SolveResult DirectionalPortals::solve(size_t, const CellState& s, const SolverParams& settings,
                                      const SolveControls& controls, ShotShape shape, ShotEngine& engine,
                                      Context& ctx) const {
  // No moments yet (the lamps' first shot, or nothing crossed a portal): Lambertian everywhere.
  const std::vector<glm::vec4> none(s.pendingMoments.empty() ? s.atlas.texelCount() : 0, glm::vec4(0.0f));
  const std::vector<glm::vec4> lobes =
      fitEmissionLobes(s.pendingMoments.empty() ? none : s.pendingMoments, s.atlas, lobeMinWidth_);
  shape.directionalEmission = true;
  shape.emissionLobes = lobes;
  return solveCell(s, settings, engine, ctx, controls, shape);
}

SolveResult BinnedPortals::solve(size_t, const CellState& s, const SolverParams& settings,
                                 const SolveControls& controls, ShotShape shape, ShotEngine& engine,
                                 Context& ctx) const {
  // Texels with bins emit by them; the rest (reflectors, and everything before light crossed a portal)
  // as Lambertians.
  std::vector<glm::vec4> lobes(s.atlas.texelCount(), glm::vec4(0.0f));
  std::vector<float> bins;
  bins.reserve(s.pendingBins.size() * kBinSlotFloats);
  for (const auto& [t, b] : s.pendingBins) {
    const glm::dvec3 sum = binTotals(b);
    if (!(sum.r + sum.g + sum.b > 0.0) || size_t(t) >= lobes.size()) continue;
    lobes[size_t(t)] = binnedLobe(int(bins.size() / kBinSlotFloats));
    const EmissionBinSlot f = normalisedEmissionBins(b);
    bins.insert(bins.end(), f.begin(), f.end());
  }
  shape.directionalEmission = true;
  shape.arrivalMoments = false;  // the bins are traced after the solve (cell_round.h)
  shape.emissionLobes = lobes;
  shape.emissionBins = bins;
  return solveCell(s, settings, engine, ctx, controls, shape);
}

std::unique_ptr<PortalTransfer> makePortalTransfer(const CellSolveParams& params) {
  switch (params.portals) {
    case PortalLight::Binned:
      return std::make_unique<BinnedPortals>(params.portalBinRays);
    case PortalLight::Directional:
      return std::make_unique<DirectionalPortals>(params.lobeMinWidth);
    case PortalLight::Diffuse:
      break;
  }
  return std::make_unique<DiffusePortals>();
}

}  // namespace cpgi
