// `cpgi compare-light A_DIR B_DIR`: the accuracy of lightmap A against lightmap B (the reference) on the
// same atlas, or with --scene on B's (A read at B's texels: compare_light_resample.h), in the metric of
// design.md §5; with --report DIR, also report.html with the error per texel and per cell.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/compare_light_cells.h"
#include "apps/compare_light_resample.h"
#include "apps/compare_light_seams.h"
#include "apps/options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "radiosity/bake/report_page.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/metrics/metrics.h"
#include "radiosity/metrics/texel_sample.h"

namespace cpgi::cli {

namespace {

namespace fs = std::filesystem;

struct CompareLightOptions {
  std::string a, b;
  bool json = false;
  std::string report;  ///< a folder for report.html with the error heat map, or empty
  std::string bench;   ///< with `report`: bench results for its speed-against-accuracy chart, or empty
  std::string scene;   ///< A read at B's texels through this scene when their atlases differ, or empty
  LoadOptions load;    ///< how `scene` is read (--keep-contacts: as a reference traced uncut was)
};

struct Lightmap {
  ImageRGB rgb;
  std::vector<float> area;
  std::vector<float> emissive;      ///< 1 for lamp texels; only in `cpgi reference` output, else empty
  std::vector<float> sigma;         ///< per-texel standard error; only in `cpgi reference` output
  std::vector<float> sampleWeight;  ///< only in a sparse reference (`--texels`): > 0 on traced texels
  std::vector<float> cell;          ///< per texel its cell index (cell_metrics.h); empty in older outputs
};

Lightmap readLightmap(const std::string& dir) {
  const fs::path path = fs::path(dir) / "lightmap.exr";
  if (!fs::exists(path))
    throw InputError(path.string(), "no such file (not a bake or reference output folder?)");
  Lightmap map;
  std::vector<ExrChannel> extra;
  map.rgb = readExr(path.string(), &extra);
  for (ExrChannel& c : extra)
    if (c.name == "area")
      map.area = std::move(c.values);
    else if (c.name == "emissive")
      map.emissive = std::move(c.values);
    else if (c.name == "stderr")
      map.sigma = std::move(c.values);
    else if (c.name == "sample_weight")
      map.sampleWeight = std::move(c.values);
    else if (c.name == kCellChannel)
      map.cell = std::move(c.values);
  if (map.area.size() != map.rgb.pixels.size())
    throw InputError(path.string(), "no per-texel \"area\" channel (not written by cpgi bake or reference)");
  return map;
}

bool sameAtlas(const Lightmap& a, const Lightmap& b) {
  if (a.rgb.width != b.rgb.width || a.rgb.height != b.rgb.height) return false;
  for (size_t i = 0; i < a.area.size(); ++i)
    if (std::abs(a.area[i] - b.area[i]) > 1e-4f * std::max(a.area[i], b.area[i])) return false;
  return true;
}

/// The reference's own noise over the texels compared, with their weights: sqrt(Σ w σ² / Σ w |R|²) (the
/// metric of reference_tracer.h's relativeStandardError), when B carries its per-texel error.
std::optional<double> referenceNoise(const Lightmap& b, std::span<const float> weight) {
  if (b.sigma.size() != weight.size()) return std::nullopt;
  double noise = 0.0, signal = 0.0;
  for (size_t i = 0; i < weight.size(); ++i) {
    if (!(weight[i] > 0.0f)) continue;
    const glm::dvec3 r(b.rgb.pixels[i]);
    noise += weight[i] * double(b.sigma[i]) * b.sigma[i];
    signal += weight[i] * glm::dot(r, r);
  }
  return signal > 0.0 ? std::sqrt(noise / signal) : 0.0;
}

// The texels' weights without the lamps.
std::vector<float> reflectorArea(std::vector<float> area, const std::vector<float>& emissive) {
  for (size_t i = 0; i < area.size(); ++i)
    if (emissive[i] > 0.5f) area[i] = 0.0f;
  return area;
}

// --report DIR: the page with the error per texel; the heat map leaves out the lamps as the figures
// without lamps do, and the untraced texels of a sample (`area` is 0 there).
void writeReportPage(const CompareLightOptions& o, const nlohmann::json& figures, const Lightmap& a,
                     const Lightmap& b, const std::vector<float>& area, const std::vector<float>& emissive,
                     const nlohmann::json& bench) {
  std::vector<float> weight = area;
  if (emissive.size() == weight.size())
    for (size_t i = 0; i < weight.size(); ++i)
      if (emissive[i] > 0.5f) weight[i] = 0.0f;
  writeComparisonReportPage(o.report, o.a, figures, a.rgb, b.rgb, b.area, weight, bench);
}

// The scene B's (else A's) report.json names, when that file is there: the atlases differ (a bake at
// --density auto against a reference at a fixed density) and the user gave no --scene.
std::string recordedScene(const std::string& bDir, const std::string& aDir) {
  for (const std::string& dir : {bDir, aDir}) {
    std::ifstream f(std::filesystem::path(dir) / "report.json");
    const nlohmann::json report = nlohmann::json::parse(f, nullptr, false);
    if (!report.is_object()) continue;
    for (const char* key : {"scene_file", "scene"})
      if (report.contains(key) && report[key].is_string()) {
        const std::string path = report[key].get<std::string>();
        std::error_code error;
        if (!path.empty() && std::filesystem::is_regular_file(path, error)) return path;
      }
  }
  return "";
}

// A read at each of B's texel centres through the scene (its lightmap coordinates, bilinear), as an engine
// reads A's baked.glb, when the two atlases differ.
void readOnAtlasOf(const CompareLightOptions& o, const Lightmap& b, Lightmap& a) {
  std::string scene = o.scene;
  if (scene.empty()) {
    scene = recordedScene(o.b, o.a);
    if (scene.empty())
      throw InputError(o.b, "lightmap is " + std::to_string(b.rgb.width) + "x" +
                                std::to_string(b.rgb.height) + " but " + o.a + "'s is " +
                                std::to_string(a.rgb.width) + "x" + std::to_string(a.rgb.height) +
                                " or its texel areas differ, and the scene " +
                                "their reports name is not there; give --scene to read A at B's texels");
    if (!o.json)
      std::cerr << "compare-light: the atlases differ; " << o.a << " is read at " << o.b
                << "'s texels through " << scene << "\n";
  }
  std::vector<char> unread;
  a.rgb = sampleOnReferenceAtlas(scene, o.a, a.rgb, o.b, b.area, b.rgb.width, b.rgb.height, &unread, o.load);
  a.area = b.area;  // 0 where A has nothing to read: left out of every figure
  const size_t left = size_t(std::count(unread.begin(), unread.end(), char(1)));
  for (size_t i = 0; i < unread.size(); ++i)
    if (unread[i]) a.area[i] = 0.0f;
  if (left > 0)
    std::cerr << "compare-light: warning: " << left << " of " << o.b << "'s texels lie on surfaces " << o.a
              << "/baked.glb does not hold; left out\n";
  a.emissive.clear();
  a.cell.clear();
}

int runCompareLight(const CompareLightOptions& o) {
  const nlohmann::json bench = o.bench.empty() ? nlohmann::json(nullptr) : readBenchResults(o.bench);
  Lightmap a = readLightmap(o.a);
  const Lightmap b = readLightmap(o.b);
  if (!a.sampleWeight.empty())
    throw InputError(o.a,
                     "is a sparse reference (cpgi reference --texels traces a sample of texels), not a "
                     "lightmap to test; give it as B, the reference");
  if (!sameAtlas(a, b)) readOnAtlasOf(o, b, a);

  // Against a sparse reference, the metric's sums run over its traced texels, each weighted by the number
  // of texels it stands for (texel_sample.h): unbiased estimates of the sums over every texel.
  const bool sparse = !b.sampleWeight.empty();
  const size_t valid = size_t(std::count_if(b.area.begin(), b.area.end(), [](float x) { return x > 0.0f; }));
  std::vector<float> area = b.area;
  for (size_t i = 0; i < area.size(); ++i)
    if (!(a.area[i] > 0.0f)) area[i] = 0.0f;
  if (sparse)
    for (size_t i = 0; i < area.size(); ++i) area[i] *= b.sampleWeight[i];
  const LightmapError e = compareLightmaps(a.rgb.pixels, b.rgb.pixels, area);
  const std::optional<double> noise = referenceNoise(b, area);
  double samplingError = 0.0, samplingErrorReflectors = 0.0;
  if (sparse) samplingError = sampledRelRmseError(a.rgb.pixels, b.rgb.pixels, b.area, b.sampleWeight, valid);

  // Without the lamps, whose large B would otherwise dominate Σ a|R|² (when either side marks them).
  const std::vector<float>& emissive = !b.emissive.empty() ? b.emissive : a.emissive;
  std::optional<LightmapError> reflectors;
  std::optional<double> noiseReflectors;
  if (emissive.size() == b.area.size()) {
    std::vector<float> reflectorArea = area, unweighted = b.area;
    for (size_t i = 0; i < area.size(); ++i)
      if (emissive[i] > 0.5f) reflectorArea[i] = 0.0f, unweighted[i] = 0.0f;
    reflectors = compareLightmaps(a.rgb.pixels, b.rgb.pixels, reflectorArea);
    noiseReflectors = referenceNoise(b, reflectorArea);
    if (sparse)
      samplingErrorReflectors =
          sampledRelRmseError(a.rgb.pixels, b.rgb.pixels, unweighted, b.sampleWeight, valid);
  }

  // Per cell, without the lamps: each texel's cell from the reference, else from A (same atlas).
  const Lightmap& cellSource = !b.cell.empty() ? b : a;
  std::vector<std::string> names = readCellNames(&cellSource == &b ? o.b : o.a);
  if (names.empty()) names = readCellNames(&cellSource == &b ? o.a : o.b);
  std::vector<CellError> cells;
  if (!cellSource.cell.empty() && !names.empty()) {
    std::vector<float> cellWeight = area;
    if (emissive.size() == area.size())
      for (size_t i = 0; i < area.size(); ++i)
        if (emissive[i] > 0.5f) cellWeight[i] = 0.0f;
    cells = compareCells(a.rgb.pixels, b.rgb.pixels, cellWeight, b.sigma, cellSource.cell, b.sampleWeight,
                         valid, names);
  }
  const std::optional<size_t> worst = worstCell(cells);

  auto orNull = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  nlohmann::json j = {{"a", o.a},
                      {"b", o.b},
                      {"rel_rmse", e.relRmse},
                      {"rel_mean_error", e.relMeanError},
                      {"max_abs", e.maxAbs},
                      {"texels", e.texels},
                      {"texels_valid", valid},
                      {"sparse_reference", sparse},
                      {"rel_rmse_sampling_error", samplingError}};
  j["reference_noise"] = orNull(noise);
  j["rel_rmse_nonemissive"] = orNull(reflectors ? std::optional<double>(reflectors->relRmse) : std::nullopt);
  j["rel_mean_error_nonemissive"] =
      orNull(reflectors ? std::optional<double>(reflectors->relMeanError) : std::nullopt);
  j["rel_rmse_nonemissive_sampling_error"] =
      reflectors ? nlohmann::json(samplingErrorReflectors) : nlohmann::json(nullptr);
  j["reference_noise_nonemissive"] = orNull(noiseReflectors);
  j["cells"] = cellsJson(cells);
  j["worst_cell"] = worst ? nlohmann::json(cells[*worst].name) : nlohmann::json(nullptr);
  std::string seamsWhy;
  j["portal_seams"] = portalSeamsJson(o.scene.empty() ? recordedScene(o.b, o.a) : o.scene, o.b, a.rgb.pixels,
                                      b.rgb.pixels, reflectors ? reflectorArea(area, emissive) : area, b.area,
                                      b.rgb.width, b.rgb.height, seamsWhy, o.load);
  if (!o.report.empty()) writeReportPage(o, j, a, b, area, emissive, bench);
  if (o.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  if (sparse)
    std::printf("texels compared            %zu of %zu (the sparse reference's sample)\n", e.texels, valid);
  else
    std::printf("texels compared            %zu\n", e.texels);
  if (sparse)
    std::printf("rel_rmse                   %.4f%% +- %.4f%% (texel sampling)\n", 100.0 * e.relRmse,
                100.0 * samplingError);
  else
    std::printf("rel_rmse                   %.4f%%\n", 100.0 * e.relRmse);
  std::printf("rel_mean_error             %+.4f%%\n", 100.0 * e.relMeanError);
  std::printf("max_abs                    %.6g W/m2\n", e.maxAbs);
  if (noise) std::printf("reference noise            %.4f%%\n", 100.0 * *noise);
  if (reflectors) {
    std::printf("rel_rmse without lamps     %.4f%% (%zu texels)", 100.0 * reflectors->relRmse,
                reflectors->texels);
    if (sparse) std::printf(" +- %.4f%% (texel sampling)", 100.0 * samplingErrorReflectors);
    std::printf("\n");
    std::printf("rel_mean_error w/o lamps   %+.4f%%\n", 100.0 * reflectors->relMeanError);
  }
  if (noiseReflectors) std::printf("reference noise w/o lamps  %.4f%%\n", 100.0 * *noiseReflectors);
  if (!cells.empty()) printCells(cells);
  if (j["portal_seams"].is_null())
    std::printf("portal seams               not measured: %s\n", seamsWhy.c_str());
  printPortalSeams(j["portal_seams"]);
  if (noise && e.relRmse < 2.0 * *noise)
    std::printf("note: rel_rmse is within 2x the reference's noise; trace the reference with more --spp\n");
  return 0;
}

}  // namespace

void addCompareLightCommand(CLI::App& app, CommandFn& selected) {
  auto opts = std::make_shared<CompareLightOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare-light",
      "Relative RMSE (area-weighted, RGB) of lightmap A against reference B on the same atlas");
  cmd->add_option("A_DIR", opts->a, "Output folder of the lightmap under test (bake or reference)")
      ->required();
  cmd->add_option("B_DIR", opts->b, "Output folder of the reference lightmap (full, or a --texels sample)")
      ->required();
  cmd->add_flag("--json", opts->json,
                "Print JSON (rel_rmse, rel_mean_error, max_abs, texels, reference_noise, ...)")
      ->group("Output");
  addReportOption(*cmd, opts->report);
  cmd->add_option("--bench", opts->bench,
                  "With --report: also chart speed against accuracy from this results.json of "
                  "bench/speed_accuracy.py")
      ->needs(cmd->get_option("--report"))
      ->group("Output");
  cmd->add_option("--scene", opts->scene,
                  "When A's atlas is not B's (another density, or --density auto): the scene both were made "
                  "from; A is read at B's texel centres as an engine reads A's baked.glb (bilinear), B's "
                  "atlas rebuilt from the scene with the options its report.json records (default: the scene "
                  "B's or A's report.json names, when that file is there)")
      ->group("Input");
  cmd->add_flag_callback(
         "--keep-contacts", [opts] { opts->load.cutContacts = false; },
         "With --scene: read the scene with its faces whole where other geometry runs through them, as "
         "B was made (a reference traced before faces were cut at their contacts, or with --keep-contacts)")
      ->group("Input");
  cmd->callback([opts, &selected] { selected = [opts] { return runCompareLight(*opts); }; });
}

}  // namespace cpgi::cli
