// `bake --density auto` (issue 13): texels where the light varies, few where it is flat. The lamps,
// punctual lights and sky shoot once onto a pilot atlas of a fixed density; the detail of that direct
// light (shadow, beam and penumbra edges, the fall-off near a lamp: radiosity/lightmap/light_density.h)
// and the contacts the light that bounces darkens (radiosity/lightmap/contact_density.h) set each
// surface's texels per metre. The interreflection needs no more than those: it is smooth elsewhere, and
// solved on a coarser atlas still (two_level_solve.h). The result is one ordinary atlas with a density
// per chart, which any engine reads.
#pragma once

#include <string>
#include <vector>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/light_density.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

/// The most valid texels `bake --density auto` lays out by default (--max-texels): past it, every surface's
/// density is scaled down alike to fit (fitTexelBudget). A daylit house asked for 2.96 M texels (sun
/// shadows at 40 a metre over its whole floor plan and the furniture's contacts), whose sky gather and
/// solve did not finish in 25 minutes (issue 46).
inline constexpr size_t kDefaultMaxTexels = 1'000'000;

struct AutoDensityParams {
  /// The pilot atlas's texels per metre: its texel must see a shadow's edge to know where one is. Lower
  /// where that would lay out more than maxTexels texels over the scene's area (the pilot's time and
  /// memory grow with the area, bounded by the budget).
  float pilotDensity = 10.0f;
  /// The output's texel budget (bake --max-texels); the pilot keeps to kPilotTexelShare of it; 0: none.
  size_t maxTexels = kDefaultMaxTexels;
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
  float pilotDensity = 0.0f;    ///< its texels per metre (under AutoDensityParams::pilotDensity for a budget)
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

/// The share of the output's texel budget the pilot lays out at most: its sky gather and shot cost what the
/// output's do per texel, and it only has to find where the light varies (OpenArena's aggressor in metres:
/// a pilot of 1.38 M texels at 10 a metre took 332 s of a 300 s time limit before the output's own gather).
inline constexpr double kPilotTexelShare = 0.25;

/// The pilot's texels per metre: params.pilotDensity, or lower so that the scene's area (one side of each
/// triangle) takes at most kPilotTexelShare × params.maxTexels texels at it.
float pilotDensity(const Scene& scene, const AutoDensityParams& params);

/// The valid texels `density` (per scene triangle; empty: `uniform` everywhere) asks, by the area:
/// Σ area × density² (the charts' borders and rounding not counted).
double texelsByArea(const Scene& scene, const std::vector<float>& density, float uniform);

/// What fitTexelBudget did.
struct TexelBudget {
  size_t asked = 0;    ///< valid texels at the densities asked (estimated from the area when over budget)
  float scale = 1.0f;  ///< every density's factor (1: within the budget as asked)
  /// One line saying so when scaled ("" otherwise): the texels asked, the budget, the scale, the texels.
  std::string note;
};

/// The output's atlas with `params` (per-triangle densities in params.triangleDensity), within `maxTexels`
/// valid texels (0: no limit): over it, every triangle's density is scaled by one factor, first by the
/// texels the area asks (Σ area × density² over the triangles), then again by the atlas built until it
/// fits (the charts' borders and rounding). `params.triangleDensity` is left with the densities used.
/// Each layout stops at `deadline` as buildAtlas does (AtlasLayoutStopped).
LightmapAtlas fitTexelBudget(
    const Scene& scene, const QuadSet& quads, AtlasParams& params, size_t maxTexels, Context& ctx,
    TexelBudget* budget = nullptr,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

}  // namespace cpgi
