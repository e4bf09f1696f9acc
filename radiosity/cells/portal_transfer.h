// How a portal re-emits on its far side the light that reached it (CellSolveParams::portals), one class per
// portal model. The cell solver (cell_solver.cpp) moves the exitance itself, rescaled so that the power
// through the opening is conserved whatever the model; a model adds how a cell's pending light is shot at
// its next solve and what travels with the exitance:
//  - DiffusePortals (the thesis): a Lambertian area light; nothing travels along.
//  - DirectionalPortals: the arrival moments travel with the exitance (cell_round.h) and become emission
//    lobes (radiosity/solve/emission_lobes.h), so light keeps the direction it crossed the opening in.
//  - BinnedPortals: arrival bins found by rays in the sending cell travel with the exitance and are
//    emitted as they are (radiosity/solve/emission_bins.h).
// A new portal model is one more class here and one more case in makePortalTransfer.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/solve/shot_engine.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

class PortalTransfer {
 public:
  virtual ~PortalTransfer() = default;

  /// Solves cell `c` (state `s`), shooting its pending exitance (already its atlas's emission) with
  /// `controls`, its shots shaped as `shape` and the model asks. Called side by side for distinct cells
  /// within a round.
  virtual SolveResult solve(size_t c, const CellState& s, const SolverParams& settings,
                            const SolveControls& controls, ShotShape shape, ShotEngine& engine,
                            Context& ctx) const = 0;
  /// Rays per sending portal texel for the sends' arrival bins (cellRoundOf); 0: the model has none.
  virtual int binRays() const { return 0; }
};

/// The thesis's portal: the irradiance reaching the opening is re-emitted as a Lambertian area light.
class DiffusePortals : public PortalTransfer {
 public:
  SolveResult solve(size_t c, const CellState& s, const SolverParams& settings, const SolveControls& controls,
                    ShotShape shape, ShotEngine& engine, Context& ctx) const override;
};

/// Light keeps the direction it arrived in: per texel, the arrival moments of what is pending
/// (CellState::pendingMoments) are fitted into an emission lobe at each solve; the solve's arrival
/// moments travel through the portals with the exitance (cell_round.h: PortalSend::moments,
/// CellRound::keptMoments), in the single process and in the cell jobs' files alike.
class DirectionalPortals : public PortalTransfer {
 public:
  /// `lobeMinWidth`: CellSolveParams::lobeMinWidth.
  explicit DirectionalPortals(float lobeMinWidth) : lobeMinWidth_(lobeMinWidth) {}
  SolveResult solve(size_t c, const CellState& s, const SolverParams& settings, const SolveControls& controls,
                    ShotShape shape, ShotEngine& engine, Context& ctx) const override;

 private:
  float lobeMinWidth_;
};

/// Light keeps the directions it arrived in, binned: per texel, the arrival bins of what is pending
/// (CellState::pendingBins) are its emission at each solve; each send's bins are found by rays in the
/// sending cell (cell_round.h: portalArrivalBins), in the single process and the cell jobs alike.
class BinnedPortals : public PortalTransfer {
 public:
  explicit BinnedPortals(int rays) : rays_(rays) {}
  SolveResult solve(size_t c, const CellState& s, const SolverParams& settings, const SolveControls& controls,
                    ShotShape shape, ShotEngine& engine, Context& ctx) const override;
  int binRays() const override { return rays_; }

 private:
  int rays_;
};

/// The model `params.portals` names (its parameters checked by solveCells).
std::unique_ptr<PortalTransfer> makePortalTransfer(const CellSolveParams& params);

}  // namespace cpgi
