// report.html for the commands (core/html_report/html_report.h): gathers what a bake or a decomposition
// leaves in its output folder and stages the page beside it, so it appears with the rest on commit.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// After a bake or a reference: shows the staged baked.glb with `radiosity` (per atlas texel, W/m², as
/// solved; dilated here) and `cells` (may be empty), and the numbers of `report`.
void writeBakeReportPage(OutputDir& out, const std::string& title, const nlohmann::json& report,
                         const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
                         std::vector<glm::vec3> radiosity, const std::string& kind = "bake");

/// After a decomposition: shows the staged cells.glb coloured by cell, its portals and `report`
/// (cells.json).
void writeDecompositionReportPage(OutputDir& out, const std::string& title, const nlohmann::json& report,
                                  const Scene& scene, const CellGraph& cells);

/// After `compare-light A B --report DIR`: DIR/report.html with A's baked.glb lit by `a` (its lightmap)
/// and the error heat map against `b`: per texel |A − B| / RMS(B) with the sign of the luminance
/// difference, RMS and map over texels of `weight` > 0 (the others stay black); `area` for the cells
/// table. `figures` (compare-light's JSON) fill the numbers; `bench` (rows of bench/speed_accuracy.py's
/// results.json, or null) the speed-against-accuracy chart. Throws InputError when A has no baked.glb.
void writeComparisonReportPage(const std::string& dir, const std::string& aDir, const nlohmann::json& figures,
                               const ImageRGB& a, const ImageRGB& b, const std::vector<float>& area,
                               const std::vector<float>& weight, const nlohmann::json& bench = nullptr);

/// The rows of a bench results file (bench/speed_accuracy.py's results.json: an array of objects, each
/// with a scene, a method and positive seconds and rel_rmse). Throws InputError naming the file otherwise.
nlohmann::json readBenchResults(const std::string& path);

}  // namespace cpgi
