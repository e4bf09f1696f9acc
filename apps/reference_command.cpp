// `cpgi reference SCENE -o DIR`: the independent path-traced reference on the same atlas as `cpgi bake`,
// written in the same files, so that `cpgi compare-light` can measure a bake against it.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/compare_light_cells.h"
#include "apps/options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/cell_source.h"
#include "radiosity/bake/lightmap_report.h"
#include "radiosity/bake/report_page.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/bounce_limit.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/lightmap/finite_result.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/metrics/texel_sample.h"
#include "radiosity/reference/noisy_cells.h"
#include "radiosity/reference/reference_tracer.h"

namespace cpgi::cli {

namespace {

struct ReferenceOptions {
  std::string scene;
  std::string outDir;
  AtlasParams atlas;
  ReferenceParams trace{.spp = 1024};
  long long texels = 0;  ///< valid texels to trace, a stratified sample (texel_sample.h); see texelsGiven
  bool texelsGiven = false;
  bool maxBouncesGiven = false;  ///< --max-bounces: the user bounded the paths, light past them left out
  CellNoiseTarget cellNoise;     ///< --cell-noise, --max-spp
  LoadOptions load;              ///< --strict, --allow-outside-files, --emit, --albedo
  SkyRequest sky;                ///< --sky, --sun, --ground: the same light as the bake's (core/sky.h)
  bool allowDark = false;
  ViewParams views;  ///< --view-size; each picture exposed for what its camera sees
  bool quiet = false;
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

// Step 1: which texels to trace: all of them, or a stratified sample (--texels), with the weight of each
// in the metric: its area times, on a sample, the number of texels it stands for (0 where not traced),
// so that the noise estimates the full reference's.
struct TexelChoice {
  bool sparse = false;
  TexelSample sample;
  ExrChannel sampleWeight{"sample_weight", {}};
  std::vector<float> weightedArea;
};

TexelChoice chooseTexels(const ReferenceOptions& o, const LightmapAtlas& atlas, Context& ctx) {
  TexelChoice c;
  // A sample as large as the atlas is the full reference: traced, written and reported as one.
  const size_t valid = atlas.validTexels();
  c.sparse = o.texelsGiven && size_t(o.texels) < valid;
  if (o.texelsGiven && !c.sparse) {
    ctx.warn("--texels " + std::to_string(o.texels) + " is not below the atlas's " + std::to_string(valid) +
             " valid texels: all are traced");
    if (!o.quiet) printWarning(ctx.warnings().back());
  }
  if (c.sparse) c.sample = sampleTexels(valid, size_t(o.texels), o.trace.seed);
  c.weightedArea = atlas.area;
  c.sampleWeight.values.assign(atlas.texelCount(), 0.0f);
  if (c.sparse) {
    // One walk in atlas order, ranks increasing: no rank-to-texel table (19.6 M entries at seed3 128²).
    size_t rank = 0, k = 0;
    for (size_t i = 0; i < atlas.texelCount() && k < c.sample.ranks.size(); ++i)
      if (atlas.patch[i] >= 0 && rank++ == c.sample.ranks[k])
        c.sampleWeight.values[i] = c.sample.weights[k++];
    for (size_t i = 0; i < atlas.texelCount(); ++i) c.weightedArea[i] *= c.sampleWeight.values[i];
  }
  return c;
}

// Bake's rule for albedo near 1 (radiosity/lightmap/bounce_limit.h), for paths: where light would bounce
// more than 200 times before 1 % of it is left (bake's default --unshot), the paths' Russian roulette
// (survival at most 0.95 a bounce, about 20 bounces on average) ends them long before, and the few that
// run on carry weights growing by ρ/0.95 a bounce: a reference of noise, or at albedo 1 of a B that has no
// finite value, after minutes of tracing. Refused up front unless --max-bounces bounds the paths (the
// light past N bounces left out, as a bake's --max-shots leaves the unshot light out).
void requireBoundedPaths(const ReferenceOptions& o, const Scene& scene, const LightmapAtlas& atlas) {
  if (o.maxBouncesGiven || !scene.hasLight()) return;
  constexpr double kShare = 0.01;
  const BounceEstimate e = estimateBounces(atlas, kShare);
  if (!e.tooMany()) return;
  std::ostringstream s;
  s << e.describe() << " before " << kShare
    << " of it is left, far beyond the paths' Russian roulette (about 20 bounces): the reference would be "
       "noise; lower the albedo, or bound the paths with `maximum bounces` N (the light past N bounces "
       "left out)";
  throw InputError(o.scene, s.str());
}

// Step 2: the reference's own figures beside report.json's common keys.
struct ReferenceFigures {
  double solveSeconds = 0.0, noise = 0.0, noiseNonEmissive = 0.0;
  size_t traced = 0;
  std::vector<std::string> cellNames;  ///< of lightmap.exr's "cell" channel
  std::vector<CellNoise> cellNoise;    ///< each cell's noise, after any extra passes
  int extraPasses = 0;
  int baseSpp = 0;  ///< paths on every traced texel (--spp rounded up to whole batches)
  int maxSpp = 0;   ///< paths on the most traced texel
};

// The noisiest cell's mean, or nullopt when no cell has a figure.
std::optional<size_t> noisiestCell(const std::vector<CellNoise>& cells) {
  std::optional<size_t> worst;
  for (size_t c = 0; c < cells.size(); ++c)
    if (std::isfinite(cells[c].meanNoise) && (!worst || cells[c].meanNoise > cells[*worst].meanNoise))
      worst = c;
  return worst;
}

nlohmann::json referenceReport(const ReferenceOptions& o, const LoadedScene& loaded, const QuadSet& quads,
                               const LightmapAtlas& atlas, const ReferenceResult& result,
                               const ReferenceFigures& f, const LightmapOutputs& written, double seconds,
                               const Context& ctx) {
  LightmapRun run{.method = "reference",
                  .scene = o.scene,
                  .seconds = seconds,
                  .solveSeconds = f.solveSeconds,
                  .atlas = &atlas,
                  .atlasParams = o.atlas,
                  .triangles = loaded.scene.triangles.size(),
                  .quads = quads.quads.size(),
                  .views = written.views,
                  .cellNames = f.cellNames};
  nlohmann::json report = lightmapReport(run, ctx);
  report["texels_traced"] = f.traced;
  report["engine_lightmap"] = written.engine;
  report["atlas_width"] = atlas.width;
  report["atlas_height"] = atlas.height;
  report["patches"] = atlas.patches.size();
  report["texels_per_quad"] = o.atlas.texelsPerQuad;
  report["density"] = o.atlas.texelsPerQuad > 0 ? 0.0f : o.atlas.density;
  report["spp"] = f.baseSpp;
  report["sky"] = skyReport(loaded.scene);
  report["texel_value"] = o.trace.texelMean ? "mean" : "centre";
  report["seed"] = o.trace.seed;
  report["max_bounces"] = o.trace.maxBounces;
  report["rays"] = result.rays;
  report["noise"] = f.noise;
  report["noise_nonemissive"] = f.noiseNonEmissive;
  report["cell_noise_target"] = o.cellNoise.meanNoise;
  report["max_spp"] = f.maxSpp;
  report["extra_passes"] = f.extraPasses;
  report["cells_noise"] = cellNoiseJson(f.cellNoise);
  return report;
}

void printSummary(const ReferenceOptions& o, const ReferenceFigures& f, bool sparse, size_t valid, int spp,
                  double seconds) {
  if (o.quiet) return;
  if (const std::optional<size_t> worst = noisiestCell(f.cellNoise))
    std::printf("reference: noisiest cell %s, its mean ±%.2f%% (%zu cells; %d extra passes, up to %d spp)\n",
                f.cellNoise[*worst].name.c_str(), 100.0 * f.cellNoise[*worst].meanNoise, f.cellNoise.size(),
                f.extraPasses, f.maxSpp);
  if (sparse)
    std::printf(
        "reference: %zu of %zu texels traced (a sample, marked in lightmap.exr; no baked.glb or views), %d "
        "spp, noise %.3f%% (%.3f%% without lamps), %.1f s (trace %.1f s) -> %s\n",
        f.traced, valid, spp, 100.0 * f.noise, 100.0 * f.noiseNonEmissive, seconds, f.solveSeconds,
        o.outDir.c_str());
  else
    std::printf(
        "reference: %zu texels, %d spp, noise %.3f%% (%.3f%% without lamps), %.1f s (trace %.1f s) -> %s\n",
        valid, spp, 100.0 * f.noise, 100.0 * f.noiseNonEmissive, seconds, f.solveSeconds, o.outDir.c_str());
}

int runReference(const ReferenceOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.texels < 0 || (o.texels == 0 && o.texelsGiven))
    throw InputError("--texels", "must be at least 1 (leave it out to trace every texel), got " +
                                     std::to_string(o.texels));
  Context ctx;
  ctx.setProgress(stderrProgress(o.quiet));
  LoadedScene loaded = loadScene(o.scene, o.load);
  applySky(o.sky, loaded.scene);
  requireLight(loaded, o.scene, o.allowDark);
  printLoaderWarnings(o.scene, loaded.warnings);
  const Scene& scene = loaded.scene;

  OutputDir out(o.outDir, kLightmapResultNames);
  const QuadSet quads = findQuads(scene);
  const LightmapAtlas atlas = buildAtlas(scene, quads, o.atlas, ctx);
  requireBoundedPaths(o, scene, atlas);
  const TexelChoice choice = chooseTexels(o, atlas, ctx);

  // "cell": each texel's cell of the scene's own graph (or of its automatic rooms, labelled as bake
  // does), for compare-light's per-cell figures and the per-cell noise target.
  const RoomLabels rooms = loaded.cells.empty() || loaded.cells.definedByVolumes()
                               ? labelTexelsByRoom(scene, o.scene, atlas, ctx, loaded.cells)
                               : RoomLabels{};
  const ExrChannel cells = rooms.graph.empty() ? cellChannel(atlas, scene, loaded.cells) : rooms.channel;

  ReferenceFigures f;
  f.cellNames = cellNames(rooms.graph.empty() ? loaded.cells : rooms.graph);
  const ExrChannel emissive{"emissive", emissiveMask(atlas)};
  // Lamps (B ≥ E, e.g. 100) outweigh lit walls (B ~ 1–10) in Σ a|R|², so the error and noise are also
  // given over the texels that do not emit, where the solvers actually differ.
  std::vector<float> reflectorArea = choice.weightedArea;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (emissive.values[i] > 0.0f) reflectorArea[i] = 0.0f;
  const auto solveStart = std::chrono::steady_clock::now();
  RefinedReference refined = traceToCellNoise(scene, atlas, o.trace, choice.sample.ranks, cells.values,
                                              reflectorArea, f.cellNames, o.cellNoise, ctx);
  const ReferenceResult& result = refined.result;
  f.solveSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - solveStart).count();
  f.cellNoise = std::move(refined.cells);
  f.extraPasses = refined.passes;
  f.maxSpp = result.spp;
  f.baseSpp = refined.baseSpp;
  requireFiniteResult(o.scene, atlas, result.radiosity);
  f.noise = relativeStandardError(result, choice.weightedArea);
  f.noiseNonEmissive = relativeStandardError(result, reflectorArea);

  ExrChannel sigma{"stderr", std::vector<float>(atlas.texelCount(), 0.0f)};
  for (size_t i = 0; i < atlas.texelCount(); ++i) sigma.values[i] = glm::length(result.standardError[i]);
  LightmapOutputs written;
  if (choice.sparse)
    writeSparseLightmap(out, atlas, result.radiosity, {sigma, emissive, cells}, choice.sampleWeight);
  else
    written = writeLightmapOutputs(out, scene, loaded.cells, atlas, result.radiosity,
                                   {sigma, emissive, cells}, ctx, o.views);
  f.traced = choice.sparse ? choice.sample.ranks.size() : atlas.validTexels();

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json report = referenceReport(o, loaded, quads, atlas, result, f, written, seconds, ctx);
  writeReport(out, report);
  if (!choice.sparse)  // a sample has no baked.glb to show
    writeBakeReportPage(out, "reference of " + o.scene, report, scene, loaded.cells, atlas, result.radiosity,
                        "reference");
  out.commit();
  printSummary(o, f, choice.sparse, atlas.validTexels(), o.trace.spp, seconds);
  return 0;
}

}  // namespace

void addReferenceCommand(CLI::App& app, CommandFn& selected) {
  auto opts = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reference",
      "Path-traced reference lightmap on the same atlas as `bake` (Embree, NEE + MIS), for compare-light");
  cmd->add_option("SCENE", opts->scene, "Scene file (.glb, .gltf, .obj)")->required();
  cmd->add_option("-o,--output", opts->outDir,
                  "Output folder (lightmap.exr, report.json, report.html, baked.glb, view-*)")
      ->required()
      ->group("Output");
  addAtlasOptions(*cmd, opts->atlas);
  addSppOption(*cmd, opts->trace.spp);
  auto* maxBounces = addMaxBouncesOption(*cmd, opts->trace.maxBounces);
  addCellNoiseOptions(*cmd, opts->cellNoise);
  const OptionGroup solver(*cmd, "Solver");
  cmd->add_option("--seed", opts->trace.seed, "Random seed (same seed, same result)")->capture_default_str();
  auto* texels =
      cmd->add_option("--texels", opts->texels,
                      "Trace only N valid texels, a stratified sample chosen from --seed, for compare-light "
                      "(lightmap.exr marks them; no baked.glb or views). Default: every texel");
  cmd->add_flag(
      "--texel-centre", [opts](int64_t) { opts->trace.texelMean = false; },
      "Take each texel's value at its centre instead of its mean over the texel (the default: a texel's "
      "power over its area, as in the bake's books)");
  addViewOptions(*cmd, opts->views);
  addLoadOptions(*cmd, opts->load);
  addDarkOption(*cmd, opts->allowDark);
  addSkyOptions(*cmd, opts->sky, false);
  cmd->add_flag("-q,--quiet", opts->quiet, "No progress and no summary line")->group("Output");
  cmd->callback([opts, texels, maxBounces, &selected] {
    opts->texelsGiven = texels->count() > 0;
    opts->maxBouncesGiven = maxBounces->count() > 0;
    selected = [opts] { return runReference(*opts); };
  });
}

}  // namespace cpgi::cli
