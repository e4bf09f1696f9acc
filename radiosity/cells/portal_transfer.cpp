#include "radiosity/cells/portal_transfer.h"

#include "radiosity/gpu/emission_lobes.h"

namespace cpgi {

SolveResult DiffusePortals::solve(size_t, const CellState& s, const SolverParams& settings,
                                  SolveControls controls, const EglContext& gl, Context& ctx) const {
  // A cell's atlas emits what arrived at it (its lamps shot first, over the whole scene:
  // cell_first_shot.h), so nothing in it is a lamp to shoot by rays.
  SolverParams own = settings;
  own.lampRays = 0;
  return solveProgressive(s.cs.scene, s.atlas, own, gl, ctx, controls);
}

SolveResult DirectionalPortals::solve(size_t, const CellState& s, const SolverParams& settings,
                                      SolveControls controls, const EglContext& gl, Context& ctx) const {
  // No moments yet (the lamps' first shot, or nothing crossed a portal): Lambertian everywhere.
  const std::vector<glm::vec4> none(s.pendingMoments.empty() ? s.atlas.texelCount() : 0, glm::vec4(0.0f));
  const std::vector<glm::vec4> lobes =
      fitEmissionLobes(s.pendingMoments.empty() ? none : s.pendingMoments, s.atlas, lobeMinWidth_);
  controls.directionalEmission = true;
  controls.emissionLobes = lobes;
  return solveProgressive(s.cs.scene, s.atlas, settings, gl, ctx, controls);
}

std::unique_ptr<PortalTransfer> makePortalTransfer(const CellSolveParams& params) {
  switch (params.portals) {
    case PortalLight::Directional:
      return std::make_unique<DirectionalPortals>(params.lobeMinWidth);
    case PortalLight::Diffuse:
      break;
  }
  return std::make_unique<DiffusePortals>();
}

}  // namespace cpgi
