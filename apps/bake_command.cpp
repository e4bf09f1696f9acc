// `cpgi bake SCENE -o DIR [--method global] [--texels-per-quad N | --density T] [--unshot F] [--max-shots N]
//  [--visibility hemisphere|hemicube] [--item-buffer N] [--repair]`: GPU progressive radiosity over a
// lightmap atlas (design.md §1, §3). Writes lightmap.exr (R, G, B radiosity + "area" + "emissive"),
// baked.glb (the scene with the lightmap as an unlit texture), lightmap.png, view-*.png/.exr from each
// camera (radiosity/views.h) and report.json, all or nothing.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/atlas.h"
#include "radiosity/egl_context.h"
#include "radiosity/gpu_solver.h"
#include "radiosity/views.h"

namespace cpgi::cli {
namespace {

struct BakeOptions {
  std::string scene;
  std::string output;
  std::string method = "global";
  int texelsPerQuad = 0;
  float density = AtlasParams{}.density;
  double unshot = SolverParams{}.unshotFraction;
  int maxShots = SolverParams{}.maxShots;
  std::string visibility = visibilityName(SolverParams{}.visibility);
  int itemBuffer = SolverParams{}.itemBuffer;
  bool repair = false;
  bool quiet = false;
};

// A one-line progress display on a terminal; nothing when stderr is a file or a pipe.
Context::ProgressFn progressPrinter(bool quiet) {
  if (quiet || !::isatty(STDERR_FILENO)) return {};
  return [](const std::string& stage, double fraction, const std::string& status) {
    const int width = 24, done = int(std::clamp(fraction, 0.0, 1.0) * width);
    std::fprintf(stderr, "\r%-6s [%s%s] %-48s", stage.c_str(), std::string(done, '#').c_str(),
                 std::string(width - done, ' ').c_str(), status.c_str());
    if (fraction >= 1.0) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

int runBake(const BakeOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  Context ctx;
  ctx.setProgress(progressPrinter(o.quiet));

  AtlasParams atlasParams;
  atlasParams.texelsPerQuad = o.texelsPerQuad;
  atlasParams.density = o.density;
  SolverParams solverParams;
  solverParams.visibility = parseVisibility(o.visibility);
  solverParams.itemBuffer = o.itemBuffer;
  solverParams.unshotFraction = o.unshot;
  solverParams.maxShots = o.maxShots;

  LoadedScene loaded;
  {
    auto t = ctx.time("load");
    loaded = loadScene(o.scene, LoadOptions{.repair = o.repair});
  }
  for (const std::string& w : loaded.warnings) ctx.warn(w);
  OutputDir out(o.output);

  QuadSet quads;
  LightmapAtlas atlas;
  {
    auto t = ctx.time("atlas");
    quads = findQuads(loaded.scene);
    atlas = buildAtlas(loaded.scene, quads, atlasParams, ctx);
  }
  if (atlas.patches.empty()) throw InputError(o.scene, "no surface to bake");
  if (!(loaded.scene.emittedPower().r + loaded.scene.emittedPower().g + loaded.scene.emittedPower().b > 0.0f))
    ctx.warn(o.scene + ": nothing emits light; the lightmap is black");

  std::unique_ptr<EglContext> gl;
  {
    auto t = ctx.time("egl");
    gl = std::make_unique<EglContext>(ctx);
  }
  SolveResult solved;
  {
    auto t = ctx.time("solve");
    solved = solveProgressive(loaded.scene, atlas, solverParams, *gl, ctx);
  }

  std::vector<std::string> views;
  {
    auto t = ctx.time("write");
    std::vector<glm::vec3> lit = solved.radiosity;
    dilate(atlas, lit);
    ImageRGB image{atlas.width, atlas.height, lit};
    // "emissive" marks lamp texels, as `cpgi reference` does, so compare-light can leave them out.
    ExrChannel emissive{"emissive", std::vector<float>(atlas.texelCount(), 0.0f)};
    for (size_t i = 0; i < atlas.texelCount(); ++i)
      if (atlas.patch[i] >= 0 && atlas.emission[i] != glm::vec3(0.0f)) emissive.values[i] = 1.0f;
    writeExr(out.file("lightmap.exr").string(), image, {ExrChannel{"area", atlas.area}, emissive});

    // The PNG (alone and inside baked.glb) shows radiance B/π at the views' exposure, like the reference's.
    const float exposure = viewExposure(atlas, lit);
    const std::string png = encodePng(image, exposure / 3.14159265f);
    writeFileAtomically(out.file("lightmap.png"), png);
    GltfWriteOptions gltf;
    gltf.lightmapUVs = &atlas.triangleUV;
    gltf.lightmapPng = png;
    // writeGltf picks the format by extension, which OutputDir's temporary name does not end in.
    const std::filesystem::path stagedGlb = out.file("baked.glb");
    std::filesystem::path withExtension = stagedGlb;
    withExtension += ".glb";
    writeGltf(withExtension.string(), loaded.scene, gltf);
    std::filesystem::rename(withExtension, stagedGlb);

    ViewParams viewParams;
    viewParams.exposure = exposure;
    views = renderViews(loaded.scene, loaded.cells, atlas, lit, out, ctx, viewParams);
  }

  nlohmann::json timings = nlohmann::json::object();
  for (const Context::Timing& t : ctx.timings())
    timings[t.stage] = timings.value(t.stage, 0.0) + t.seconds;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const EnergyTotals& e = solved.energy;
  nlohmann::json report = {
      {"method", "global"},
      {"scene", o.scene},
      {"seconds", seconds},
      {"solve_seconds", solved.seconds},
      {"texels", atlas.validTexels()},
      {"shots", solved.shots},
      {"unshot_fraction", solved.unshotFraction},
      {"unshot_target", solverParams.unshotFraction},
      {"cells", 1},
      {"portals", 0},
      {"visibility", visibilityName(solverParams.visibility)},
      {"item_buffer", solverParams.itemBuffer},
      {"atlas",
       {{"width", atlas.width},
        {"height", atlas.height},
        {"patches", atlas.patches.size()},
        {"texels_per_quad", atlasParams.texelsPerQuad},
        {"density", atlasParams.texelsPerQuad > 0 ? 0.0f : atlasParams.density}}},
      {"triangles", loaded.scene.triangles.size()},
      {"quads", quads.quads.size()},
      {"renderer", gl->renderer()},
      {"gl_version", gl->version()},
      {"egl_platform", gl->platform()},
      {"timings", timings},
      {"energy",
       {{"emitted_w", e.emitted},
        {"shot_w", e.shot},
        {"received_w", e.received},
        {"absorbed_w", e.absorbed},
        {"unshot_w", e.unshot},
        {"escaped_w", e.escaped()}}},
      {"views", views},
      {"warnings", ctx.warnings()}};
  writeFileAtomically(out.file("report.json"), report.dump(2) + "\n");
  out.commit();
  if (!o.quiet) {
    std::cout << o.output << ": " << atlas.validTexels() << " texels, " << solved.shots << " shots, unshot "
              << solved.unshotFraction * 100.0 << " %, " << seconds << " s\n";
    for (const std::string& w : ctx.warnings()) std::cerr << "warning: " << w << "\n";
  }
  return 0;
}

}  // namespace

void addBakeCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<BakeOptions>();
  CLI::App* sub = app.add_subcommand("bake", "Bake diffuse global illumination into a lightmap (GPU radiosity)");
  sub->add_option("scene", o->scene, "Scene (.glb, .gltf, .obj)")->required();
  sub->add_option("-o,--output", o->output, "Output folder")->required();
  sub->add_option("--method", o->method, "global: one progressive radiosity solve over the whole scene")
      ->check(CLI::IsMember({"global"}))
      ->capture_default_str();
  auto* tpq = sub->add_option("--texels-per-quad", o->texelsPerQuad,
                              "N×N texels per quad whatever its size (the thesis's mode)")
                  ->check(CLI::Range(1, 4096));
  auto* density = sub->add_option("--density", o->density, "Texels per metre along each patch edge")
                      ->check(kPositive)
                      ->capture_default_str();
  tpq->excludes(density);
  sub->add_option("--unshot", o->unshot, "Stop when this fraction of the emitted power is still unshot")
      ->check(CLI::Range(1e-9, 0.999999))
      ->capture_default_str();
  sub->add_option("--max-shots", o->maxShots, "Stop after this many shots")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  sub->add_option("--visibility", o->visibility,
                  "hemisphere: the thesis's one-pass item buffer; hemicube: five faces, exact straight edges")
      ->check(CLI::IsMember({"hemisphere", "hemicube"}))
      ->capture_default_str();
  sub->add_option("--item-buffer", o->itemBuffer,
                  "Item-buffer edge in pixels (hemicube: faces of half this edge)")
      ->capture_default_str();
  sub->add_flag("--repair", o->repair, "Drop zero-area and duplicate triangles instead of failing");
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary");
  sub->callback([&selected, o] { selected = [o] { return runBake(*o); }; });
}

}  // namespace cpgi::cli
