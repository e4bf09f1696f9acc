// GPU progressive radiosity (thesis ch. 6, after Coombe, Harris & Lastra 2004) over a lightmap atlas:
// every atlas texel is a sub-patch with radiosity and residual (unshot) textures on the GPU. One shot:
// select the patch with the largest unshot power (emitters first), build a residual pyramid over it
// (sub-shooters), render an item buffer of patch IDs from its centre, and let every visible receiver texel
// gather ρ ΔB F(dA → A_s) with the disk approximation. Stops when the unshot power falls under a fraction of
// the emitted power.
//
// Requires a current OpenGL 4.5 context (EglContext) on the calling thread.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/shot_settings.h"
#include "radiosity/lightmap/solve_result.h"

namespace cpgi {

enum class Visibility {
  Hemisphere,  ///< the thesis's one-pass hemispherical item buffer (curved-edge error on coarse meshes)
  Hemicube,    ///< five perspective faces: straight edges stay straight
};

const char* visibilityName(Visibility v);

/// The user's settings of a solve (the CLI binds them to flags, apps/options.cpp): the shared ones
/// (stop, regions, pieces; shot_settings.h) and the item buffers'.
struct SolverParams : ShotSettings {
  Visibility visibility = Visibility::Hemicube;
  /// Hemisphere: the buffer's edge in pixels. Hemicube: twice a face's edge (faces of N/2, so both modes
  /// hold about N² pixels). In [16, GL_MAX_TEXTURE_SIZE], even.
  int itemBuffer = 512;
  /// Item-buffer neighbourhood radius for the visibility test: 0 → the receiver's own pixel, with the
  /// plane test of shaders/visibility.glsl (right on average at silhouettes); 1 → also the thesis's
  /// 3×3 (a texel within a pixel of a silhouette counts as lit: +15 % in a room lit through doors).
  int neighbourhood = 0;
  /// Each shot draws every visibility region's eye at a texel with probability ∝ its unshot power (a
  /// low-discrepancy draw per shot), so that visibility from a region is right on average over its power.
  /// Off: the fixed eye of shooter_layout.h, chosen clear of nearby occluders, which sees more than most of
  /// the region does (a lamp under a ceiling: the ceiling's shots delivered 1.1–1.2× their power).
  bool jitteredEyes = true;
  /// > 0: the lamps (patches whose material emits) shoot first on the CPU, by this many shadow rays per
  /// texel and lamp, 16× in penumbrae (radiosity/lightmap/lamp_light.h), and not through item buffers. 0:
  /// item buffers, as every other shot. A multiple of 4.
  int lampRays = 0;
  /// Hemicube: each shot lists per face the triangles that may show in it (shaders/item_cull.comp) and
  /// draws only those, bit-identical to drawing every triangle into every face (off: that), which on
  /// llvmpipe took 1.8× as long (bench/RESULTS.md, "Item buffers drawn indexed and culled").
  bool cullItemBuffers = true;
  /// Wait for the GPU after every pass and record per-pass times in the Context ("solve: receive", ...).
  /// Costs some speed on a real GPU; on llvmpipe the passes run synchronously anyway.
  bool profilePasses = false;
};

class SolverPrograms;

/// A first shot made before the solve, elsewhere (radiosity/gpu/two_level_solve.h: the lamps shot on the
/// output's atlas, the rest solved on a coarser one): the solve starts after it, as after any shot.
struct PriorShot {
  std::span<const glm::vec3> irradiance;  ///< per atlas texel, W/m², what it delivered
  double emitted = 0.0;                   ///< W (R + G + B) its sources emitted, all counted as shot
};

/// What a caller driving the solver sets, apart from the user's settings: the cell solver
/// (radiosity/cells/) reads what crosses its portals, stops on a per-patch bound and emits with lobes.
/// SolveControls::acceptStop: the unshot share at which a refused stop is asked again, as a fraction of
/// the share it was refused at.
inline constexpr double kStopRecheck = 0.7;

struct SolveControls {
  /// Also read back every texel's received irradiance and unshot residual (SolveResult::incident,
  /// ::residual): what a cell solve hands on through its portals (radiosity/cells/cell_solver.h).
  bool readTransfer = false;
  /// Also stop when the next shooter's unshot power (W, summed over R, G, B) is below this: a bound per
  /// patch rather than a fraction of the input, so a cell solve lit through a door stops where a solve of
  /// the whole scene would leave such small patches unshot (radiosity/cells/cell_solver.h). 0: off.
  double minShotPower = 0.0;
  /// > 0: a shot is strong (SolverParams::strongShotRegions) when it carries at least this power (W, R + G
  /// + B) rather than strongShotFraction of the solve's own emitted power. A cell solve lit through a
  /// door measures its shots against the whole scene's light, as a global solve would: against its own
  /// small input nearly every shot was strong, 16 item buffers each, and spot-door's cells took 3× a
  /// global solve's time per shot (radiosity/cells/cell_round.h, roundBudget).
  double strongShotPower = 0.0;
  /// Whether the emitters' own shots are a lamp's (resampled at beam edges and near the emitter, with
  /// jittered eyes per strong region: receive.comp, uLampShot). A cell solve's emitters are its portals,
  /// re-emitting what its neighbours sent, which a global solve carries by plain reflector shots; shot as
  /// lamps, they cost seed1's cells bake 2.4× the CPU for no gain in any cell (issue 11, session 21).
  bool emittersAreLamps = true;
  /// Directional emission (radiosity/gpu/emission_lobes.h): shooters emit with the per-texel lobes of
  /// `emissionLobes` (one per atlas texel; zero or none = Lambertian), and every texel accumulates the
  /// direction moments of what it receives (SolveResult::arrivals). Off: the passes are built without it
  /// and cost and results are those of the plain solver. Lobes without it are an error.
  bool directionalEmission = false;
  std::span<const glm::vec4> emissionLobes = {};
  /// With directional emission, whether the receivers accumulate the direction moments of what they
  /// receive (SolveResult::arrivals; directional portals carry them). Binned portals trace their bins
  /// instead, so without the moments the shooters with no lobe shoot with the plain programs: in
  /// spot-door's cells bake every reflector shot cost 1.6× the plain one for moments nobody read.
  bool arrivalMoments = true;
  /// Binned emission (radiosity/gpu/emission_bins.h) for the texels whose lobe is binnedLobe(slot): slot
  /// after slot, kArrivalBins factors f each, normalised to mean 1 (normalisedEmissionBins).
  std::span<const float> emissionBins = {};
  /// Start after this shot: ρ × its irradiance unshot, its power emitted and shot. The atlas's emission is
  /// shot as usual and the scene's punctual lights are not (the prior shot stands for them). Null: none.
  const PriorShot* priorShot = nullptr;
  /// Receive only at the texels flagged here (one per atlas texel, non-zero: receives; empty: every texel):
  /// a lamp's shot evaluated at the output's texels only where a coarser shot found its light varying
  /// (radiosity/gpu/refined_lamp_shot.h). Such a shot's sums over part of its receivers cannot check what it
  /// delivered, so it needs `patchShotScale`: per patch, the factor that patch's shots are scaled by instead
  /// of the solver's own check (SolveResult::shotScales of the coarser shot).
  std::span<const uint8_t> receivers = {};
  std::span<const float> patchShotScale = {};
  /// Also read back what the lamps' shots found at each texel (SolveResult::lampFlags).
  bool readLampFlags = false;
  /// Programs compiled by an earlier solve on this context (identical results); null: compiled for this one.
  SolverPrograms* programs = nullptr;
  /// Asked each time the unshot share reaches the stop (SolverParams::unshotFraction), with the radiosity
  /// and the unshot residual so far (per atlas texel): true stops; false shoots on and asks again once the
  /// share has fallen to kStopRecheck of what it was (SolveResult::stopChecks counts the asks). The bake's
  /// stop per cell (radiosity/gpu/ambient.h, ambientShares). Empty: stop.
  std::function<bool(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual)>
      acceptStop = {};
  /// The number the shots count from in the eyes' draw and the item buffer's turn (jitteredEyes): 0 for a
  /// solve; bench/shot_probe.cpp averages one shot over many draws with it.
  uint32_t firstShotNumber = 0;
  /// Shoot no more after this instant (bake --time-limit): the result is what the shots so far gave,
  /// with SolveResult::timedOut set and what is left counted as unshot, so the energy still balances.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

/// The solver's GLSL programs, compiled once and reused by every solve given the same object (a cell
/// solve runs once per cell and round). llvmpipe translates a program to machine code at its first draw
/// or dispatch, so a fresh set per solve costs setup time and slower first shots. Belongs to the
/// context (and thread) current when the first solve used it.
class SolverPrograms {
 public:
  SolverPrograms();
  ~SolverPrograms();
  SolverPrograms(const SolverPrograms&) = delete;
  SolverPrograms& operator=(const SolverPrograms&) = delete;
  struct Set;  // gpu_solver.cpp
  /// The programs for `settings` with or without directional emission (their #defines: visibility mode,
  /// ...), compiled at first use.
  const Set& get(const SolverParams& settings, bool directionalEmission, bool binnedEmission = false);

 private:
  std::map<std::string, std::unique_ptr<Set>> sets_;  // by the programs' #defines
};

/// Solves the atlas with the user's `settings` and the caller's `controls`. `scene` supplies occluders:
/// every scene triangle is drawn in the item buffer, those outside the atlas with no patch (they block
/// light but receive none). Its punctual lights (Scene::lights) are shot first, exactly, on the CPU
/// (radiosity/lightmap/direct_light.h): the solve starts from their reflected light as unshot radiosity and
/// counts their power as emitted and shot. Throws InputError for bad settings, SystemError for GL failures.
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                             const EglContext& gl, Context& ctx, const SolveControls& controls = {});

}  // namespace cpgi
