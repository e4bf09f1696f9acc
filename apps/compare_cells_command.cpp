// cpgi compare-cells SCENE A B: two cell decompositions of one scene, as labels of the same empty voxels.
// A and B are each `auto` (decompose SCENE now and use its voxel labels), a scene file with cells
// (cell:/portal:/cellvolume: nodes, e.g. a decompose output's cells.glb or the hand-made scene itself), or
// a decompose output folder. B is the reference.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "decomposition/compare.h"
#include "decomposition/decompose.h"

namespace cpgi::cli {
namespace {

struct CompareOptions {
  std::string scene, a, b;
  double voxel = 0.0;
  bool json = false;
};

struct Labelled {
  std::string source;
  CellGraph graph;
  std::vector<int32_t> labels;
};

Labelled labelsFor(const std::string& what, const Scene& scene, const std::string& scenePath,
                   const decomp::VoxelSpace& space, Context& ctx) {
  Labelled out;
  out.source = what;
  if (what == "auto") {
    decomp::DecomposeParams p;
    p.voxelSize = space.frame.voxel;
    p.sourceName = scenePath;
    decomp::Decomposition d = decomp::decompose(scene, p, ctx);
    if (d.frame.dims != space.frame.dims)
      throw SystemError("compare-cells: the automatic decomposition's grid differs from the scene's");
    out.graph = std::move(d.graph);
    out.labels = std::move(d.voxelCell);
    return out;
  }
  std::string path = what;
  if (std::filesystem::is_directory(path)) path = (std::filesystem::path(path) / "cells.glb").string();
  if (!std::filesystem::exists(path)) throw InputError(what, "no such file (give a scene with cells, a folder with cells.glb, or auto)");
  LoadedScene loaded = loadScene(path, LoadOptions{true});
  if (loaded.cells.empty()) throw InputError(path, "has no cell: nodes to compare");
  out.source = path;
  out.graph = std::move(loaded.cells);
  out.labels = decomp::labelsFromCells(loaded.scene, out.graph, space.frame, space.space);
  return out;
}

int runCompare(const CompareOptions& o) {
  LoadedScene loaded = loadScene(o.scene, LoadOptions{true});
  decomp::DecomposeParams params;
  params.voxelSize = o.voxel;
  if (o.voxel < 0.0 || o.voxel > 10.0) throw InputError("--voxel", "must be in (0, 10] metres (0 chooses from the scene)");
  Context ctx;
  const double h = decomp::chooseVoxelSize(loaded.scene, params);
  const decomp::VoxelSpace space = decomp::buildVoxelSpace(loaded.scene, h, ctx);
  const Labelled a = labelsFor(o.a, loaded.scene, o.scene, space, ctx);
  const Labelled b = labelsFor(o.b, loaded.scene, o.scene, space, ctx);

  size_t both = 0, inside = 0;
  for (size_t i = 0; i < space.space.size(); ++i) {
    inside += space.space[i] == decomp::Space::Inside;
    both += a.labels[i] >= 0 && b.labels[i] >= 0;
  }
  const double ari = decomp::adjustedRandIndex(a.labels, b.labels);
  const int countA = int(a.graph.cells.size()), countB = int(b.graph.cells.size());
  const std::vector<double> iouB = decomp::bestMatchIoU(b.labels, countB, a.labels, countA);
  double meanIoU = 0.0;
  for (double v : iouB) meanIoU += v;
  meanIoU = iouB.empty() ? 0.0 : meanIoU / double(iouB.size());
  const std::vector<decomp::PortalMatch> matches = decomp::matchPortals(b.graph.portals, a.graph.portals);
  double worst = 0.0;
  bool unmatched = false;
  for (const auto& m : matches) {
    if (m.candidate < 0) unmatched = true;
    worst = std::max(worst, double(m.centreDistance));
  }

  nlohmann::json j;
  j["scene"] = o.scene;
  j["a"] = a.source;
  j["b"] = b.source;
  j["voxel_m"] = h;
  j["inside_voxels"] = inside;
  j["labelled_in_both"] = both;
  j["cells_a"] = countA;
  j["cells_b"] = countB;
  j["portals_a"] = a.graph.portals.size();
  j["portals_b"] = b.graph.portals.size();
  j["adjusted_rand_index"] = ari;
  j["matched_iou"] = meanIoU;
  nlohmann::json perCell = nlohmann::json::array();
  for (int c = 0; c < countB; ++c) perCell.push_back({{"cell", b.graph.cells[size_t(c)].name}, {"best_iou", iouB[size_t(c)]}});
  j["matched_iou_per_cell"] = perCell;
  nlohmann::json pm = nlohmann::json::array();
  for (const auto& m : matches) {
    nlohmann::json e = {{"reference", b.graph.portals[size_t(m.reference)].name}};
    if (m.candidate >= 0) {
      e["candidate"] = a.graph.portals[size_t(m.candidate)].name;
      e["centre_distance_m"] = m.centreDistance;
      e["normal_angle_deg"] = m.normalAngle;
      e["area_ratio"] = m.areaRatio;
    } else {
      e["candidate"] = nullptr;
    }
    pm.push_back(e);
  }
  j["portal_matches"] = pm;
  // The worst matched portal's centre error; null when B has portals that A cannot match at all.
  if (unmatched) j["portal_centre_error_m"] = nullptr;
  else j["portal_centre_error_m"] = worst;
  j["seconds"] = ctx.totalSeconds("voxelize") + ctx.totalSeconds("classify");

  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::printf("A: %s (%d cells, %zu portals)\nB: %s (%d cells, %zu portals)\n", a.source.c_str(), countA,
              a.graph.portals.size(), b.source.c_str(), countB, b.graph.portals.size());
  std::printf("voxel %.3g m, %zu inside voxels, %zu labelled by both\n", h, inside, both);
  std::printf("adjusted Rand index %.4f, mean best-match IoU %.4f\n", ari, meanIoU);
  for (int c = 0; c < countB; ++c) std::printf("  cell %-12s best IoU %.4f\n", b.graph.cells[size_t(c)].name.c_str(), iouB[size_t(c)]);
  for (const auto& m : matches) {
    if (m.candidate < 0) {
      std::printf("  portal %-16s unmatched\n", b.graph.portals[size_t(m.reference)].name.c_str());
      continue;
    }
    std::printf("  portal %-16s ~ %-16s centre %.3f m, normal %.2f deg, area ratio %.3f\n",
                b.graph.portals[size_t(m.reference)].name.c_str(), a.graph.portals[size_t(m.candidate)].name.c_str(),
                m.centreDistance, m.normalAngle, m.areaRatio);
  }
  return 0;
}

}  // namespace

void addCompareCellsCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare-cells",
      "Compare two cell decompositions of SCENE over its empty voxels (adjusted Rand index, best-match IoU, "
      "portal matches). A and B: `auto`, a scene with cell:/portal: nodes, or a decompose output folder; B is "
      "the reference");
  cmd->add_option("scene", o->scene, "The scene both decompositions are of")->required();
  cmd->add_option("a", o->a, "Candidate decomposition")->required();
  cmd->add_option("b", o->b, "Reference decomposition")->required();
  cmd->add_option("--voxel", o->voxel, "Voxel edge, metres; 0 = as decompose chooses")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON (adjusted_rand_index, matched_iou, portal_matches, portal_centre_error_m)");
  cmd->callback([o, &selected] { selected = [o] { return runCompare(*o); }; });
}

}  // namespace cpgi::cli
