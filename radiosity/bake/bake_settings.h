// Every setting of a bake in one place, with the one set of defaults the library and the command line
// share (Cycles' SessionParams): `cpgi bake` parses its flags into a BakeSettings and hands it to bake()
// (bake.h); a library caller who fills nothing gets the command line's default bake. The settings that
// the libraries below already define with their units and limits (AtlasParams, SolverParams, ...) are
// nested here as they are; what only a bake decides (the method, the stop per cell, two levels, the time
// limit) is documented on its field. A new bake option is a field here (with its JSON name in
// bake_settings.cpp) and a flag in apps/bake_command.cpp.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene_io.h"
#include "core/sky.h"
#include "decomposition/decompose.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/lightmap/views.h"
#include "radiosity/solve/ambient.h"
#include "radiosity/solve/auto_density.h"
#include "radiosity/solve/refined_lamp_shot.h"

namespace cpgi {

enum class BakeMethod {
  Global,  ///< one progressive solve over the whole scene (design.md §1, ch. 6)
  Cells,   ///< cell by cell, light handed on through portals (ch. 8, radiosity/cells/cell_solver.h)
};
const char* bakeMethodName(BakeMethod m);  ///< "global", "cells"

/// How a two-level solve shoots its interreflection (radiosity/solve/two_level_solve.h).
enum class IndirectSolver {
  Auto,  ///< rays where the GL device is a software rasterizer (llvmpipe, softpipe), else item buffers
  Gpu,   ///< item buffers on the GL device
  Rays,  ///< Embree rays on the CPU (radiosity/cpu/ray_shot_engine.h)
};
const char* indirectSolverName(IndirectSolver s);  ///< "auto", "gpu", "rays"

/// How every shot of a bake sees (radiosity/solve/shot_engine.h).
enum class Backend {
  Auto,  ///< GL item buffers where an OpenGL 4.5 context can be made (EGL), else Embree rays
  Gl,    ///< GL item buffers (radiosity/gpu/gl_shot_engine.h); fails without a GL device
  Rays,  ///< Embree rays on the CPU (radiosity/cpu/ray_shot_engine.h), no GL at all: the lamps by shadow
         ///< rays, every portal model as on GL
};
const char* backendName(Backend b);  ///< "auto", "gl", "rays"

/// --solve-density auto (SolverSettings::solveDensity): chosen by the bake (bake.h, chosenSolveDensity).
inline constexpr float kAutoSolveDensity = -1.0f;

/// The lamps' first shot of a bake: 64 shadow rays per texel and lamp, 16× in penumbrae
/// (radiosity/lightmap/lamp_light.h); SolverParams' own default stays item buffers for every shot, as the
/// thesis. Measured at the default stop (density 10, per cell against `cpgi reference --texels 4000 --spp
/// 4096`): spot-door's rooms 0.973 / 1.013 (13.4 / 9.7 % per texel) with item buffers, 1.016 / 0.996
/// (3.7 / 0.5 %) with rays; seed3's B 1.023 → 0.984; the other seed cells within 0.002; 1.2–1.35× the CPU
/// seconds; on the 108-room office's 36 lamps the lamps' shot costs 1.5× their item-buffer shots (256
/// rays: 5×).
inline constexpr int kBakeLampRays = 64;
/// The portal light of a cells bake: binned; CellSolveParams' own default stays the thesis's diffuse
/// portal. Measured at the default stop (density 10, per cell against `cpgi reference --texels 4000
/// --spp 4096`, ratio of means and per-texel RMSE without the reference's noise; bench/RESULTS.md, session
/// 17): openings' room C, lit through a narrow door, 0.965 (21.3 %) diffuse, 0.984 (8.4 %) directional,
/// 1.006 (4.5 %) binned; the rooms behind doors in seed1–3 3.4–3.6 % binned where one lobe gave 4.2–4.8 %;
/// 1.04–1.25× the wall seconds of one lobe.
inline constexpr PortalLight kBakePortalLight = PortalLight::Binned;

struct BakeSettings {
  /// The scene and how it is read (used by loadBakeScene and in messages and report.json).
  struct Input {
    std::string scene;       ///< path of the .glb, .gltf or .obj, in metres; names the scene in every message
    LoadOptions load;        ///< --strict, --emit, --albedo, --allow-outside-files, file and triangle limits
    bool allowDark = false;  ///< bake a scene nothing lights (black) instead of refusing it
  } input;

  /// The output's lightmap atlas.
  struct Atlas {
    /// Texels per quad or per metre, chart limits. Its memoryLimit is Limits::maxMemory's (set by the
    /// bake) and its triangleDensity the automatic density's.
    AtlasParams params;
    /// The texels per metre chosen per surface where the lamps' light varies (radiosity/gpu/
    /// auto_density.h) instead of params.density everywhere; false with params.texelsPerQuad > 0.
    bool densityAuto = true;
    AutoDensityParams autoDensity;  ///< with densityAuto
  } atlas;

  /// The progressive solve and its stop.
  struct Solver {
    /// Stop (unshot fraction, max shots), visibility, item buffer, regions; lamp rays kBakeLampRays.
    SolverParams params = [] {
      SolverParams p;
      p.lampRays = kBakeLampRays;
      return p;
    }();
    /// The interreflection solved on an atlas of this many texels per metre, the lamps' light on the
    /// output's (radiosity/solve/two_level_solve.h); 0: one level; kAutoSolveDensity: chosen by the bake
    /// (two levels past 100 000 output texels or with the automatic density; cell jobs and on-demand
    /// cells: one level).
    /// In [0, 10000] or kAutoSolveDensity.
    float solveDensity = kAutoSolveDensity;
    /// With two levels: the lamps shoot first on an atlas this many times coarser, then at the output's
    /// texels where its light varies (radiosity/solve/refined_lamp_shot.h). In [1, 1000].
    float lampCoarsening = RefinedLampParams{}.coarsening;
    IndirectSolver indirect = IndirectSolver::Auto;  ///< with two levels: who shoots the interreflection
    Backend backend = Backend::Auto;                 ///< who shoots everything else (and, with Rays, all)
    /// The ambient term for the power still unshot at the stop (radiosity/solve/ambient.h).
    bool ambient = true;
    /// The stop per cell: at the unshot stop, shoot on (cells: run more rounds) while in some cell the
    /// ambient term would be more than this share of its light. In [0, 1]; 0: the unshot stop alone.
    double ambientShare = kDefaultAmbientShare;
  } solver;

  /// Cell by cell (method Cells), its cells and what is baked of them.
  struct Cells {
    BakeMethod method = BakeMethod::Global;
    /// With Cells: "auto" (the automatic decomposition with `decompose`), the scene file itself (its own
    /// cells or room volumes), a decompose output folder or another glTF of the scene (loadBakeScene);
    /// empty: the scene's own cells when it has them, else "auto".
    std::string source;
    /// Read: portals (kBakePortalLight), lobeMinWidth, portalBinRays, portalDensityScale, maxRounds, jobs.
    /// Its solver and atlas are Solver's and Atlas's; the rest is set by the bake.
    CellSolveParams params = [] {
      CellSolveParams p;
      p.portals = kBakePortalLight;
      return p;
    }();
    decomp::DecomposeParams decompose;  ///< with source "auto" (or room volumes); memoryLimit: Limits'
    /// On demand (radiosity/cells/cell_selection.h): bake only these cells ("A,B"), or those within
    /// `depth` portals of the cell holding the point `around` ("X,Y,Z", metres); empty: every cell.
    std::string onlyCells;
    std::string around;
    int depth = 0;                                 ///< >= 0
    BoundaryMode boundary = BoundaryMode::Coarse;  ///< what the cells next to the baked ones do
  } cells;

  /// Light from outside an open building (core/sky.h): none by default.
  SkyRequest sky;

  /// What is written.
  struct Output {
    /// The result folder (lightmap.exr, lightmap.png, lightmap_irradiance.*, baked.glb, preview.glb,
    /// report.json, report.html, view-*),
    /// swapped in as a set at the end (core/output_dir.h); empty: nothing is written, bake() returns it.
    std::string folder;
    ViewParams views;           ///< the view-*.png / .exr pictures
    EngineOutputParams engine;  ///< baked.glb and the irradiance lightmap for engines
  } output;

  /// What the bake may take.
  struct Limits {
    /// Seconds of wall clock from the bake's start (BakeRun::start) after which shooting stops and a
    /// partial result is written; 0: none. In [0, 1e9].
    double timeLimit = 0.0;
    /// Bytes the bake may take (atlas, item buffers, decomposition), refused up front; 0: 75 % of this
    /// machine's memory (core/memory_limit.h).
    uint64_t maxMemory = 0;
    /// Refuse up front a scene whose albedo would need more bounces than the solve's shots allow in a
    /// reasonable time (radiosity/lightmap/bounce_limit.h), unless the time limit bounds it; false when
    /// the caller bounds the solve by Solver::params.maxShots itself (the command line's --max-shots).
    bool refuseEndless = true;
  } limits;
};

/// BakeSettings as JSON (every field, under its C++ name; enums by their names) and back; a field missing
/// from the JSON keeps its default. bakeSettingsFromJson throws InputError("bake settings", ...) on a
/// wrong type or an unknown name. The cell jobs keep them in plan.json (radiosity/bake/bake_jobs.h).
nlohmann::json bakeSettingsJson(const BakeSettings& s);
BakeSettings bakeSettingsFromJson(const nlohmann::json& j);

}  // namespace cpgi
