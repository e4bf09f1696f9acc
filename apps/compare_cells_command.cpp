// cpgi compare-cells SCENE A B: two cell decompositions of one scene, as labels of the same empty voxels.
// A and B are each `auto` (decompose SCENE now and use its voxel labels), a scene file with cells
// (cell:/portal:/cellvolume: nodes, e.g. a decompose output's cells.glb or the hand-made scene itself), or
// a decompose output folder. B is the reference. With --bake, SCENE is also baked with each (`bake --method
// cells`) and both bakes are measured against a path-traced reference (apps/compare_cells_bake.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/compare_cells_bake.h"
#include "apps/options.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/scene_io.h"
#include "decomposition/compare.h"
#include "decomposition/decompose.h"
#include "decomposition/volume_cells.h"
#include "radiosity/bake/cell_source.h"

namespace cpgi::cli {
namespace {

struct CompareOptions {
  std::string scene, a, b;
  decomp::DecomposeParams decompose;  ///< voxelSize 0: as decompose chooses
  LoadOptions load;                   ///< SCENE's and A's/B's scene files
  bool json = false;
  bool bake = false;
  CellBakeComparison bakeParams = [] {
    CellBakeComparison p;
    p.reference.spp = 64;  // a check of two decompositions, not a reference to keep
    return p;
  }();
};

struct Labelled {
  std::string source;
  CellGraph graph;
  std::vector<int32_t> labels;
  double decomposeSeconds = 0.0;  ///< auto only
  CellsToBake bake;               ///< with --bake: the scene and graph `bake --method cells` would use
};

Labelled labelsFor(const std::string& what, const LoadedScene& scene, const std::string& scenePath,
                   const decomp::VoxelSpace& space, const decomp::DecomposeParams& params,
                   const LoadOptions& load, bool forBake, Context& ctx) {
  Labelled out;
  out.source = what;
  out.bake.source = what;
  if (what == "auto") {
    decomp::DecomposeParams p = params;
    p.voxelSize = space.frame.voxel;
    p.sourceName = scenePath;
    const auto start = std::chrono::steady_clock::now();
    decomp::Decomposition d = decomp::decompose(scene.scene, p, ctx);
    out.decomposeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (d.frame.dims != space.frame.dims)
      throw SystemError("compare-cells: the automatic decomposition's grid differs from the scene's");
    if (forBake) {  // the very decomposition compared, split triangles and all
      out.bake.scene = std::move(d.scene);
      out.bake.scene.lights = scene.scene.lights;  // split triangles, the same lights
      out.bake.graph = d.graph;
    }
    out.graph = std::move(d.graph);
    out.labels = std::move(d.voxelCell);
    return out;
  }
  std::string path = what;
  if (std::filesystem::is_directory(path)) path = (std::filesystem::path(path) / "cells.glb").string();
  if (!std::filesystem::exists(path))
    throw InputError(what, "no such file (give a scene with cells, a folder with cells.glb, or auto)");
  LoadedScene loaded = loadScene(path, load);
  if (loaded.cells.empty()) throw InputError(path, "has no cell: or cellvolume: nodes to compare");
  out.source = path;
  out.graph = std::move(loaded.cells);
  out.labels = decomp::labelsFromCells(loaded.scene, out.graph, space.frame, space.space);
  if (forBake) {
    LoadedScene copy = scene;
    out.bake.source = path;
    out.bake.graph = resolveCells(path, scenePath, copy, params, load, ctx);
    out.bake.scene = std::move(copy.scene);
  }
  return out;
}

// A side's portals. Rooms given as cellvolume: meshes alone (an IFC export's) carry none: theirs are the ones
// the decomposition fits where the volumes meet (decompose --from-volumes), so there is something to match.
std::vector<PortalQuad> portalsOf(const LoadedScene& loaded, const Labelled& x,
                                  const decomp::DecomposeParams& params, bool& fitted, Context& ctx) {
  fitted = false;
  const bool volumesOnly = x.graph.portals.empty() && !x.graph.cells.empty() &&
                           std::all_of(x.graph.cells.begin(), x.graph.cells.end(), [](const Cell& c) {
                             return c.triangles.empty() && !c.volume.empty();
                           });
  if (!volumesOnly) return x.graph.portals;
  try {
    std::vector<PortalQuad> portals =
        decomp::decomposeFromVolumes(loaded.scene, x.graph, params, {}, ctx).graph.portals;
    fitted = true;
    return portals;
  } catch (const InputError& e) {  // volumes that hold no empty space: nothing to fit, nothing to score
    ctx.warn(std::string("no portals fitted where the room volumes meet: ") + e.what());
    return x.graph.portals;
  }
}

nlohmann::json portalMatchesJson(const std::vector<decomp::PortalMatch>& matches,
                                 const std::vector<PortalQuad>& portalsA,
                                 const std::vector<PortalQuad>& portalsB) {
  nlohmann::json pm = nlohmann::json::array();
  for (const auto& m : matches) {
    nlohmann::json e = {{"reference", portalsB[size_t(m.reference)].name}};
    if (m.candidate >= 0) {
      e["candidate"] = portalsA[size_t(m.candidate)].name;
      e["centre_distance_m"] = m.centreDistance;
      e["normal_angle_deg"] = m.normalAngle;
      e["area_ratio"] = m.areaRatio;
    } else {
      e["candidate"] = nullptr;
    }
    pm.push_back(e);
  }
  return pm;
}

int runCompare(const CompareOptions& o) {
  LoadedScene loaded = loadScene(o.scene, o.load);
  decomp::DecomposeParams params = o.decompose;
  params.memoryLimit = o.bakeParams.atlas.memoryLimit;  // --max-memory (with --bake) or its default
  if (params.voxelSize < 0.0 || params.voxelSize > 10.0)
    throw InputError("voxel size", "must be in (0, 10] metres (0 chooses from the scene)");
  Context ctx;
  ctx.setProgress(stderrProgress(false));
  // The grid the decomposition makes: from the faces whole (decompose.h, withUnseenSurfaces).
  const Scene withUnseen = decomp::withUnseenSurfaces(loaded.scene);
  const Scene& surfaces = decomp::hasUnseenSurfaces(loaded.scene) ? withUnseen : loaded.scene;
  const decomp::GridChoice grid = decomp::chooseGrid(surfaces, params, ctx);
  const double h = grid.voxel;
  const decomp::VoxelSpace space = decomp::buildVoxelSpace(surfaces, h, ctx, params.memoryLimit,
                                                           grid.extent.trimmed ? grid.extent.box : Bounds{});
  const Labelled a = labelsFor(o.a, loaded, o.scene, space, params, o.load, o.bake, ctx);
  const Labelled b = labelsFor(o.b, loaded, o.scene, space, params, o.load, o.bake, ctx);

  size_t inside = 0;
  for (const decomp::Space v : space.space) inside += v == decomp::Space::Inside;
  const int countA = int(a.graph.cells.size()), countB = int(b.graph.cells.size());
  // Scored over the whole interior, the voxels either puts in a room: a decomposition that labels only
  // part of the rooms (a scene whose cells reach only enclosed space, in an open house) scores low.
  const decomp::InteriorLabels interior = decomp::interiorLabels(
      a.labels, countA, a.graph.findCell("outside"), b.labels, countB, b.graph.findCell("outside"));
  std::optional<double> ari;
  if (interior.both >= 2)
    ari = decomp::adjustedRandIndex(interior.a, interior.b);
  else
    ctx.warn("compare-cells: A and B share no room voxel: nothing to score (no adjusted Rand index)");
  for (const auto& [name, coverage] :
       {std::pair{"A", interior.coverageA()}, std::pair{"B", interior.coverageB()}})
    if (interior.interior > 0 && coverage < 0.5)
      ctx.warn("compare-cells: " + std::string(name) + " puts only " +
               std::to_string(int(std::lround(100 * coverage))) +
               " % of the interior in a room (the interior: the voxels A or B puts in a room)");
  // Each side's "no room" counts in the other's cell sizes but is no match.
  std::vector<double> iouB = decomp::bestMatchIoU(interior.b, countB + 1, interior.a, countA + 1, countA);
  iouB.resize(size_t(countB));
  double meanIoU = 0.0;
  for (double v : iouB) meanIoU += v;
  meanIoU = iouB.empty() ? 0.0 : meanIoU / double(iouB.size());
  bool fittedA = false, fittedB = false;
  const std::vector<PortalQuad> portalsA = portalsOf(loaded, a, params, fittedA, ctx),
                                portalsB = portalsOf(loaded, b, params, fittedB, ctx);
  const std::vector<decomp::PortalMatch> matches = decomp::matchPortals(portalsB, portalsA);
  double worst = 0.0;
  bool unmatched = false;
  for (const auto& m : matches) {
    if (m.candidate < 0) unmatched = true;
    worst = std::max(worst, double(m.centreDistance));
  }
  if (matches.empty()) ctx.warn("compare-cells: B has no portals: no portal to match");

  nlohmann::json j;
  j["scene"] = o.scene;
  j["a"] = a.source;
  j["b"] = b.source;
  j["voxel_m"] = h;
  j["inside_voxels"] = inside;
  j["interior_voxels"] = interior.interior;
  j["labelled_in_both"] = interior.both;
  j["coverage_a"] = interior.coverageA();
  j["coverage_b"] = interior.coverageB();
  j["cells_a"] = countA;
  j["cells_b"] = countB;
  j["portals_a"] = portalsA.size();
  j["portals_b"] = portalsB.size();
  // "volumes": fitted where the side's room volumes meet (it gave rooms as cellvolume: meshes alone).
  j["portals_a_from"] = fittedA ? "volumes" : "cells";
  j["portals_b_from"] = fittedB ? "volumes" : "cells";
  // null, not a perfect 1, when there is nothing to compare.
  j["adjusted_rand_index"] = ari ? nlohmann::json(*ari) : nlohmann::json(nullptr);
  j["matched_iou"] = meanIoU;
  nlohmann::json perCell = nlohmann::json::array();
  for (int c = 0; c < countB; ++c)
    perCell.push_back({{"cell", b.graph.cells[size_t(c)].name}, {"best_iou", iouB[size_t(c)]}});
  j["matched_iou_per_cell"] = perCell;
  j["portal_matches"] = portalMatchesJson(matches, portalsA, portalsB);
  // The worst matched portal's centre error; null when B has portals that A cannot match at all, or none.
  if (unmatched || matches.empty())
    j["portal_centre_error_m"] = nullptr;
  else
    j["portal_centre_error_m"] = worst;
  j["seconds"] = ctx.totalSeconds("voxelize") + ctx.totalSeconds("classify");
  if (o.a == "auto") j["decompose_seconds_a"] = a.decomposeSeconds;
  if (o.b == "auto") j["decompose_seconds_b"] = b.decomposeSeconds;
  if (o.bake) j["bake"] = compareCellBakes(o.scene, a.bake, b.bake, o.bakeParams, ctx);
  j["warnings"] = ctx.warnings();

  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::printf("A: %s (%d cells, %zu portals)\nB: %s (%d cells, %zu portals)\n", a.source.c_str(), countA,
              portalsA.size(), b.source.c_str(), countB, portalsB.size());
  std::printf(
      "voxel %.3g m, %zu interior voxels (in a room of A or B): %.0f %% in A's rooms, %.0f %% in B's\n", h,
      interior.interior, 100 * interior.coverageA(), 100 * interior.coverageB());
  if (ari)
    std::printf("adjusted Rand index %.4f, mean best-match IoU %.4f\n", *ari, meanIoU);
  else
    std::printf("adjusted Rand index n/a (no room voxel in both), mean best-match IoU %.4f\n", meanIoU);
  for (int c = 0; c < countB; ++c)
    std::printf("  cell %-12s best IoU %.4f\n", b.graph.cells[size_t(c)].name.c_str(), iouB[size_t(c)]);
  for (const auto& m : matches) {
    if (m.candidate < 0) {
      std::printf("  portal %-16s unmatched\n", portalsB[size_t(m.reference)].name.c_str());
      continue;
    }
    std::printf("  portal %-16s ~ %-16s centre %.3f m, normal %.2f deg, area ratio %.3f\n",
                portalsB[size_t(m.reference)].name.c_str(), portalsA[size_t(m.candidate)].name.c_str(),
                m.centreDistance, m.normalAngle, m.areaRatio);
  }
  if (o.bake) printCellBakes(j["bake"]);
  for (const std::string& w : ctx.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return 0;
}

}  // namespace

void addCompareCellsCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare-cells",
      "Compare two cell decompositions of SCENE over its empty voxels (adjusted Rand index, best-match IoU, "
      "portal matches). A and B: `auto`, a scene with cell:/portal: nodes, or a decompose output folder; B "
      "is "
      "the reference");
  cmd->add_option("scene", o->scene, "The scene both decompositions are of")->required();
  cmd->add_option("a", o->a, "Candidate decomposition")->required();
  cmd->add_option("b", o->b, "Reference decomposition")->required();
  addDecomposeOptions(*cmd, o->decompose);
  addLoadOptions(*cmd, o->load);
  cmd->add_flag("--json", o->json,
                "Print JSON (adjusted_rand_index, matched_iou, portal_matches, portal_centre_error_m; with "
                "--bake, a bake object: a, b, references, difference_points)")
      ->group("Output");
  CLI::Option* bake =
      cmd->add_flag("--bake", o->bake,
                    "Also bake SCENE with A's and with B's cells (bake --method cells) and give each bake's "
                    "seconds, shots, "
                    "rounds and relative RMSE against a path-traced reference on the same atlas")
          ->group("Solver");
  const OptionScope withBake{.needs = bake};
  addAtlasOptions(*cmd, o->bakeParams.atlas, withBake);
  addSolverOptions(*cmd, o->bakeParams.solver, withBake);
  addSppOption(*cmd, o->bakeParams.reference.spp, withBake);
  cmd->callback([o, &selected] { selected = [o] { return runCompare(*o); }; });
}

}  // namespace cpgi::cli
