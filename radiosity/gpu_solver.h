// GPU progressive radiosity (thesis ch. 6, after Coombe, Harris & Lastra 2004) over a lightmap atlas:
// every atlas texel is a sub-patch with radiosity and residual (unshot) textures on the GPU. One shot:
// select the patch with the largest unshot power (emitters first), build a residual pyramid over it
// (sub-shooters), render an item buffer of patch IDs from its centre, and let every visible receiver texel
// gather ρ ΔB F(dA → A_s) with the disk approximation. Stops when the unshot power falls under a fraction of
// the emitted power.
//
// Requires a current OpenGL 4.5 context (EglContext) on the calling thread.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/atlas.h"
#include "radiosity/egl_context.h"

namespace cpgi {

enum class Visibility {
  Hemisphere,  ///< the thesis's one-pass hemispherical item buffer (curved-edge error on coarse meshes)
  Hemicube,    ///< five perspective faces: straight edges stay straight
};

const char* visibilityName(Visibility v);
/// Parses "hemisphere" / "hemicube"; throws InputError("--visibility", ...) otherwise.
Visibility parseVisibility(const std::string& name);

struct SolverParams {
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
  /// Stop when the unshot power is at most this fraction of the emitted power, in (0, 1).
  double unshotFraction = 0.01;
  /// Stop after this many shots whatever the unshot fraction (>= 1).
  int maxShots = 100000;
  /// A shooter piece (a region, then a node of its residual pyramid, then a texel) counts as one piece
  /// for receivers farther than this many times its bounding radius; nearer receivers use its four
  /// children. >= 1.
  float farField = 2.0f;
  /// A shooter is split into visibility regions about this long (m), each with its own item buffer
  /// drawn from its centre, so a lamp just under a ceiling's centre does not hide the whole ceiling.
  float regionSize = 1.0f;
  /// At most this many regions per chart edge, 1..4 (so at most 16 item buffers per shot).
  int maxRegions = 2;
  /// Shots carrying at least `strongShotFraction` of the emitted power use up to `strongShotRegions`
  /// per edge (1..4; 0 = maxRegions). Such shots hold most of the light, and one eye per metres-wide
  /// region is what gives light through a door from a large shooter a hard, misplaced edge; the many
  /// weak shots after them keep the cheaper layout.
  /// Measured on seed3 (density 10, unshot 1 %, error without lamps against the reference, CPU seconds):
  /// 2 regions 16.5 % / 17.9 s; all shots 4: 12.4 % / 39.1 s; strong ≥ 1 %: 13.4 % / 20.4 s;
  /// strong ≥ 0.2 % (the default): 12.4 % / 25.5 s.
  int strongShotRegions = 4;
  double strongShotFraction = 0.002;
  /// Wait for the GPU after every pass and record per-pass times in the Context ("solve: receive", ...).
  /// Costs some speed on a real GPU; on llvmpipe the passes run synchronously anyway.
  bool profilePasses = false;
  /// Also read back every texel's received irradiance and unshot residual (SolveResult::incident,
  /// ::residual): what a cell solve hands on through its portals (radiosity/cell_solver.h).
  bool readTransfer = false;
  /// Also stop when the next shooter's unshot power (W, summed over R, G, B) is below this: a bound per
  /// patch rather than a fraction of the input, so a cell solve lit through a door stops where a solve of
  /// the whole scene would leave such small patches unshot (radiosity/cell_solver.h). 0: off.
  double minShotPower = 0.0;
  /// Directional emission (radiosity/emission_lobes.h): shooters emit with per-texel lobes (the
  /// emissionLobes argument of solveProgressive; Lambertian where zero), and every texel accumulates the
  /// direction moments of what it receives (SolveResult::arrivals). Off: the passes are built without it
  /// and cost and results are those of the plain solver.
  bool directionalEmission = false;
};

/// Energy bookkeeping, W summed over R, G, B. At every step emitted = absorbed + unshot + escaped,
/// where escaped is the part of the shot power no receiver caught (open scenes, form-factor error).
struct EnergyTotals {
  double emitted = 0.0;
  double shot = 0.0;      ///< power that left shooters so far
  double received = 0.0;  ///< Σ irradiance × area over all texels
  double absorbed = 0.0;  ///< Σ (1 − ρ) irradiance × area
  double unshot = 0.0;    ///< Σ residual × area
  /// Σ over shots of max(0, received − shot) beyond a float tolerance: light the solve made up, which a
  /// correct solve never does (a shooter's form factors sum to at most 1). Non-zero is a defect.
  double created = 0.0;
  /// The largest received / shot of any one shot (≤ 1 when no energy is created).
  double worstShotGain = 0.0;
  double escaped() const { return shot - received; }
};

struct SolveResult {
  std::vector<glm::vec3> radiosity;  ///< per atlas texel (W/m²), padding 0, not dilated
  /// With SolverParams::readTransfer, per atlas texel: irradiance received over the whole solve (W/m²;
  /// a texel of albedo 0 keeps all of it, e.g. a portal) and the residual still unshot at the end.
  std::vector<glm::vec3> incident, residual;
  /// With SolverParams::directionalEmission, per atlas texel: the arrival moments of everything it received
  /// (emission_lobes.h, arrivalMoment), to be fitted into a lobe on the far side of a portal.
  std::vector<glm::vec4> arrivals;
  int shots = 0;
  double unshotFraction = 0.0;  ///< unshot / emitted at the end (0 when nothing emits)
  EnergyTotals energy;
  std::vector<EnergyTotals> history;  ///< after the initial state and after every shot
  std::vector<int> shooters;          ///< the patch of every shot, in order
  double seconds = 0.0;               ///< solve time (upload, shots, read back)
  double setupSeconds = 0.0;          ///< programs and textures
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
  /// The programs for `params` (their #defines: visibility mode, ...), compiled at first use.
  const Set& get(const SolverParams& params);

 private:
  std::map<std::string, std::unique_ptr<Set>> sets_;  // by the programs' #defines
};

/// Solves the atlas. `scene` supplies occluders: every scene triangle is drawn in the item buffer, those
/// outside the atlas with no patch (they block light but receive none).
/// Throws InputError for bad params, SystemError for GL failures.
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& params,
                             const EglContext& gl, Context& ctx);
/// The same, with programs compiled by an earlier solve on this context (identical results).
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& params,
                             const EglContext& gl, Context& ctx, SolverPrograms& programs);

/// The same with SolverParams::directionalEmission on: `emissionLobes` holds one packed lobe per atlas
/// texel (emission_lobes.h; zero = Lambertian) for the emission and whatever residual the texel shoots.
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& params,
                             const std::vector<glm::vec4>& emissionLobes, const EglContext& gl, Context& ctx);
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& params,
                             const std::vector<glm::vec4>& emissionLobes, const EglContext& gl, Context& ctx,
                             SolverPrograms& programs);

}  // namespace cpgi
