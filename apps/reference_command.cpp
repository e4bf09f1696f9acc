// `cpgi reference SCENE -o DIR`: the independent path-traced reference on the same atlas as `cpgi bake`,
// written in the same files, so that `cpgi compare-light` can measure a bake against it.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/error.h"
#include "core/output_dir.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/atlas.h"
#include "radiosity/lightmap_output.h"
#include "radiosity/reference_tracer.h"

namespace cpgi::cli {

namespace {

struct ReferenceOptions {
  std::string scene;
  std::string outDir;
  int texelsPerQuad = 0;
  float density = AtlasParams{}.density;
  int spp = 1024;
  uint64_t seed = ReferenceParams{}.seed;
  bool repair = false;
  bool quiet = false;
};

int runReference(const ReferenceOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.spp < 2)
    throw InputError("--spp", "needs at least 2 samples per texel, got " + std::to_string(o.spp));
  if (o.texelsPerQuad < 0) throw InputError("--texels-per-quad", "must be positive");
  if (!(o.density > 0.0f)) throw InputError("--density", "must be positive");

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

  ReferenceParams params;
  params.spp = o.spp;
  params.seed = o.seed;
  const auto solveStart = std::chrono::steady_clock::now();
  const ReferenceResult result = traceReference(scene, atlas, params, ctx);
  const double solveSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - solveStart).count();
  const double noise = relativeStandardError(result, atlas.area);
  // Lamps (B ≥ E, e.g. 100) outweigh lit walls (B ~ 1–10) in Σ a|R|², so the error and noise are also
  // given over the texels that do not emit, where the solvers actually differ.
  ExrChannel emissive{"emissive", std::vector<float>(atlas.texelCount(), 0.0f)};
  std::vector<float> reflectorArea = atlas.area;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0 && glm::any(glm::greaterThan(atlas.emission[i], glm::vec3(0.0f))))
      emissive.values[i] = 1.0f, reflectorArea[i] = 0.0f;
  const double noiseNonEmissive = relativeStandardError(result, reflectorArea);

  ExrChannel sigma{"stderr", std::vector<float>(atlas.texelCount(), 0.0f)};
  for (size_t i = 0; i < atlas.texelCount(); ++i) sigma.values[i] = glm::length(result.standardError[i]);
  const LightmapOutputs written =
      writeLightmapOutputs(out, scene, loaded.cells, atlas, result.radiosity, {sigma, emissive}, ctx);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json report = {
      {"method", "reference"},
      {"scene", o.scene},
      {"seconds", seconds},
      {"solve_seconds", solveSeconds},
      {"texels", atlas.validTexels()},
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
  out.commit();

  if (!o.quiet)
    std::printf(
        "reference: %zu texels, %d spp, noise %.3f%% (%.3f%% without lamps), %.1f s (trace %.1f s) -> %s\n",
        atlas.validTexels(), result.spp, 100.0 * noise, 100.0 * noiseNonEmissive, seconds, solveSeconds,
        o.outDir.c_str());
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
  cmd->add_flag("--repair", opts->repair, "Drop zero-area and duplicate triangles instead of failing");
  cmd->add_flag("-q,--quiet", opts->quiet, "No progress and no summary line");
  cmd->callback([opts, &selected] { selected = [opts] { return runReference(*opts); }; });
}

}  // namespace cpgi::cli
