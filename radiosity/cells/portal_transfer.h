// How a portal re-emits on its far side the light that reached it (CellSolveParams::portals), one class per
// portal model. The cell solver (cell_solver.cpp) moves the exitance itself, rescaled so that the power
// through the opening is conserved whatever the model; a model adds how a cell's pending light is shot at
// its next solve and what travels with the exitance:
//  - DiffusePortals (the thesis): a Lambertian area light; nothing travels along.
//  - DirectionalPortals: the arrival moments travel with the exitance and become emission lobes
//    (radiosity/gpu/emission_lobes.h), so light keeps the direction it crossed the opening in.
// A new portal model is one more class here and one more case in makePortalTransfer.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gpu_solver.h"

namespace cpgi {

class PortalTransfer {
 public:
  virtual ~PortalTransfer() = default;

  /// Solves cell `c` (state `s`), shooting its pending exitance (already its atlas's emission) with
  /// `controls`. Called side by side for distinct cells within a round.
  virtual SolveResult solve(size_t c, const CellState& s, const SolverParams& settings,
                            SolveControls controls, const EglContext& gl, Context& ctx) const = 0;

  /// A round's bookkeeping, called in cell order. beginRound: nothing gathered for the next round yet.
  virtual void beginRound() {}
  /// Cell `c` waits this round: its pending light stays pending.
  virtual void keepPending(size_t c) { (void)c; }
  /// Cell `c` was solved: the share of its pending light it left unshot (`residual`) stays pending.
  virtual void keepUnshot(size_t c, const CellState& s, const std::vector<glm::vec3>& residual) {
    (void)c, (void)s, (void)residual;
  }
  /// Light `solved` collected on `link`'s sending side crosses it, its exitance scaled by `scale`.
  virtual void send(const PortalLink& link, const SolveResult& solved, const glm::vec3& scale) {
    (void)link, (void)solved, (void)scale;
  }
  /// What was gathered becomes pending for the next round.
  virtual void endRound() {}
};

/// The thesis's portal: the irradiance reaching the opening is re-emitted as a Lambertian area light.
class DiffusePortals : public PortalTransfer {
 public:
  SolveResult solve(size_t c, const CellState& s, const SolverParams& settings, SolveControls controls,
                    const EglContext& gl, Context& ctx) const override;
};

/// Light keeps the direction it arrived in: per texel, the arrival moments of what is pending are fitted
/// into an emission lobe at each solve, and the moments travel through the portals with the exitance.
class DirectionalPortals : public PortalTransfer {
 public:
  /// `lobeMinWidth`: CellSolveParams::lobeMinWidth.
  DirectionalPortals(const std::vector<CellState>& cells, float lobeMinWidth);
  SolveResult solve(size_t c, const CellState& s, const SolverParams& settings, SolveControls controls,
                    const EglContext& gl, Context& ctx) const override;
  void beginRound() override;
  void keepPending(size_t c) override;
  void keepUnshot(size_t c, const CellState& s, const std::vector<glm::vec3>& residual) override;
  void send(const PortalLink& link, const SolveResult& solved, const glm::vec3& scale) override;
  void endRound() override;

 private:
  float lobeMinWidth_;
  std::vector<std::vector<glm::vec4>> pending_;  ///< per cell and texel: moments of CellState::pending
  std::vector<std::vector<glm::vec4>> next_;     ///< gathered this round
};

/// The model `params.portals` names (its parameters checked by solveCells).
std::unique_ptr<PortalTransfer> makePortalTransfer(const CellSolveParams& params,
                                                   const std::vector<CellState>& cells);

}  // namespace cpgi
