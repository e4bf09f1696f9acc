// The light solved at the resolution it varies at (issue 13), not at every output texel. A lamp's own shot
// draws sharp shadows and penumbrae, so the lamps shoot onto the output atlas itself; the light they
// leave on the surfaces is then carried, as area-weighted means, to a coarser atlas of the same scene,
// where the many shots of the interreflection (most of a solve's shots, each as costly as a lamp's per
// receiver texel) are solved, and their irradiance comes back to the output texels by bilinear
// interpolation within each chart. An output texel's radiosity is E + ρ (direct + indirect): the
// direct at full resolution, the indirect at the solve's.
#pragma once

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/gpu/gpu_solver.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

struct TwoLevelParams {
  /// The coarse atlas's texel density (texels per metre; its other settings are the output atlas's).
  float solveDensity = 5.0f;
  /// Surfaces with something close in front of them solved finer, up to the output's texels
  /// (radiosity/lightmap/contact_density.h).
  bool refineContacts = true;
};

/// What the two levels were, beside the SolveResult.
struct TwoLevelData {
  size_t solveTexels = 0;       ///< valid texels of the coarse atlas
  size_t refinedTriangles = 0;  ///< triangles solved finer than solveDensity (contacts)
  int lampShots = 0;            ///< shots on the output atlas
  double lampSeconds = 0.0;     ///< their solve
  double solveSeconds = 0.0;    ///< the coarse solve
};

/// Solves `atlas` (the output's, built with `atlasParams` from `quads`) in two levels. The result is over
/// the output atlas: radiosity, and with controls.readTransfer the incident and residual (the coarse
/// solve's, interpolated); energy is the whole solve's (emitted, shot, received, absorbed, unshot as one
/// solve's would be); shots count both levels. Where the coarse atlas would hold as many texels as the
/// output's, it is one solve on the output's (data: solveTexels = its texels, no lamp shots counted). `data` receives the levels' figures when not null.
SolveResult solveTwoLevel(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                          const AtlasParams& atlasParams, const TwoLevelParams& levels,
                          const SolverParams& settings, const EglContext& gl, Context& ctx,
                          const SolveControls& controls = {}, TwoLevelData* data = nullptr);

}  // namespace cpgi
