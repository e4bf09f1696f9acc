// report.json of a bake (bake_steps.h, bakeReport): the keys every lightmap producer writes
// (lightmap_report.h) and the bake's own: solver settings, two levels, the automatic density, the stop per
// cell, the ambient term, a partial result, and a cells bake's rounds, per-cell and per-portal energy.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "radiosity/bake/bake_steps.h"
#include "radiosity/bake/lightmap_report.h"
#include "radiosity/lightmap/cell_channel.h"

namespace cpgi::bake_steps {
namespace {

// report.json's "on_demand": which cells were baked and what the others did (null for a whole bake).
nlohmann::json onDemandReport(const BakeSettings& s, const OnDemand& d, const CellGraph& graph,
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
  if (!s.cells.onlyCells.empty()) j["only_cells"] = s.cells.onlyCells;
  if (d.aroundCell >= 0) {
    j["around"] = s.cells.around;
    j["around_cell"] = graph.cells[d.aroundCell].name;
    j["depth"] = s.cells.depth;
  }
  return j;
}

// report.json's keys of a cells bake: rounds, per-cell and per-portal energy, the on-demand choice.
void addCellsReport(const BakeSettings& s, const BakeInput& in, const CellSolveData& r,
                    nlohmann::json& report) {
  report["energy"].erase("shot_w");
  report["energy"].erase("received_w");
  report["rounds"] = r.rounds;
  report["jobs"] = s.cells.params.jobs;
  report["portal_mode"] = portalLightName(s.cells.params.portals);
  report["max_cell_texels"] = r.maxCellTexels;
  nlohmann::json cells = nlohmann::json::array(), portals = nlohmann::json::array();
  for (const CellEnergy& c : r.cells)
    cells.push_back({{"name", c.name},
                     {"emitted_w", c.emitted},
                     {"received_w", c.received},
                     {"absorbed_w", c.absorbed},
                     {"sent_w", c.sent},
                     {"unshot_w", c.unshot},
                     {"escaped_w", c.escaped},
                     {"created_w", c.created},
                     {"worst_shot_gain", c.worstShotGain},
                     {"solves", c.solves},
                     {"written", c.written},
                     {"shots", c.shots},
                     {"texels", c.texels},
                     {"solve_seconds", c.seconds}});
  for (const PortalEnergy& pe : r.portals) {
    // By name: an on-demand bake solves only some of the graph's portals.
    const auto q = std::find_if((*in.cells).portals.begin(), (*in.cells).portals.end(),
                                [&](const PortalQuad& g) { return g.name == pe.name; });
    portals.push_back({{"name", pe.name},
                       {"cell_a", (*in.cells).cells[q->cellA].name},
                       {"cell_b", (*in.cells).cells[q->cellB].name},
                       {"a_to_b_w", pe.aToB},
                       {"b_to_a_w", pe.bToA}});
  }
  report["cell_energy"] = cells;
  report["portal_energy"] = portals;
  report["on_demand"] = onDemandReport(s, in.onDemand, (*in.cells), in.atlas);
}

// --density auto's choice: its settings, the pilot, and the output's texels by the density they got.
nlohmann::json autoDensityReport(const BakeSettings& s, const BakeInput& in) {
  if (!in.autoDensity) return nullptr;
  const AutoDensityParams& p = s.atlas.autoDensity;
  std::map<double, size_t> texels;  // by texels per metre along the chart's coarser axis, to 0.1
  for (const Patch& patch : in.atlas.patches) {
    const double edge = std::max(glm::length(patch.texelU), glm::length(patch.texelV));
    if (edge > 0.0) texels[std::round(10.0 / edge) / 10.0] += size_t(patch.w) * size_t(patch.h);
  }
  nlohmann::json byDensity = nlohmann::json::array();
  for (const auto& [density, count] : texels) byDensity.push_back({{"density", density}, {"texels", count}});
  return {{"pilot_density", p.pilotDensity},
          {"min_density", p.light.minDensity},
          {"max_density", p.light.maxDensity},
          {"tolerance", p.light.tolerance},
          {"floor_share", p.light.floorShare},
          {"contacts", p.contacts},
          {"max_contact_density", p.maxContactDensity},
          {"pilot_texels", in.autoDensity->pilotTexels},
          {"pilot_s", in.autoDensity->pilotSeconds},
          {"contact_triangles", in.autoDensity->contactTriangles},
          {"chart_texels_by_density", byDensity}};
}

// --time-limit's seconds as the user gave them (120, not 120.000000).
std::string formatSeconds(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

// A two-level solve's own figures (radiosity/solve/two_level_solve.h, TwoLevelData).
void addTwoLevelReport(const BakeSettings& s, const TwoLevelData& levels, nlohmann::json& report) {
  report["lamp_shots"] = levels.lampShots;
  report["refined_triangles"] = levels.refinedTriangles;
  report["lamp_coarsening"] = s.solver.lampCoarsening;
  report["lamp_coarse_texels"] = levels.lampCoarseTexels;
  report["lamp_refined_texels"] = levels.lampRefinedTexels;
  report["lamp_solve_s"] = levels.lampSeconds;
  report["indirect_solve_s"] = levels.solveSeconds;
  report["indirect_item_buffer"] = levels.indirectItemBuffer;
  report["indirect_solver"] = levels.indirectBackend == "rays" ? "rays" : "gpu";
  // Its set-up against --time-limit: the estimate it was weighed by, what it took, and how it ended.
  report["indirect_setup"] = {
      {"estimate_s", levels.setupEstimate},
      {"s", levels.setupSeconds},
      {"cpu_s", levels.setupCpuSeconds},
      {"stopped", levels.setupStop.empty() ? nlohmann::json(nullptr) : nlohmann::json(levels.setupStop)}};
}

}  // namespace

nlohmann::json bakeReport(const BakeSettings& s, const BakeInput& in, const SolveResult& r,
                          const std::optional<TwoLevelData>& levels, const EglContext* gl,
                          const std::string& backend, const BakeFigures& f, const Context& ctx) {
  const bool cells = s.cells.method == BakeMethod::Cells;
  LightmapRun run{.method = bakeMethodName(s.cells.method),
                  .scene = s.input.scene,
                  .seconds = f.seconds,
                  .solveSeconds = r.seconds,
                  .atlas = &in.atlas,
                  .atlasParams = s.atlas.params,
                  .triangles = in.scene->triangles.size(),
                  .quads = in.quads.quads.size(),
                  .shots = r.shots,
                  .unshotFraction = r.unshotFraction,
                  .cells = cells ? (*in.cells).cells.size() : size_t(1),
                  .portals = cells ? (*in.cells).portals.size() : size_t(0),
                  .views = f.views,
                  .cellNames = f.cellNames};
  nlohmann::json report = lightmapReport(run, ctx);
  report["engine_lightmap"] = f.engine;
  report["unshot_target"] = s.solver.params.unshotFraction;
  report["visibility"] = visibilityName(s.solver.params.visibility);
  report["item_buffer"] = s.solver.params.itemBuffer;
  report["regions"] = s.solver.params.maxRegions;
  report["strong_shot_regions"] = s.solver.params.strongShotRegions;
  report["strong_shot_fraction"] = s.solver.params.strongShotFraction;
  report["region_size"] = s.solver.params.regionSize;
  report["jittered_eyes"] = s.solver.params.jitteredEyes;
  report["lamp_rays"] = s.solver.params.lampRays;
  // Two levels (radiosity/solve/two_level_solve.h): the lamps on the output's atlas, the rest on a coarser
  // one.
  report["solve_density"] = !levels                       ? nlohmann::json(nullptr)
                            : levels->solveDensity > 0.0f ? nlohmann::json(levels->solveDensity)
                                                          : nlohmann::json(chosenSolveDensity(s, in.atlas));
  report["solve_density_option"] = s.solver.solveDensity == kAutoSolveDensity
                                       ? nlohmann::json("auto")
                                       : nlohmann::json(s.solver.solveDensity);
  report["solve_texels"] = levels ? levels->solveTexels : in.atlas.validTexels();
  if (levels) addTwoLevelReport(s, *levels, report);
  report["density_option"] = s.atlas.densityAuto ? nlohmann::json("auto") : nlohmann::json(nullptr);
  report["stop_bounded"] = r.stopBounded;  // the loop's bound on the stop per room (progressive_loop.h)
  report["max_texels"] =
      s.atlas.densityAuto ? nlohmann::json(s.atlas.autoDensity.maxTexels) : nlohmann::json(nullptr);
  report["auto_density"] = autoDensityReport(s, in);
  if (s.atlas.densityAuto) report["atlas"]["density"] = "auto";
  report["backend"] =
      backend;  // the engine of the lamps' shots and every solve (indirect_solver: two levels')
  report["renderer"] = gl ? nlohmann::json(gl->renderer()) : nlohmann::json(nullptr);
  report["gl_version"] = gl ? nlohmann::json(gl->version()) : nlohmann::json(nullptr);
  report["egl_platform"] = gl ? nlohmann::json(gl->platform()) : nlohmann::json(nullptr);
  report["sky"] = skyReport(*in.scene);
  report["energy"] = energyReport(r.energy);
  // A solve the time limit stopped: the light it had not yet carried is still unshot (spread by the ambient
  // term unless --no-ambient), beside what the surfaces absorbed and what left the scene.
  report["energy"]["stopped_early"] = r.timedOut;
  report["energy"]["unshot_share"] = r.energy.emitted > 0.0 ? r.energy.unshot / r.energy.emitted : 0.0;
  report["ambient_w_m2"] = {f.ambient.r, f.ambient.g, f.ambient.b};
  // The stop per cell: the target, how often the solve was asked to stop, and each cell's share at the end.
  report["ambient_share_target"] = levels ? nlohmann::json(nullptr) : nlohmann::json(s.solver.ambientShare);
  report["stop_checks"] = r.stopChecks;
  nlohmann::json shares = nlohmann::json::object();
  for (size_t c = 0; c < f.ambientShares.size(); ++c)
    shares[c < f.cellNames.size() ? f.cellNames[c] : std::string("(no cell)")] = f.ambientShares[c];
  report["ambient_share"] = shares;
  nlohmann::json escape = nlohmann::json::object();
  for (size_t c = 0; c < f.ambientEscape.size(); ++c)
    escape[c < f.cellNames.size() ? f.cellNames[c] : std::string("(no cell)")] = f.ambientEscape[c];
  report["ambient_escape"] = escape;
  // A bake stopped by --time-limit is valid but partial: what it left unshot is in energy.unshot_w (and
  // spread by the ambient term unless --no-ambient).
  report["time_limit_s"] =
      s.limits.timeLimit > 0.0 ? nlohmann::json(s.limits.timeLimit) : nlohmann::json(nullptr);
  // The outputs' share kept back from the solve (bake_limits.h), and the views the limit left out.
  report["output_estimate_s"] = {{"views", f.outputs.viewSeconds},
                                 {"files", f.outputs.filesSeconds},
                                 {"page", f.outputs.pageSeconds},
                                 {"directional", f.outputs.directionalSeconds},
                                 {"probes", f.outputs.probesSeconds},
                                 {"ray", f.outputs.raySeconds},
                                 {"texel", f.outputs.texelSeconds},
                                 {"texel_cpu", f.outputs.texelCpuSeconds},
                                 {"load", f.outputs.load},
                                 {"cpu_share", f.outputs.load > 0.0 ? 1.0 / f.outputs.load : 0.0}};
  report["views_skipped"] = f.skippedViews;
  report["view_width"] = f.viewWidth;
  std::vector<std::string> skipped = f.outputsLeftOut;
  skipped.insert(skipped.end(), f.skippedOutputs.begin(), f.skippedOutputs.end());
  report["outputs_skipped"] = skipped;
  report["partial"] = r.timedOut || !f.skippedViews.empty() || !skipped.empty();
  std::ostringstream why;
  if (r.timedOut)
    why << "time limit of " << formatSeconds(s.limits.timeLimit) << " s reached after " << r.shots
        << " shots with " << r.unshotFraction * 100.0 << " % of the emitted power unshot (target "
        << s.solver.params.unshotFraction * 100.0 << " %)";
  if (r.timedOut && levels && !levels->setupStop.empty())
    why << "; the interreflection's set-up " << levels->setupStop << " (indirect_setup)";
  if (!f.skippedViews.empty())
    why << (r.timedOut ? "; " : "") << "time limit of " << formatSeconds(s.limits.timeLimit)
        << " s reached before " << f.skippedViews.size() << " of " << f.skippedViews.size() + f.views.size()
        << " views were rendered (views_skipped)";
  for (const std::string& o : f.skippedOutputs)
    why << (why.tellp() > 0 ? "; " : "") << "time limit of " << formatSeconds(s.limits.timeLimit)
        << " s reached during the " << o << " gather, whose files were not written (outputs_skipped)";
  for (const std::string& o : f.outputsLeftOut)
    why << (why.tellp() > 0 ? "; " : "") << "time limit of " << formatSeconds(s.limits.timeLimit)
        << " s left no time for the " << o << ", left out before they started (outputs_skipped)";
  if (report["partial"].get<bool>()) report["partial_reason"] = why.str();
  if (r.perCell) addCellsReport(s, in, *r.perCell, report);
  return report;
}

}  // namespace cpgi::bake_steps
