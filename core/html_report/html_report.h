// report.html: one self-contained page beside a bake or a decomposition that shows the result in 3D
// (three.js, inlined) with its cells and portals, and the numbers of report.json. It opens offline from
// file://: the viewer script, the glTF and the lightmap are all inside the file.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/output_dir.h"
#include "core/scene.h"

namespace cpgi {

/// The baked lightmap as the page shows it: per atlas texel, row-major, width × height, v down the rows
/// (the atlas's and glTF's convention).
struct ReportLightmap {
  int width = 0, height = 0;
  std::vector<glm::vec3> radiosity;  ///< W/m², dilated (so filtering at chart edges stays lit)
  std::vector<float> area;           ///< m² per texel, 0 on padding
  std::vector<int> cellOfTexel;      ///< index into the cell graph, -1 for padding or no cell; may be empty
  /// A comparison only (else empty): per texel, |A − B| / RMS(B) with the sign of A's luminance minus B's,
  /// RMS over the reference's texels weighted by area; the page's error heat map.
  std::vector<float> error;
  /// A bake with --directional on cpgi's own atlas (else empty): per texel the vector irradiance V =
  /// ∫ L ω dω, its x, y and z components (RGB each; radiosity/lightmap/directional_lightmap.h), dilated;
  /// the page's normal-mapped test surface.
  std::array<std::vector<glm::vec3>, 3> irradianceVector;
};

struct HtmlReportInput {
  std::string title;      ///< shown on top, e.g. "bake of seed1.glb"
  std::string kind;       ///< "bake", "reference", "comparison" or "decomposition"
  nlohmann::json report;  ///< report.json as written beside the page
  std::string glb;        ///< the glTF binary shown: baked.glb (TEXCOORD_1 = atlas) or cells.glb
  /// Where a person would stand in each cell (radiosity/lightmap/views.h's defaultCameras), by the cell's
  /// name; the page offers a view from each. A cell without one gets none.
  std::vector<Camera> cellCameras;
  const CellGraph* cells = nullptr;  ///< cells and portals (may be null or empty)
  /// What the overview frames (buildingBounds); empty: the whole model.
  Bounds frame;
  const ReportLightmap* lightmap = nullptr;  ///< null for a decomposition
  /// Rows of bench/speed_accuracy.py's results.json (scene, method, resolution, seconds, rel_rmse,
  /// rel_rmse_nonemissive ...) for the speed-against-accuracy chart; null for none.
  nlohmann::json bench;
  /// probes.json of a bake with light probes (radiosity/bake/light_probes.h): the page's probe-lit sphere;
  /// null for none.
  nlohmann::json probes;
};

/// The building in `scene`, for the overview to frame rather than the terrain around it: the bounds of the
/// triangles of every cell but the outside when `cells` gives rooms; else of the triangles whose centre
/// lies in the box of the middle 96 % of the triangles' centres on each axis, grown by a quarter of its size
/// (a ground plane or sky box many times the building's size is two triangles among thousands).
Bounds buildingBounds(const Scene& scene, const CellGraph* cells);

/// The page's HTML. Throws std::invalid_argument when the lightmap's arrays do not match its size.
std::string renderHtmlReport(const HtmlReportInput& input);

/// Stages `report.html` in `out` (it appears with the rest on out.commit()).
void writeHtmlReport(OutputDir& out, const HtmlReportInput& input);

/// Reads a staged or finished file whole (to embed baked.glb). Throws SystemError naming it.
std::string readFileBytes(const std::string& path);

}  // namespace cpgi
