// The light solved at the resolution it varies at (issue 13), not at every output texel. A lamp's own shot
// draws sharp shadows and penumbrae, so the lamps shoot onto the output atlas itself; the light they
// leave on the surfaces is then carried, as area-weighted means, to a coarser atlas of the same scene,
// where the many shots of the interreflection (most of a solve's shots, each as costly as a lamp's per
// receiver texel) are solved, and their irradiance comes back to the output texels by bilinear
// interpolation within each chart. An output texel's radiosity is E + ρ (direct + indirect): the
// direct at full resolution, the indirect at the solve's.
#pragma once

#include <functional>
#include <string>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/refined_lamp_shot.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

struct TwoLevelParams {
  /// The coarse atlas's texel density (texels per metre; its other settings are the output atlas's).
  float solveDensity = 5.0f;
  /// Surfaces with something close in front of them solved finer, up to the output's texels
  /// (radiosity/lightmap/contact_density.h).
  bool refineContacts = true;
  /// The most texels per metre a contact asks of the coarse atlas, where the output is finer still (a
  /// --density auto bake gives small furniture parts 100–500 a metre): the furnished house's
  /// interreflection held 337 029 solve texels up to the output's, 244 896 up to 20. At 10, seed3's room
  /// C (16 columns on its floor) read 5.52 % against a 64² reference, 3.59 % at 20 (bench/RESULTS.md).
  float maxContactDensity = 20.0f;
  /// The coarse atlas's fewest texels along a quad chart's edge (a loose triangle keeps 2, its one texel
  /// inside): the interreflection on a book's spine is one value, and a furnished house's 22 000 small
  /// charts at the output's 2 × 2 were 115 000 of its solve texels at 5 a metre, 83 000 at 1.
  int minTexels = 1;
  /// At most this many valid texels in the coarse atlas (0: no bound): past it, the solve density and the
  /// contacts' densities are scaled down together until it fits. Every shot of the interreflection visits
  /// every coarse texel, so a large level at solveDensity made each shot as costly as its output's:
  /// OpenArena's oa_dm7 (16 700 m² of surface) held 651 320 solve texels at 5 a metre against a house's 143
  /// 000–163 000.
  size_t maxSolveTexels = 0;
  /// The lamps' shot on the output atlas: at a coarser one first, then at the output's texels where that
  /// one's light varies (refined_lamp_shot.h).
  RefinedLampParams lamps = {};
};

/// The coarse atlas's texel budget of an automatic solve density (TwoLevelParams::maxSolveTexels): above
/// the houses' 143 000–163 000 at 5 texels a metre, so they keep it.
inline constexpr size_t kAutoSolveTexels = 200'000;

/// What the two levels were, beside the SolveResult.
struct TwoLevelData {
  size_t solveTexels = 0;        ///< valid texels of the coarse atlas
  size_t refinedTriangles = 0;   ///< triangles solved finer than solveDensity (contacts)
  int lampShots = 0;             ///< shots on the output atlas
  double lampSeconds = 0.0;      ///< their solve
  double solveSeconds = 0.0;     ///< the coarse solve
  size_t lampCoarseTexels = 0;   ///< valid texels of the lamps' coarse shot (0: shot on the output's alone)
  size_t lampRefinedTexels = 0;  ///< output texels the lamps shot at their own resolution
  int indirectItemBuffer = 0;    ///< the interreflection's item buffer (indirectItemBuffer())
  std::string indirectBackend;   ///< the engine of the interreflection (ShotEngine::name)
  float solveDensity = 0.0f;     ///< the coarse atlas's texels per metre (maxSolveTexels may lower it)
  /// The interreflection's set-up (its contacts' rays, coarse atlas and engine): its estimate (wall s, at the
  /// load observed when last asked), its wall and CPU seconds (the contacts, the atlas and the engine's
  /// set-up; not the lamps' shot between them), and how it
  /// ended: "" whole, "stopped" (the deadline came during the engine's set-up or before its first shot) or
  /// "not started" (the engine's set-up never began: the deadline came first, or its estimate would have
  /// ended past it, said in a warning).
  double setupEstimate = 0.0;
  double setupSeconds = 0.0, setupCpuSeconds = 0.0;
  std::string setupStop;
};

/// What a two-level solve's set-up has to do: the scene's triangles (the contacts' rays, the ray scene),
/// the coarse atlas's valid texels and patches (its layout, the shooters' eyes, the engine's buffers).
struct SetupWork {
  size_t triangles = 0, texels = 0, patches = 0;
};
/// The CPU seconds of that set-up on an unloaded core, with room to spare (bench/RESULTS.md, "The solve's
/// engine set-up inside the limit"): times the load (SolveControls::load), its wall seconds.
double setupCpuSeconds(const SetupWork& work);

/// The item buffer of the interreflection on the coarse atlas: `itemBuffer` (the user's, sized for 10
/// texels per metre) scaled by solveDensity / 10, at most itemBuffer, at least 64, even. What a pixel
/// must resolve is a receiver texel: at 5 texels a metre a 256 buffer still gives a 20 cm texel 4 × 4
/// pixels 4 m away, and it halves the solve (seed3 at 64² per quad: 32.6 → 15.5 s, every room within
/// 0.8 points of the 512's ratio and RMSE; openings at 10 texels a metre, its far room C 1.017 → 0.994
/// ± 0.013 of the eye sequences' spread).
int indirectItemBuffer(int itemBuffer, float solveDensity);

/// A solve of the interreflection on the coarse atlas in place of the progressive solver's: a cells bake
/// solves it cell by cell (radiosity/cells/cell_solver.h, solveCellsTwoLevel). It gets the coarse atlas,
/// the parameters it was built with and the controls (priorShot: the lamps' light averaged onto it), and
/// returns the radiosity over it and, with controls.readTransfer, the residual; without an irradiance
/// (SolveResult::incident) its radiosity less the lamps' reflected light is what comes back to the output.
using CoarseSolve = std::function<SolveResult(const LightmapAtlas& coarse, const AtlasParams& coarseParams,
                                              const SolveControls& controls)>;

/// Solves `atlas` (the output's, built with `atlasParams` from `quads`) in two levels: the lamps on
/// `engines.lamps`, the interreflection on `engines.reflections` (on `lamps` where it needs what the
/// other cannot do, EngineFeatures). The result is over
/// the output atlas: radiosity, and with controls.readTransfer the incident and residual (the coarse
/// solve's, interpolated); energy is the whole solve's (emitted, shot, received, absorbed, unshot as one
/// solve's would be); shots count both levels. Where the coarse atlas would hold as many texels as the
/// output's, it is one solve on the output's (data: solveTexels = its texels, no lamp shots counted). `data`
/// receives the levels' figures when not null.
SolveResult solveTwoLevel(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                          const AtlasParams& atlasParams, const TwoLevelParams& levels,
                          const SolverParams& settings, const ShotEngines& engines, Context& ctx,
                          const SolveControls& controls = {}, TwoLevelData* data = nullptr,
                          const CoarseSolve& solveCoarse = {});

}  // namespace cpgi
