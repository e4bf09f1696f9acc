// cpgi decompose SCENE -o DIR: automatic cells and portals (decomposition/decompose.h), written as
// DIR/cells.glb (the scene split by cell plus portal quads), DIR/cells.json, DIR/decomposition.png and
// DIR/report.html (apps/report_page.h).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/commands.h"
#include "apps/options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/scene_io.h"
#include "decomposition/decompose.h"
#include "decomposition/picture.h"
#include "decomposition/report.h"
#include "decomposition/volume_cells.h"
#include "radiosity/bake/report_page.h"

namespace cpgi::cli {
namespace {

struct DecomposeOptions {
  std::string scene;
  std::string out;
  LoadOptions load;  ///< --strict, --allow-outside-files, --emit, --albedo
  bool json = false;
  bool fromVolumes = false;  ///< the scene's own rooms given as cellvolume: meshes alone, not the watershed
  decomp::DecomposeParams params;
};

int runDecompose(DecomposeOptions o) {
  LoadedScene loaded = loadScene(o.scene, o.load);
  printLoaderWarnings(o.scene, loaded.warnings);
  if (o.fromVolumes && !loaded.cells.definedByVolumes())
    throw InputError(o.scene,
                     "--from-volumes needs rooms given as cellvolume: meshes alone (no cell: or "
                     "portal: nodes)");
  if (!loaded.cells.empty() && !o.fromVolumes)
    printWarning(o.scene + ": ignoring its " + std::to_string(loaded.cells.cells.size()) +
                 " hand-made cells (compare them with `cpgi compare-cells`)");
  o.params.sourceName = o.scene;

  OutputDir dir(o.out, {"cells.glb", "cells.json", "decomposition.png", "report.html"});
  Context ctx;
  ctx.setProgress(stderrProgress(false));
  decomp::Decomposition d = o.fromVolumes
                                ? decomp::decomposeFromVolumes(loaded.scene, loaded.cells, o.params, {}, ctx)
                                : decomp::decompose(loaded.scene, o.params, ctx);
  d.scene.lights = loaded.scene.lights;  // cells.glb is the scene split by cell: its lights go with it
  d.scene.seal = loaded.scene.seal;      // and its seal, so that it decomposes as the scene did
  // The watershed's rooms take the names of the scene's own room volumes where one covers them.
  if (!o.fromVolumes) decomp::nameCellsByVolumes(d, loaded.cells);

  GltfWriteOptions gltf;
  gltf.cells = &d.graph;
  gltf.keepSeal = true;
  // A staged name keeps its extension, by which writeGltf picks the format; a write error names the file
  // as the user knows it (DIR/cells.glb).
  writeGltf(dir.file("cells.glb").string(), d.scene, gltf);
  {
    auto timer = ctx.time("picture");
    writePng(dir.file("decomposition.png").string(), decomp::drawDecomposition(d));
  }
  const nlohmann::json report = decomp::decompositionReport(d, o.params, ctx);
  writeFileAtomically(dir.file("cells.json"), report.dump(2) + "\n");
  writeDecompositionReportPage(dir, "decomposition of " + o.scene, report, d.scene, d.graph);
  dir.commit();

  for (const std::string& w : ctx.warnings()) printWarning(w);
  if (o.json) {
    std::cout << report.dump(2) << "\n";
    return 0;
  }
  const std::string from =
      o.fromVolumes ? "the scene's cellvolume: meshes" : std::to_string(d.basins) + " watershed basins";
  std::printf("%zu cells, %zu portals from %s; voxel %.3g m (%s)\n", d.graph.cells.size(),
              d.graph.portals.size(), from.c_str(), d.frame.voxel, d.voxelChoice.c_str());
  std::printf("grid %d x %d x %d; %zu triangles in, %zu out (%zu split at portals)\n", d.frame.dims.x,
              d.frame.dims.y, d.frame.dims.z, d.inputTriangles, d.scene.triangles.size(), d.splitTriangles);
  std::printf("outside: %s; voxel faces between cells not covered by a portal: %zu\n",
              d.outsideCell >= 0 ? "a cell (\"outside\")" : "not a cell (no room opens onto it)",
              d.leakingFaces);
  std::string closed, pockets;
  for (size_t c = 0; c < d.closedRoom.size(); ++c)
    if (d.closedRoom[c]) closed += (closed.empty() ? "" : ", ") + d.graph.cells[c].name;
  for (size_t c = 0; c < d.outsidePocket.size(); ++c)
    if (d.outsidePocket[c]) pockets += (pockets.empty() ? "" : ", ") + d.graph.cells[c].name;
  std::printf("closed rooms (no portal, touching no other cell): %s; the rooms are %s through portals\n",
              closed.empty() ? "none" : closed.c_str(),
              d.connectedOpen ? "all reachable from each other" : "NOT all reachable from each other");
  std::printf("%s\n", decomp::graphSummary(d).c_str());
  std::string apart;
  for (size_t c = 0; c < d.reachable.size(); ++c)
    if (!d.reachable[c] && !d.closedRoom[c]) apart += (apart.empty() ? "" : ", ") + d.graph.cells[c].name;
  std::printf("every cell reachable through portals or a closed room: %s\n",
              apart.empty() ? "yes" : ("NO: not reached from the main part: " + apart).c_str());
  if (!pockets.empty())
    std::printf(
        "sealed from the outside: no portal joins the rooms to it; only it reaches %s (space behind "
        "one-sided walls)\n",
        pockets.c_str());
  if (d.leakMerges > 0)
    std::printf("%d pairs of cells merged: they met outside any portal of theirs\n", d.leakMerges);
  for (const Context::Timing& t : ctx.timings()) std::printf("  %-20s %8.3f s\n", t.stage.c_str(), t.seconds);
  std::printf("  %-20s %8.3f s\n", "total", report["timings_s"]["total"].get<double>());
  std::printf("wrote %s/{cells.glb, cells.json, decomposition.png}\n", o.out.c_str());
  return 0;
}

}  // namespace

void addDecomposeCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<DecomposeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "decompose",
      "Automatic cells and portals: voxelize, watershed of the distance to the geometry, merge basins that "
      "meet at no real constriction, fit one quad per opening");
  cmd->add_option("scene", o->scene, "Scene file (.glb, .gltf, .obj)")->required();
  cmd->add_option("-o,--out", o->out,
                  "Output folder for cells.glb, cells.json, decomposition.png, report.html")
      ->required()
      ->group("Output");
  addDecomposeOptions(*cmd, o->params);
  addMemoryOption(*cmd, o->params.memoryLimit);
  addLoadOptions(*cmd, o->load);
  cmd->add_flag(
         "--from-volumes", o->fromVolumes,
         "The cells of the scene's own rooms given as cellvolume: meshes alone (as `bake --cells SCENE` "
         "makes them): portals where they meet an opening, every surface in the room it faces")
      ->group("Cells");
  cmd->add_flag("--json", o->json, "Print cells.json to stdout instead of the summary")->group("Output");
  cmd->callback([o, &selected] { selected = [o] { return runDecompose(*o); }; });
}

}  // namespace cpgi::cli
