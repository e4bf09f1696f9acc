#include "radiosity/bake/report_page.h"
#include "radiosity/lightmap/lightmap_output.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/html_report/html_report.h"
#include "core/image_io.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/spherical_harmonics.h"
#include "radiosity/lightmap/views.h"

namespace cpgi {
namespace {
std::string bDir(const nlohmann::json& figures) {
  return figures.value("b", std::string("the reference"));
}

// The page's view from inside each cell: the same cameras as the bake's pictures of a scene without any.
std::vector<Camera> cellCameras(const Scene& scene, const CellGraph& cells) {
  if (cells.empty()) return {};
  return defaultCameras(RayScene(scene), scene, cells);
}
}  // namespace

void writeBakeReportPage(OutputDir& out, const std::string& title, const nlohmann::json& report,
                         const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
                         std::vector<glm::vec3> radiosity, const std::string& kind) {
  dilate(atlas, radiosity);  // as lightmap.exr: filtering at chart edges must not pull in black
  ReportLightmap lightmap;
  lightmap.width = atlas.width, lightmap.height = atlas.height;
  lightmap.radiosity = std::move(radiosity);
  lightmap.area = atlas.area;
  if (!cells.empty())
    for (const float c : cellChannel(atlas, scene, cells).values) lightmap.cellOfTexel.push_back(int(c));
  HtmlReportInput input;
  input.title = title;
  input.kind = kind;
  input.report = report;
  input.glb = readFileBytes(out.staged("preview.glb").string());
  input.cellCameras = cellCameras(scene, cells);
  input.cells = &cells;
  input.frame = buildingBounds(scene, &cells);
  input.lightmap = &lightmap;
  // A bake with light probes staged probes.json: the page lights a sphere with them; one with --directional
  // on cpgi's atlas, its SH files: the page's normal-mapped test surface.
  const nlohmann::json engine = report.value("engine_lightmap", nlohmann::json::object());
  // (A gather the time limit stopped wrote no files: its entry has none.)
  if (engine.is_object() && engine.contains("directional") && engine["directional"].contains("files") &&
      engine.value("uv", "") == "own") {
    const char* files[3] = {"lightmap_sh_l1x.exr", "lightmap_sh_l1y.exr", "lightmap_sh_l1z.exr"};
    for (size_t k = 0; k < 3; ++k) {
      ImageRGB sh = readExr(out.staged(files[k]).string());
      for (glm::vec3& c : sh.pixels) c /= kShY1;
      lightmap.irradianceVector[k] = std::move(sh.pixels);
    }
  }
  if (engine.is_object() && engine.contains("probes") && engine["probes"].contains("file"))
    input.probes = nlohmann::json::parse(readFileBytes(out.staged("probes.json").string()));
  writeHtmlReport(out, input);
}

void writeDecompositionReportPage(OutputDir& out, const std::string& title, const nlohmann::json& report,
                                  const Scene& scene, const CellGraph& cells) {
  HtmlReportInput input;
  input.title = title;
  input.kind = "decomposition";
  input.report = report;
  input.glb = readFileBytes(out.staged("cells.glb").string());
  input.cellCameras = cellCameras(scene, cells);
  input.cells = &cells;
  input.frame = buildingBounds(scene, &cells);
  writeHtmlReport(out, input);
}

void writeComparisonReportPage(const std::string& dir, const std::string& aDir, const nlohmann::json& figures,
                               const ImageRGB& a, const ImageRGB& b, const std::vector<float>& area,
                               const std::vector<float>& weight, const nlohmann::json& bench) {
  const std::string glbPath = previewGlb(aDir).string();
  if (!std::filesystem::exists(glbPath))
    throw InputError(glbPath,
                     "no such file (--report shows A's preview.glb; A must be a bake or reference folder)");
  const LoadedScene baked = loadScene(glbPath);  // for its cells and portals

  double signal = 0.0, weights = 0.0;
  for (size_t i = 0; i < weight.size(); ++i)
    if (weight[i] > 0.0f)
      signal += weight[i] * glm::dot(glm::dvec3(b.pixels[i]), glm::dvec3(b.pixels[i])), weights += weight[i];
  const double rms = weights > 0.0 ? std::sqrt(signal / weights) : 0.0;
  ReportLightmap lightmap;
  lightmap.width = a.width, lightmap.height = a.height;
  lightmap.radiosity = a.pixels;
  lightmap.area = area;
  lightmap.error.assign(weight.size(), NAN);  // not compared: left black by the heat map
  const glm::vec3 luminance(0.2126f, 0.7152f, 0.0722f);
  for (size_t i = 0; i < weight.size() && rms > 0.0; ++i)
    if (weight[i] > 0.0f) {
      const float sign = glm::dot(a.pixels[i] - b.pixels[i], luminance) < 0.0f ? -1.0f : 1.0f;
      lightmap.error[i] = sign * float(glm::length(a.pixels[i] - b.pixels[i]) / rms);
    }

  OutputDir out(dir, {"report.html"});
  HtmlReportInput input;
  input.title = "comparison of " + aDir + " against " + bDir(figures);
  input.kind = "comparison";
  input.report = figures;
  input.glb = readFileBytes(glbPath);
  input.cellCameras = cellCameras(baked.scene, baked.cells);
  input.cells = &baked.cells;
  input.frame = buildingBounds(baked.scene, &baked.cells);
  input.lightmap = &lightmap;
  input.bench = bench;
  writeHtmlReport(out, input);
  out.commit();
}

nlohmann::json readBenchResults(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot read it (bench results: bench/speed_accuracy.py's results.json)");
  const nlohmann::json rows = nlohmann::json::parse(in, nullptr, false);
  if (rows.is_discarded() || !rows.is_array() || rows.empty())
    throw InputError(path, "is not a JSON array of bench rows (bench/speed_accuracy.py's results.json)");
  for (size_t i = 0; i < rows.size(); ++i) {
    const nlohmann::json& r = rows[i];
    const auto positive = [&](const char* key) {
      return r.contains(key) && r[key].is_number() && r[key].get<double>() > 0.0;
    };
    if (!r.is_object() || !r.contains("scene") || !r.contains("method") || !positive("seconds") ||
        !positive("rel_rmse"))
      throw InputError(path, "row " + std::to_string(i + 1) +
                                 " lacks a scene, a method, or positive seconds and rel_rmse");
  }
  return rows;
}

}  // namespace cpgi
