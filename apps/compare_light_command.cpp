// `cpgi compare-light A_DIR B_DIR`: the accuracy of lightmap A against lightmap B (the reference) on the
// same atlas, in the metric of design.md §5.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "radiosity/metrics.h"

namespace cpgi::cli {

namespace {

namespace fs = std::filesystem;

struct CompareLightOptions {
  std::string a, b;
  bool json = false;
};

struct Lightmap {
  ImageRGB rgb;
  std::vector<float> area;
  std::vector<float> emissive;  ///< 1 for lamp texels; only in `cpgi reference` output, else empty
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
  if (map.area.size() != map.rgb.pixels.size())
    throw InputError(path.string(), "no per-texel \"area\" channel (not written by cpgi bake or reference)");
  return map;
}

/// The reference's own noise (`key` of B's report.json), when it has one (a `cpgi reference` output).
std::optional<double> referenceNoise(const std::string& dir, const std::string& key) {
  const fs::path path = fs::path(dir) / "report.json";
  std::ifstream in(path);
  if (!in) return std::nullopt;
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (report.is_discarded()) throw InputError(path.string(), "not valid JSON");
  if (report.contains(key) && report[key].is_number()) return report[key].get<double>();
  return std::nullopt;
}

int runCompareLight(const CompareLightOptions& o) {
  const Lightmap a = readLightmap(o.a), b = readLightmap(o.b);
  if (a.rgb.width != b.rgb.width || a.rgb.height != b.rgb.height)
    throw InputError(o.b, "lightmap is " + std::to_string(b.rgb.width) + "x" + std::to_string(b.rgb.height) +
                              " but " + o.a + "'s is " + std::to_string(a.rgb.width) + "x" +
                              std::to_string(a.rgb.height) + "; bake both with the same atlas options");
  for (size_t i = 0; i < a.area.size(); ++i)
    if (std::abs(a.area[i] - b.area[i]) > 1e-4f * std::max(a.area[i], b.area[i]))
      throw InputError(
          o.b, "texel areas differ from " + o.a + "'s: not the same atlas (same scene and atlas options?)");

  const LightmapError e = compareLightmaps(a.rgb.pixels, b.rgb.pixels, b.area);
  const std::optional<double> noise = referenceNoise(o.b, "noise");
  // Without the lamps, whose large B would otherwise dominate Σ a|R|² (when either side marks them).
  const std::vector<float>& emissive = !b.emissive.empty() ? b.emissive : a.emissive;
  std::optional<LightmapError> reflectors;
  if (emissive.size() == b.area.size()) {
    std::vector<float> area = b.area;
    for (size_t i = 0; i < area.size(); ++i)
      if (emissive[i] > 0.5f) area[i] = 0.0f;
    reflectors = compareLightmaps(a.rgb.pixels, b.rgb.pixels, area);
  }
  const std::optional<double> noiseReflectors = referenceNoise(o.b, "noise_nonemissive");

  auto orNull = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  if (o.json) {
    nlohmann::json j = {{"a", o.a},
                        {"b", o.b},
                        {"rel_rmse", e.relRmse},
                        {"rel_mean_error", e.relMeanError},
                        {"max_abs", e.maxAbs},
                        {"texels", e.texels}};
    j["reference_noise"] = orNull(noise);
    j["rel_rmse_nonemissive"] =
        orNull(reflectors ? std::optional<double>(reflectors->relRmse) : std::nullopt);
    j["rel_mean_error_nonemissive"] =
        orNull(reflectors ? std::optional<double>(reflectors->relMeanError) : std::nullopt);
    j["reference_noise_nonemissive"] = orNull(noiseReflectors);
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("texels compared            %zu\n", e.texels);
  std::printf("rel_rmse                   %.4f%%\n", 100.0 * e.relRmse);
  std::printf("rel_mean_error             %+.4f%%\n", 100.0 * e.relMeanError);
  std::printf("max_abs                    %.6g W/m2\n", e.maxAbs);
  if (noise) std::printf("reference noise            %.4f%%\n", 100.0 * *noise);
  if (reflectors) {
    std::printf("rel_rmse without lamps     %.4f%% (%zu texels)\n", 100.0 * reflectors->relRmse,
                reflectors->texels);
    std::printf("rel_mean_error w/o lamps   %+.4f%%\n", 100.0 * reflectors->relMeanError);
  }
  if (noiseReflectors) std::printf("reference noise w/o lamps  %.4f%%\n", 100.0 * *noiseReflectors);
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
  cmd->add_option("B_DIR", opts->b, "Output folder of the reference lightmap")->required();
  cmd->add_flag("--json", opts->json,
                "Print JSON (rel_rmse, rel_mean_error, max_abs, texels, reference_noise)");
  cmd->callback([opts, &selected] { selected = [opts] { return runCompareLight(*opts); }; });
}

}  // namespace cpgi::cli
