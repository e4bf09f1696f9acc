// What `cpgi bake` and `cpgi reference` share besides the output files
// (radiosity/lightmap/lightmap_output.h): report.json, whose common keys
// (design.md §3) are written here once, so the two reports stay comparable key for key; each command adds its
// own keys beside them.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/context.h"
#include "core/output_dir.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/solve_result.h"

namespace cpgi {

/// The figures every lightmap producer reports.
struct LightmapRun {
  std::string method;  ///< "global", "cells" or "reference"
  std::string scene;
  double seconds = 0.0;       ///< the whole command
  double solveSeconds = 0.0;  ///< the solve (or trace) alone
  const LightmapAtlas* atlas = nullptr;
  AtlasParams atlasParams;
  size_t triangles = 0, quads = 0;
  int shots = 0;
  double unshotFraction = 0.0;
  size_t cells = 1, portals = 0;
  std::vector<std::string> views;
  /// The names of the indices in lightmap.exr's "cell" channel (radiosity/lightmap/cell_channel.h).
  std::vector<std::string> cellNames;
};

/// report.json's common keys: method, scene, seconds, solve_seconds, texels, shots, unshot_fraction,
/// cells, portals, atlas {width, height, patches, texels_per_quad, density}, triangles, quads, timings
/// (seconds per stage of `ctx`, summed), views, cell_names and warnings.
nlohmann::json lightmapReport(const LightmapRun& run, const Context& ctx);

/// report.json's "energy" of a solve (W over R, G, B): emitted, shot, received, absorbed, unshot, escaped,
/// created (light a shot made up beyond its power; non-zero is a defect) and worst_shot_gain.
nlohmann::json energyReport(const EnergyTotals& e);

/// report.json's "sky": null without one, else its kind, zenith radiance and horizontal irradiance,
/// the ground's radiance, the bake's gather rays and the sun (the directional light named "sun", or null):
/// the light the scene's surroundings gave, so a bake and a reference can be checked to share it.
nlohmann::json skyReport(const Scene& scene);

/// The names of a bake's or a reference's result set (OutputDir's resultNames): those of an earlier run
/// that a new one does not write (views of other cameras, a sampled reference's missing baked.glb) go
/// when the new set is committed.
inline const std::vector<std::string> kLightmapResultNames = {"lightmap.exr",
                                                              "lightmap.png",
                                                              "lightmap_irradiance.exr",
                                                              "lightmap_irradiance_rgbm.png",
                                                              "lightmap_sh_*",
                                                              "lightmap-*",
                                                              "probes.json",
                                                              "baked.glb",
                                                              "preview.glb",
                                                              "report.json",
                                                              "report.html",
                                                              "view-*"};

/// Stages `report` as report.json in `out` (visible at out.commit()).
void writeReport(OutputDir& out, const nlohmann::json& report);

}  // namespace cpgi
