#include "radiosity/cells/portal_transfer.h"

#include <algorithm>

#include "radiosity/gpu/emission_lobes.h"

namespace cpgi {

SolveResult DiffusePortals::solve(size_t, const CellState& s, const SolverParams& settings,
                                  SolveControls controls, const EglContext& gl, Context& ctx) const {
  return solveProgressive(s.cs.scene, s.atlas, settings, gl, ctx, controls);
}

DirectionalPortals::DirectionalPortals(const std::vector<CellState>& cells, float lobeMinWidth)
    : lobeMinWidth_(lobeMinWidth), pending_(cells.size()), next_(cells.size()) {
  for (size_t c = 0; c < cells.size(); ++c) pending_[c].assign(cells[c].atlas.texelCount(), glm::vec4(0.0f));
}

SolveResult DirectionalPortals::solve(size_t c, const CellState& s, const SolverParams& settings,
                                      SolveControls controls, const EglContext& gl, Context& ctx) const {
  const std::vector<glm::vec4> lobes = fitEmissionLobes(pending_[c], s.atlas, lobeMinWidth_);
  controls.directionalEmission = true;
  controls.emissionLobes = lobes;
  return solveProgressive(s.cs.scene, s.atlas, settings, gl, ctx, controls);
}

void DirectionalPortals::beginRound() {
  for (size_t c = 0; c < pending_.size(); ++c) next_[c].assign(pending_[c].size(), glm::vec4(0.0f));
}

void DirectionalPortals::keepPending(size_t c) {
  for (size_t i = 0; i < pending_[c].size(); ++i) next_[c][i] += pending_[c][i];
}

// A texel's residual is the part of its pending exitance it did not shoot (portal texels have albedo 0
// and gain none), so its moments are the pending ones scaled by the same share.
void DirectionalPortals::keepUnshot(size_t c, const CellState& s, const std::vector<glm::vec3>& residual) {
  const std::vector<glm::vec4>& arrivals = pending_[c];
  for (size_t i = 0; i < arrivals.size(); ++i) {
    const float pending = s.pending[i].r + s.pending[i].g + s.pending[i].b;
    const float left = residual[i].r + residual[i].g + residual[i].b;
    if (arrivals[i].w > 0.0f && pending > 0.0f && left > 0.0f)
      next_[c][i] += arrivals[i] * std::min(left / pending, 1.0f);
  }
}

// The moments go along in world coordinates (the far side's normal is this side's negated, as the moments
// assume), weighted like the exitance they describe.
void DirectionalPortals::send(const PortalLink& link, const SolveResult& solved, const glm::vec3& scale) {
  for (const auto& [tt, ft] : link.texels)
    next_[link.to][tt] += solved.arrivals[ft] * ((scale.r + scale.g + scale.b) / 3.0f);
}

void DirectionalPortals::endRound() {
  for (size_t c = 0; c < pending_.size(); ++c) pending_[c] = std::move(next_[c]);
}

std::unique_ptr<PortalTransfer> makePortalTransfer(const CellSolveParams& params,
                                                   const std::vector<CellState>& cells) {
  switch (params.portals) {
    case PortalLight::Directional:
      return std::make_unique<DirectionalPortals>(cells, params.lobeMinWidth);
    case PortalLight::Diffuse:
      break;
  }
  return std::make_unique<DiffusePortals>();
}

}  // namespace cpgi
