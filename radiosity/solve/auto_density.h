// `bake --density auto` (issue 13): texels where the light varies, few where it is flat. The lamps,
// punctual lights and sky shoot once onto a pilot atlas of a fixed density; the detail of that direct
// light (shadow, beam and penumbra edges, the fall-off near a lamp: radiosity/lightmap/light_density.h)
// and the contacts the light that bounces darkens (radiosity/lightmap/contact_density.h) set each
// surface's texels per metre. The interreflection needs no more than those: it is smooth elsewhere, and
// solved on a coarser atlas still (two_level_solve.h). The result is one ordinary atlas with a density
// per chart, which any engine reads.
#pragma once

#include <vector>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/light_density.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

struct AutoDensityParams {
  /// The pilot atlas's texels per metre: its texel must see a shadow's edge to know where one is.
  float pilotDensity = 10.0f;
  LightDensityParams light = {};
  /// Surfaces with something closer than 2 / light.minDensity in front of them get about half the gap
  /// per texel, up to maxContactDensity, for the bounced light's contact shadow.
  bool contacts = true;
  /// The most texels per metre a contact asks. seed3's room C (a lamp 1 cm under the ceiling, 16 columns
  /// on the floor) against a 64² reference: rel RMSE 4.92 % at 10 (the pilot's), 3.59 % at 20.
  float maxContactDensity = 20.0f;
};

struct AutoDensityData {
  size_t pilotTexels = 0;       ///< valid texels of the pilot atlas
  double pilotSeconds = 0.0;    ///< its atlas and the direct light's shot
  size_t contactTriangles = 0;  ///< triangles whose density their contacts set above their light's
};

/// Per scene triangle the texels per metre for the output atlas (AtlasParams::triangleDensity), within
/// [light.minDensity, light.maxDensity]. `atlasParams`: the output's other settings (chart limits,
/// memory), which the pilot atlas shares. Throws InputError when the pilot passes the memory limit.
std::vector<float> chooseAutoDensity(const Scene& scene, const QuadSet& quads, const AtlasParams& atlasParams,
                                     const AutoDensityParams& params, const SolverParams& settings,
                                     ShotEngine& engine, Context& ctx, const SolveControls& controls = {},
                                     AutoDensityData* data = nullptr);

}  // namespace cpgi
