// `cpgi reference SCENE -o DIR`: the independent path-traced reference on the same atlas as `cpgi bake`,
// written in the same files, so that `cpgi compare-light` can measure a bake against it.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/report_page.h"
#include "apps/view_size.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/atlas.h"
#include "radiosity/lightmap_output.h"
#include "radiosity/reference_tracer.h"
#include "radiosity/texel_sample.h"

namespace cpgi::cli {

namespace {

struct ReferenceOptions {
  std::string scene;
  std::string outDir;
  int texelsPerQuad = 0;
  float density = AtlasParams{}.density;
  int spp = 1024;
  long long texels = 0;  ///< valid texels to trace, a stratified sample (texel_sample.h); see texelsGiven
  bool texelsGiven = false;
  uint64_t seed = ReferenceParams{}.seed;
  bool repair = false;
  bool quiet = false;
  std::string viewSize;  ///< "W×H" of the view pictures, "" for 640 × the camera's aspect
};

/// A sample's lightmap.exr, alone: R, G, B = B on the traced texels and NaN on the other valid texels, so
/// that nothing can read them as light; 0 on padding (not dilated: nothing displays this lightmap);
/// channels "area", then `extra`, then `sampleWeight` ("sample_weight", > 0 exactly on traced texels), which
/// compare-light weights by. No baked.glb or views: pictures of a lightmap that is mostly holes would
/// look like a broken bake.
void writeSparseLightmap(OutputDir& out, const LightmapAtlas& atlas, const std::vector<glm::vec3>& radiosity,
                         const std::vector<ExrChannel>& extra, const ExrChannel& sampleWeight) {
  ImageRGB image{atlas.width, atlas.height, radiosity};
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0 && !(sampleWeight.values[i] > 0.0f)) image.pixels[i] = glm::vec3(std::nanf(""));
  std::vector<ExrChannel> channels{{"area", atlas.area}};
  channels.insert(channels.end(), extra.begin(), extra.end());
  channels.push_back(sampleWeight);
  writeExr(out.file("lightmap.exr").string(), image, channels);
}

int runReference(const ReferenceOptions& o) {
  const ViewParams viewSize = parseViewSize(o.viewSize);  // checked before any work
  const auto start = std::chrono::steady_clock::now();
  if (o.spp < 2)
    throw InputError("--spp", "needs at least 2 samples per texel, got " + std::to_string(o.spp));
  if (o.texelsPerQuad < 0) throw InputError("--texels-per-quad", "must be positive");
  if (!(o.density > 0.0f)) throw InputError("--density", "must be positive");
  if (o.texels < 0 || (o.texels == 0 && o.texelsGiven))
    throw InputError("--texels", "must be at least 1 (leave it out to trace every texel), got " +
                                     std::to_string(o.texels));

  Context ctx;
  const bool showProgress = !o.quiet && ::isatty(STDERR_FILENO);
  if (showProgress)
    ctx.setProgress([](const std::string& stage, double fraction, const std::string& status) {
      std::fprintf(stderr, "\r%s %3d%% %s   ", stage.c_str(), int(100.0 * fraction + 0.5), status.c_str());
      if (fraction >= 1.0) std::fputc('\n', stderr);
    });

  LoadOptions loadOptions;
  loadOptions.repair = o.repair;
  const LoadedScene loaded = loadScene(o.scene, loadOptions);
  for (const std::string& w : loaded.warnings) std::cerr << "cpgi: warning: " << o.scene << ": " << w << "\n";
  const Scene& scene = loaded.scene;

  OutputDir out(o.outDir);
  AtlasParams atlasParams;
  atlasParams.texelsPerQuad = o.texelsPerQuad;
  atlasParams.density = o.density;
  const QuadSet quads = findQuads(scene);
  const LightmapAtlas atlas = buildAtlas(scene, quads, atlasParams, ctx);

  // A sample as large as the atlas is the full reference: traced, written and reported as one.
  const size_t valid = atlas.validTexels();
  const bool sparse = o.texelsGiven && size_t(o.texels) < valid;
  if (o.texelsGiven && !sparse) {
    ctx.warn("--texels " + std::to_string(o.texels) + " is not below the atlas's " + std::to_string(valid) +
             " valid texels: all are traced");
    if (!o.quiet) std::cerr << "cpgi: warning: " << ctx.warnings().back() << "\n";
  }
  TexelSample sample;
  if (sparse) sample = sampleTexels(valid, size_t(o.texels), o.seed);

  ReferenceParams params;
  params.spp = o.spp;
  params.seed = o.seed;
  const auto solveStart = std::chrono::steady_clock::now();
  const ReferenceResult result = traceReference(scene, atlas, params, ctx, sample.ranks);
  const double solveSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - solveStart).count();

  // The texels' weights in the metric: their area, times, on a sample, the number of texels each one
  // stands for (0 where not traced), so that the noise below estimates the full reference's.
  std::vector<float> weightedArea = atlas.area;
  ExrChannel sampleWeight{"sample_weight", std::vector<float>(atlas.texelCount(), 0.0f)};
  if (sparse) {
    // One walk in atlas order, ranks increasing: no rank-to-texel table (19.6 M entries at seed3 128²).
    size_t rank = 0, k = 0;
    for (size_t i = 0; i < atlas.texelCount() && k < sample.ranks.size(); ++i)
      if (atlas.patch[i] >= 0 && rank++ == sample.ranks[k]) sampleWeight.values[i] = sample.weights[k++];
    for (size_t i = 0; i < atlas.texelCount(); ++i) weightedArea[i] *= sampleWeight.values[i];
  }
  const double noise = relativeStandardError(result, weightedArea);
  // Lamps (B ≥ E, e.g. 100) outweigh lit walls (B ~ 1–10) in Σ a|R|², so the error and noise are also
  // given over the texels that do not emit, where the solvers actually differ.
  ExrChannel emissive{"emissive", std::vector<float>(atlas.texelCount(), 0.0f)};
  std::vector<float> reflectorArea = weightedArea;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0 && glm::any(glm::greaterThan(atlas.emission[i], glm::vec3(0.0f))))
      emissive.values[i] = 1.0f, reflectorArea[i] = 0.0f;
  const double noiseNonEmissive = relativeStandardError(result, reflectorArea);

  ExrChannel sigma{"stderr", std::vector<float>(atlas.texelCount(), 0.0f)};
  for (size_t i = 0; i < atlas.texelCount(); ++i) sigma.values[i] = glm::length(result.standardError[i]);
  LightmapOutputs written;
  if (sparse)
    writeSparseLightmap(out, atlas, result.radiosity, {sigma, emissive}, sampleWeight);
  else
    written = writeLightmapOutputs(out, scene, loaded.cells, atlas, result.radiosity, {sigma, emissive}, ctx,
                                   viewSize);
  const size_t traced = sparse ? sample.ranks.size() : valid;

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json report = {
      {"method", "reference"},
      {"scene", o.scene},
      {"seconds", seconds},
      {"solve_seconds", solveSeconds},
      {"texels", valid},
      {"texels_traced", traced},
      {"atlas_width", atlas.width},
      {"atlas_height", atlas.height},
      {"patches", atlas.patches.size()},
      {"texels_per_quad", o.texelsPerQuad},
      {"density", o.texelsPerQuad > 0 ? 0.0f : o.density},
      {"spp", result.spp},
      {"seed", o.seed},
      {"rays", result.rays},
      {"noise", noise},
      {"noise_nonemissive", noiseNonEmissive},
      {"cells", 1},
      {"portals", 0},
      {"shots", 0},
      {"unshot_fraction", 0.0},
      {"views", written.views},
      {"warnings", ctx.warnings()},
  };
  nlohmann::json timings = nlohmann::json::array();
  for (const Context::Timing& t : ctx.timings())
    timings.push_back({{"stage", t.stage}, {"seconds", t.seconds}});
  report["timings"] = timings;
  writeFileAtomically(out.file("report.json"), report.dump(2) + "\n");
  if (!sparse)
    writeBakeReportPage(out, "reference of " + o.scene, report, scene, loaded.cells, atlas, result.radiosity,
                        "reference");
  out.commit();

  if (!o.quiet && sparse)
    std::printf(
        "reference: %zu of %zu texels traced (a sample, marked in lightmap.exr; no baked.glb or views), %d "
        "spp, noise %.3f%% (%.3f%% without lamps), %.1f s (trace %.1f s) -> %s\n",
        traced, valid, result.spp, 100.0 * noise, 100.0 * noiseNonEmissive, seconds, solveSeconds,
        o.outDir.c_str());
  else if (!o.quiet)
    std::printf(
        "reference: %zu texels, %d spp, noise %.3f%% (%.3f%% without lamps), %.1f s (trace %.1f s) -> %s\n",
        valid, result.spp, 100.0 * noise, 100.0 * noiseNonEmissive, seconds, solveSeconds, o.outDir.c_str());
  return 0;
}

}  // namespace

void addReferenceCommand(CLI::App& app, CommandFn& selected) {
  auto opts = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reference",
      "Path-traced reference lightmap on the same atlas as `bake` (Embree, NEE + MIS), for compare-light");
  cmd->add_option("SCENE", opts->scene, "Scene file (.glb, .gltf, .obj)")->required();
  cmd->add_option("-o,--output", opts->outDir, "Output folder (lightmap.exr, report.json, baked.glb, view-*)")
      ->required();
  auto* tpq = cmd->add_option("--texels-per-quad", opts->texelsPerQuad,
                              "N x N texels per quad whatever its size (the thesis's mode)");
  auto* density = cmd->add_option("--density", opts->density, "Texels per metre along each patch edge")
                      ->capture_default_str();
  tpq->excludes(density);
  cmd->add_option("--spp", opts->spp, "Paths per texel (noise falls as 1/sqrt(spp))")->capture_default_str();
  cmd->add_option("--seed", opts->seed, "Random seed (same seed, same result)")->capture_default_str();
  auto* texels =
      cmd->add_option("--texels", opts->texels,
                      "Trace only N valid texels, a stratified sample chosen from --seed, for compare-light "
                      "(lightmap.exr marks them; no baked.glb or views). Default: every texel");
  cmd->add_option("--view-size", opts->viewSize,
                  "Size of the view-*.png/.exr pictures, WxH pixels (default 640 wide, the camera's aspect)");
  cmd->add_flag("--repair", opts->repair, "Drop zero-area and duplicate triangles instead of failing");
  cmd->add_flag("-q,--quiet", opts->quiet, "No progress and no summary line");
  cmd->callback([opts, texels, &selected] {
    opts->texelsGiven = texels->count() > 0;
    selected = [opts] { return runReference(*opts); };
  });
}

}  // namespace cpgi::cli
