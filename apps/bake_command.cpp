// `cpgi bake SCENE -o DIR [--method global|cells] [--cells FILE|auto] [--portals diffuse|directional]
// [--max-rounds N]
//  [--only-cells A,B | --around X,Y,Z [--depth K]] [--boundary coarse|dark] [--jobs N]
//  [--texels-per-quad N | --density T] [--unshot F] [--max-shots N] [--visibility hemisphere|hemicube]
//  [--item-buffer N] [--regions N] [--region-size M] [--repair]`: GPU progressive radiosity over a lightmap
//  atlas (design.md §1, §3), over
// the whole scene at once or cell by cell through portals (radiosity/cell_solver.h); both write the same
// atlas layout. Writes lightmap.exr (R, G, B radiosity + "area" + "emissive"),
// baked.glb (the scene with the lightmap as an unlit texture), lightmap.png, view-*.png/.exr from each
// camera (radiosity/views.h), report.json and report.html (apps/report_page.h), all or nothing.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/cell_source.h"
#include "apps/commands.h"
#include "apps/report_page.h"
#include "apps/view_size.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "decomposition/decompose.h"
#include "radiosity/atlas.h"
#include "radiosity/cell_selection.h"
#include "radiosity/cell_solver.h"
#include "radiosity/egl_context.h"
#include "radiosity/gpu_solver.h"
#include "radiosity/views.h"

namespace cpgi::cli {
namespace {

struct BakeOptions {
  std::string scene;
  std::string output;
  std::string method = "global";
  std::string cells = "none";  ///< with --method cells: a glTF with cell:/portal: nodes, or "auto"
  std::string portals = "diffuse";
  int maxRounds = CellSolveParams{}.maxRounds;
  std::string onlyCells;  ///< on demand: "A,B"
  std::string around;     ///< on demand: "X,Y,Z"
  int depth = 0;          ///< with `around`: portals away from the point's cell
  std::string boundary = boundaryModeName(BoundaryMode::Coarse);
  int jobs = CellSolveParams{}.jobs;
  int texelsPerQuad = 0;
  float density = AtlasParams{}.density;
  double unshot = SolverParams{}.unshotFraction;
  int maxShots = SolverParams{}.maxShots;
  std::string visibility = visibilityName(SolverParams{}.visibility);
  int itemBuffer = SolverParams{}.itemBuffer;
  int regions = SolverParams{}.maxRegions;
  int strongRegions = SolverParams{}.strongShotRegions;
  double strongFraction = SolverParams{}.strongShotFraction;
  float regionSize = SolverParams{}.regionSize;
  bool repair = false;
  bool quiet = false;
  std::string viewSize;  ///< "W×H" of the view pictures, "" for 640 × the camera's aspect
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

// On-demand bakes (radiosity/cell_selection.h): the cells to bake, or nothing for a whole bake.
struct OnDemand {
  bool active = false;
  CellSelection selection;
  BoundaryMode mode = BoundaryMode::Coarse;
  int aroundCell = -1;
};

OnDemand resolveOnDemand(const BakeOptions& o, const Scene& scene, const CellGraph& graph) {
  OnDemand d;
  if (o.onlyCells.empty() && o.around.empty()) return d;
  const std::string option = o.onlyCells.empty() ? "--around" : "--only-cells";
  if (o.method != "cells") throw InputError(option, "needs --method cells");
  d.active = true;
  d.mode = parseBoundaryMode(o.boundary);
  std::vector<int> baked;
  if (!o.onlyCells.empty()) {
    baked = cellsByName(graph, o.onlyCells, "--only-cells");
  } else {
    const glm::vec3 p = parsePoint(o.around, "--around");
    d.aroundCell = cellContaining(scene, graph, p);
    if (d.aroundCell < 0) throw InputError("--around", "the point " + o.around + " is in no cell");
    baked = cellsWithin(graph, d.aroundCell, o.depth);
  }
  d.selection = selectCells(graph, baked);
  return d;
}

// report.json's "on_demand": which cells were baked and what the others did (null for a whole bake).
nlohmann::json onDemandReport(const BakeOptions& o, const OnDemand& d, const CellGraph& graph,
                              const LightmapAtlas& atlas) {
  if (!d.active) return nullptr;
  auto names = [&](const std::vector<int>& cells) {
    nlohmann::json out = nlohmann::json::array();
    for (int c : cells) out.push_back(graph.cells[c].name);
    return out;
  };
  // Texels of the atlas that belong to baked cells: the only ones with light.
  std::vector<char> baked(graph.cells.size(), 0);
  for (int c : d.selection.baked) baked[c] = 1;
  size_t texels = 0;
  for (int c : cellOfTexels(atlas, graph, atlas.triangleUV.size())) texels += c >= 0 && baked[c];
  nlohmann::json j = {{"baked", names(d.selection.baked)},
                      {"boundary", names(d.selection.boundary)},
                      {"dark", names(d.selection.dark)},
                      {"boundary_mode", boundaryModeName(d.mode)},
                      {"baked_texels", texels}};
  j["boundary_role"] =
      d.mode == BoundaryMode::Coarse
          ? "solved on a coarse atlas, lighting the baked cells through their portals; not written"
          : "dark";
  if (!o.onlyCells.empty()) j["only_cells"] = o.onlyCells;
  if (d.aroundCell >= 0) {
    j["around"] = o.around;
    j["around_cell"] = graph.cells[d.aroundCell].name;
    j["depth"] = o.depth;
  }
  return j;
}

int runBake(const BakeOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  Context ctx;
  ctx.setProgress(progressPrinter(o.quiet));
  const ViewParams viewSize = parseViewSize(o.viewSize);  // checked before any work

  AtlasParams atlasParams;
  atlasParams.texelsPerQuad = o.texelsPerQuad;
  atlasParams.density = o.density;
  SolverParams solverParams;
  solverParams.visibility = parseVisibility(o.visibility);
  solverParams.itemBuffer = o.itemBuffer;
  solverParams.maxRegions = o.regions;
  solverParams.strongShotRegions = o.strongRegions;
  solverParams.strongShotFraction = o.strongFraction;
  solverParams.regionSize = o.regionSize;
  solverParams.unshotFraction = o.unshot;
  solverParams.maxShots = o.maxShots;

  LoadedScene loaded;
  {
    auto t = ctx.time("load");
    loaded = loadScene(o.scene, LoadOptions{.repair = o.repair});
  }
  for (const std::string& w : loaded.warnings) ctx.warn(w);
  CellGraph graph;
  if (o.method == "cells")
    graph = resolveCells(o.cells, o.scene, loaded, decomp::DecomposeParams{}, o.repair, ctx);
  const OnDemand onDemand = resolveOnDemand(o, loaded.scene, graph);
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
  CellSolveResult cellSolved;
  if (o.method == "cells") {
    auto t = ctx.time("solve");
    CellSolveParams params;
    params.solver = solverParams;
    params.atlas = atlasParams;
    params.maxRounds = o.maxRounds;
    params.portals = parsePortalLight(o.portals);
    params.jobs = o.jobs;
    cellSolved = onDemand.active ? solveCellsOnDemand(loaded.scene, graph, onDemand.selection, onDemand.mode,
                                                      atlas, params, *gl, ctx)
                                 : solveCells(loaded.scene, graph, atlas, params, *gl, ctx);
    solved.radiosity = cellSolved.radiosity;
    solved.shots = cellSolved.shots;
    solved.unshotFraction = cellSolved.unshotFraction;
    solved.seconds = cellSolved.seconds;
    solved.energy.emitted = cellSolved.emitted;
    solved.energy.absorbed = cellSolved.absorbed;
    solved.energy.unshot = cellSolved.unshot;
    // Σ over cells of (shot − received): shot and received are not kept separately across cells.
    solved.energy.shot = cellSolved.escaped;
    solved.energy.received = 0.0;
  } else {
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

    // The PNG (alone and inside baked.glb) shows radiance B/π at the lightmap's exposure, like the
    // reference's.
    const float exposure = viewExposure(atlas, lit);
    const std::string png = encodePng(image, exposure / 3.14159265f);
    writeFileAtomically(out.file("lightmap.png"), png);
    GltfWriteOptions gltf;
    gltf.lightmapUVs = &atlas.triangleUV;
    gltf.lightmapPng = png;
    // The cells as cell: nodes and their portals, so viewers and `cpgi bake --cells` find them again.
    gltf.cells = o.method == "cells" ? &graph : loaded.cells.empty() ? nullptr : &loaded.cells;
    // writeGltf picks the format by extension, which OutputDir's temporary name does not end in.
    const std::filesystem::path stagedGlb = out.file("baked.glb");
    std::filesystem::path withExtension = stagedGlb;
    withExtension += ".glb";
    writeGltf(withExtension.string(), loaded.scene, gltf);
    std::filesystem::rename(withExtension, stagedGlb);

    ViewParams viewParams = viewSize;  // each picture exposed for what its camera sees
    views = renderViews(loaded.scene, loaded.cells, atlas, lit, out, ctx, viewParams);
  }

  nlohmann::json timings = nlohmann::json::object();
  for (const Context::Timing& t : ctx.timings()) timings[t.stage] = timings.value(t.stage, 0.0) + t.seconds;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const EnergyTotals& e = solved.energy;
  nlohmann::json report = {{"method", o.method},
                           {"scene", o.scene},
                           {"seconds", seconds},
                           {"solve_seconds", solved.seconds},
                           {"texels", atlas.validTexels()},
                           {"shots", solved.shots},
                           {"unshot_fraction", solved.unshotFraction},
                           {"unshot_target", solverParams.unshotFraction},
                           {"cells", o.method == "cells" ? graph.cells.size() : size_t(1)},
                           {"portals", o.method == "cells" ? graph.portals.size() : size_t(0)},
                           {"visibility", visibilityName(solverParams.visibility)},
                           {"item_buffer", solverParams.itemBuffer},
                           {"regions", solverParams.maxRegions},
                           {"strong_shot_regions", solverParams.strongShotRegions},
                           {"strong_shot_fraction", solverParams.strongShotFraction},
                           {"region_size", solverParams.regionSize},
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
  if (o.method == "cells") {
    report["energy"].erase("shot_w");
    report["energy"].erase("received_w");
    report["rounds"] = cellSolved.rounds;
    report["jobs"] = o.jobs;
    report["portal_mode"] = o.portals;
    report["max_cell_texels"] = cellSolved.maxCellTexels;
    nlohmann::json cells = nlohmann::json::array(), portals = nlohmann::json::array();
    for (const CellEnergy& c : cellSolved.cells)
      cells.push_back({{"name", c.name},
                       {"emitted_w", c.emitted},
                       {"received_w", c.received},
                       {"absorbed_w", c.absorbed},
                       {"sent_w", c.sent},
                       {"unshot_w", c.unshot},
                       {"escaped_w", c.escaped},
                       {"solves", c.solves},
                       {"written", c.written},
                       {"shots", c.shots},
                       {"texels", c.texels},
                       {"solve_seconds", c.seconds}});
    for (const PortalEnergy& pe : cellSolved.portals) {
      // By name: an on-demand bake solves only some of the graph's portals.
      const auto q = std::find_if(graph.portals.begin(), graph.portals.end(),
                                  [&](const PortalQuad& g) { return g.name == pe.name; });
      portals.push_back({{"name", pe.name},
                         {"cell_a", graph.cells[q->cellA].name},
                         {"cell_b", graph.cells[q->cellB].name},
                         {"a_to_b_w", pe.aToB},
                         {"b_to_a_w", pe.bToA}});
    }
    report["cell_energy"] = cells;
    report["portal_energy"] = portals;
    report["on_demand"] = onDemandReport(o, onDemand, graph, atlas);
  }
  writeFileAtomically(out.file("report.json"), report.dump(2) + "\n");
  writeBakeReportPage(out, "bake of " + o.scene, report, loaded.scene,
                      o.method == "cells" ? graph : loaded.cells, atlas, solved.radiosity);
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
  CLI::App* sub =
      app.add_subcommand("bake", "Bake diffuse global illumination into a lightmap (GPU radiosity)");
  sub->add_option("scene", o->scene, "Scene (.glb, .gltf, .obj)")->required();
  sub->add_option("-o,--output", o->output, "Output folder")->required();
  sub->add_option("--method", o->method,
                  "global: one progressive radiosity solve over the whole scene; cells: cell by cell, light "
                  "handed on through portals (needs --cells)")
      ->check(CLI::IsMember({"global", "cells"}))
      ->capture_default_str();
  sub->add_option("--cells", o->cells,
                  "With --method cells: a glTF with cell:/portal: nodes (the scene itself when it has them), "
                  "a decompose output folder, or auto (the automatic decomposition)")
      ->capture_default_str();
  sub->add_option("--portals", o->portals,
                  "Portal light with --method cells: diffuse (re-emits the irradiance as a Lambertian area "
                  "light) or directional (keeps the directions the light arrived with)")
      ->check(CLI::IsMember({"diffuse", "directional"}))
      ->capture_default_str();
  sub->add_option("--max-rounds", o->maxRounds, "With --method cells: solve rounds (syncs) at most")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  auto* only =
      sub->add_option("--only-cells", o->onlyCells,
                      "With --method cells: bake only these cells (comma-separated names); the others "
                      "act through their portals (see --boundary)");
  auto* around =
      sub->add_option("--around", o->around,
                      "With --method cells: bake the cell holding the point X,Y,Z (metres) and those "
                      "within --depth portals of it");
  only->excludes(around);
  sub->add_option("--depth", o->depth, "With --around: portals away from the point's cell")
      ->check(CLI::Range(0, 1000000))
      ->needs(around)
      ->capture_default_str();
  sub->add_option("--boundary", o->boundary,
                  "On demand: coarse (cells next to the baked ones are solved on a coarse atlas, so their "
                  "lamps and bounces light the baked cells through the portals; not written) or dark")
      ->check(CLI::IsMember({"coarse", "dark"}))
      ->capture_default_str();
  sub->add_option("--jobs", o->jobs,
                  "With --method cells: cells solved at once in a round, each on its own thread and OpenGL "
                  "context (same result as 1)")
      ->check(CLI::Range(1, 64))
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
  sub->add_option("--regions", o->regions,
                  "Visibility regions per edge of a large shooter, each with its own item buffer: soft light "
                  "through doors from large shooters, at up to N² item buffers per shot")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  sub->add_option("--strong-regions", o->strongRegions,
                  "Visibility regions per edge for the strong shots, those carrying at least "
                  "--strong-fraction of the emitted power (0: as --regions)")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  sub->add_option("--strong-fraction", o->strongFraction,
                  "Share of the emitted power that makes a shot strong")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("--region-size", o->regionSize, "Metres per visibility region along a shooter's edge")
      ->check(CLI::Range(0.01f, 1000.0f))
      ->capture_default_str();
  sub->add_option("--view-size", o->viewSize,
                  "Size of the view-*.png/.exr pictures, WxH pixels (default 640 wide, "
                  "the camera's aspect)");
  sub->add_flag("--repair", o->repair, "Drop zero-area and duplicate triangles instead of failing");
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary");
  sub->callback([&selected, o] { selected = [o] { return runBake(*o); }; });
}

}  // namespace cpgi::cli
