#include "radiosity/cells/cell_jobs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>

#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_first_shot.h"
#include "radiosity/cells/cell_job_files.h"
#include "radiosity/cells/cell_round.h"
#include "radiosity/cells/portal_transfer.h"
#include "radiosity/cells/round_stop.h"

namespace cpgi {
namespace fs = std::filesystem;
namespace {

std::string padded(int i, const char* prefix) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s%04d", prefix, i);
  return buf;
}

// The cells across `c`'s portals, ascending.
std::vector<int> neighboursOf(const CellGraph& graph, int c) {
  std::vector<int> out;
  for (int p : graph.portalsOf(c)) {
    const PortalQuad& q = graph.portals[size_t(p)];
    const int other = q.cellA == c ? q.cellB : q.cellA;
    if (other >= 0 && other != c) out.push_back(other);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Part of the graph: `keep` (ascending) and the portals between them, in graph order, so that every kept
// cell's scene, atlas and portal links are those of the whole graph.
struct SubGraph {
  CellGraph graph;
  std::vector<int> cellOf, portalOf;  ///< sub index → graph index
  std::vector<int> subOf;             ///< graph cell → sub index or -1
};
SubGraph subGraph(const CellGraph& graph, const std::vector<int>& keep) {
  SubGraph s;
  s.subOf.assign(graph.cells.size(), -1);
  for (int c : keep) {
    s.subOf[size_t(c)] = int(s.graph.cells.size());
    s.cellOf.push_back(c);
    s.graph.cells.push_back(graph.cells[size_t(c)]);
  }
  for (size_t p = 0; p < graph.portals.size(); ++p) {
    const PortalQuad& q = graph.portals[p];
    if (q.cellA < 0 || q.cellB < 0 || s.subOf[size_t(q.cellA)] < 0 || s.subOf[size_t(q.cellB)] < 0) continue;
    PortalQuad sub = q;
    sub.cellA = s.subOf[size_t(q.cellA)], sub.cellB = s.subOf[size_t(q.cellB)];
    s.graph.portals.push_back(sub);
    s.portalOf.push_back(int(p));
  }
  return s;
}

// A round of cell `sub` as the graph numbers it.
void toGraphIndices(CellRound& r, const SubGraph& s) {
  r.cell = s.cellOf[size_t(r.cell)];
  for (PortalSend& send : r.sends) {
    send.portal = s.portalOf[size_t(send.portal)];
    send.from = s.cellOf[size_t(send.from)], send.to = s.cellOf[size_t(send.to)];
  }
}

// The power unshot after `round` (>= 1), from its summaries.
double unshotAfter(const fs::path& dir, const CellJobPlan& plan, int round,
                   std::vector<CellRoundSummary>* summaries = nullptr) {
  std::vector<CellRoundSummary> all(plan.cells.size());
  std::vector<double> kept(plan.cells.size());
  std::vector<const PortalSend*> sends;
  tbb::parallel_for(size_t(0), all.size(), [&](size_t c) {  // a file each: read side by side
    all[c] = readSummary(cellSummaryFile(dir, round, int(c)), round, int(c));
    kept[c] = all[c].figures.keptPower;
  });
  for (const CellRoundSummary& s : all)
    for (const PortalSend& send : s.figures.sends) sends.push_back(&send);
  const double unshot = roundUnshot(kept, sends);
  if (summaries) *summaries = std::move(all);
  return unshot;
}

// The rounds' stop as solveCells keeps it (round_stop.h), from the plan's figures.
RoundStop planStop(const CellJobPlan& plan) {
  return RoundStop(plan.target, plan.maxAmbientShare, plan.stopSurfaces, plan.openings);
}

// Whether round `round` runs, after rounds that left `unshotBefore` W unshot (`stop` fed their figures):
// the test of solveCells's loop, in its order.
bool roundNeeded(const CellJobPlan& plan, int round, double unshotBefore, RoundStop& stop) {
  return plan.emitted > 0.0 && round <= plan.maxRounds && stop.another(unshotBefore);
}

// Round `round` (>= 1) from its summaries into `stop`; returns the power unshot after it.
double addRoundToStop(const fs::path& dir, const CellJobPlan& plan, int round, RoundStop& stop,
                      std::vector<CellRoundSummary>* summaries = nullptr) {
  std::vector<CellRoundSummary> all;
  const double unshot = unshotAfter(dir, plan, round, &all);
  std::vector<const CellRound*> figures;
  for (const CellRoundSummary& s : all) figures.push_back(&s.figures);
  stop.addRound(figures);
  if (summaries) *summaries = std::move(all);
  return unshot;
}

// Cell `c`'s pending light for round `round`: its own state and the portal light its neighbours sent it
// in round − 1, into s.pending, s.pendingMoments (directional portals) and s.carried (the part already in
// the radiosity).
void gatherFromFiles(const fs::path& dir, const CellJobPlan& plan, int round, int c, CellState& s) {
  const size_t texels = s.pending.size();
  const CellRound own = readCellState(cellStateFile(dir, round - 1, c), round - 1, c);
  if (own.kept.size() != texels)
    throw InputError(cellStateFile(dir, round - 1, c).string(),
                     "holds " + std::to_string(own.kept.size()) + " texels, the cell has " +
                         std::to_string(texels) + " (another scene or other options than the plan's?)");
  std::vector<PortalSend> arriving;
  if (round - 1 >= 1)
    for (int n : plan.neighbours[size_t(c)]) {
      std::vector<PortalSend> in = readPortalLight(portalLightFile(dir, round - 1, n, c), round - 1, n, c);
      arriving.insert(arriving.end(), std::make_move_iterator(in.begin()), std::make_move_iterator(in.end()));
    }
  std::vector<const PortalSend*> ptrs;
  for (const PortalSend& send : arriving) {
    for (const auto& [t, e] : send.exitance)
      if (size_t(t) >= texels)
        throw InputError(portalLightFile(dir, round - 1, send.from, c).string(), "a texel outside the cell");
    ptrs.push_back(&send);
  }
  if (!own.keptMoments.empty() && own.keptMoments.size() != texels)
    throw InputError(cellStateFile(dir, round - 1, c).string(), "holds moments for another number of texels");
  const std::vector<const PortalSend*> sorted = sendsTo(c, ptrs);
  s.carried = own.carried;
  s.pending = gatherPending(own, sorted, texels);
  s.pendingMoments = gatherPendingMoments(own, sorted, texels);
  for (const auto& [t, b] : own.keptBins)
    if (size_t(t) >= texels)
      throw InputError(cellStateFile(dir, round - 1, c).string(), "bins for a texel outside the cell");
  s.pendingBins = gatherPendingBins(own, sorted);
}

void requireFirstShotSummed(const fs::path& dir, const CellJobPlan& plan) {
  if (!plan.firstShotSummed)
    throw InputError(
        (dir / "plan.json").string(),
        "the first shot is not summed yet (cpgi cell-job PLAN --first-shot, then --first-shot-sum)");
}

void requireSupported(const CellSolveParams& params) {
  if (!params.boundaryCells.empty() || params.partOfGraph)
    throw InputError("cells", "cell jobs bake the whole cell graph (no on-demand cells)");
}

}  // namespace

fs::path roundDir(const fs::path& dir, int round) {
  return dir / padded(round, "round-");
}
fs::path cellStateFile(const fs::path& dir, int round, int cell) {
  return roundDir(dir, round) / (padded(cell, "cell-") + ".state");
}
fs::path cellSummaryFile(const fs::path& dir, int round, int cell) {
  return roundDir(dir, round) / (padded(cell, "cell-") + ".summary");
}
fs::path portalLightFile(const fs::path& dir, int round, int from, int to) {
  return roundDir(dir, round) / (padded(from, "portal-") + padded(to, "-") + ".light");
}
fs::path firstShotGroupFile(const fs::path& dir, int group) {
  return dir / "first-shot" / (padded(group, "group-") + ".shot");
}

void writeCellJobPlan(const fs::path& dir, const CellJobPlan& plan) {
  nlohmann::json j = {{"format", "cpgi cell jobs"},
                      {"version", plan.version},
                      {"bake_settings", plan.bakeSettings},
                      {"working_dir", plan.workingDir},
                      {"first_shot_summed", plan.firstShotSummed},
                      {"emitted_w", plan.emitted},
                      {"target_w", plan.target},
                      {"max_rounds", plan.maxRounds},
                      {"global_patches", plan.globalPatches},
                      {"cells", nlohmann::json::array()}};
  for (size_t c = 0; c < plan.cells.size(); ++c) {
    const CellStopSurfaces& s = plan.stopSurfaces[c];
    j["cells"].push_back({{"name", plan.cells[c]},
                          {"texels", plan.texels[c]},
                          {"neighbours", plan.neighbours[c]},
                          {"area_m2", s.area},
                          {"albedo_area_m2", {s.albedoArea.r, s.albedoArea.g, s.albedoArea.b}},
                          {"reflector_albedo_area_m2",
                           {s.reflectorAlbedoArea.r, s.reflectorAlbedoArea.g, s.reflectorAlbedoArea.b}}});
  }
  j["max_ambient_share"] = plan.maxAmbientShare;
  j["openings"] = nlohmann::json::array();
  for (const AmbientOpening& o : plan.openings) j["openings"].push_back({o.a, o.b, o.area});
  j["first_shot_groups"] = nlohmann::json::array();
  for (const FirstShotGroup& g : plan.firstShotGroups)
    j["first_shot_groups"].push_back({{"cell", g.cell}, {"patches", g.patches}});
  j["triangle_density"] = plan.triangleDensity;
  const fs::path part = dir / "plan.json.part";
  {
    std::ofstream f(part);
    f << j.dump(1) << "\n";
    if (!f) throw SystemError((dir / "plan.json").string() + ": cannot write");
  }
  fs::rename(part, dir / "plan.json");
}

CellJobPlan readCellJobPlan(const fs::path& dir) {
  const std::string file = (dir / "plan.json").string();
  std::ifstream f(file);
  if (!f)
    throw InputError(file,
                     "cannot read the cell job plan (made by `cpgi bake ... --method cells --plan DIR`)");
  CellJobPlan plan;
  try {
    const nlohmann::json j = nlohmann::json::parse(f);
    if (j.value("format", "") != "cpgi cell jobs") throw InputError(file, "not a cpgi cell job plan");
    plan.version = j.at("version").get<int>();
    if (plan.version != kCellJobPlanVersion)
      throw InputError(file, "cell job plan version " + std::to_string(plan.version) + ", this cpgi reads " +
                                 std::to_string(kCellJobPlanVersion));
    plan.bakeSettings = j.at("bake_settings");
    if (!plan.bakeSettings.is_object()) throw InputError(file, "its bake settings are not a JSON object");
    plan.workingDir = j.at("working_dir").get<std::string>();
    plan.firstShotSummed = j.at("first_shot_summed").get<bool>();
    plan.emitted = j.at("emitted_w").get<double>();
    plan.target = j.at("target_w").get<double>();
    plan.maxRounds = j.at("max_rounds").get<int>();
    plan.globalPatches = j.at("global_patches").get<size_t>();
    for (const nlohmann::json& c : j.at("cells")) {
      plan.cells.push_back(c.at("name").get<std::string>());
      plan.texels.push_back(c.at("texels").get<size_t>());
      plan.neighbours.push_back(c.at("neighbours").get<std::vector<int>>());
      for (int n : plan.neighbours.back())
        if (n < 0 || n >= int(j.at("cells").size())) throw InputError(file, "a neighbour that is no cell");
      CellStopSurfaces s;
      s.area = c.at("area_m2").get<double>();
      const auto rgb = [&](const char* key) {
        const std::vector<double> v = c.at(key).get<std::vector<double>>();
        if (v.size() != 3) throw InputError(file, std::string(key) + " is not three numbers");
        return glm::dvec3(v[0], v[1], v[2]);
      };
      s.albedoArea = rgb("albedo_area_m2");
      s.reflectorAlbedoArea = rgb("reflector_albedo_area_m2");
      plan.stopSurfaces.push_back(s);
    }
    plan.maxAmbientShare = j.at("max_ambient_share").get<double>();
    for (const nlohmann::json& o : j.at("openings")) {
      const AmbientOpening opening{o.at(0).get<size_t>(), o.at(1).get<size_t>(), o.at(2).get<double>()};
      if (opening.a >= plan.cells.size() || opening.b >= plan.cells.size())
        throw InputError(file, "an opening between cells that are not in the plan");
      plan.openings.push_back(opening);
    }
    for (const nlohmann::json& g : j.at("first_shot_groups")) {
      plan.firstShotGroups.push_back({g.at("cell").get<int>(), g.at("patches").get<std::vector<int>>()});
      if (plan.firstShotGroups.back().cell >= int(plan.cells.size()))
        throw InputError(file, "a first-shot group of a cell that is not in the plan");
    }
    plan.triangleDensity = j.at("triangle_density").get<std::vector<float>>();
    for (float d : plan.triangleDensity)
      if (!(d >= 0.0f && d < 1e6f)) throw InputError(file, "a triangle density that is not a density");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, std::string("damaged cell job plan: ") + e.what());
  }
  return plan;
}

CellJobPlan planCellJobs(const fs::path& dir, const Scene& scene, const CellGraph& graph,
                         const LightmapAtlas& global, const CellSolveParams& params,
                         nlohmann::json bakeSettings, Context& ctx) {
  requireSupported(params);
  checkCells(scene, graph, params, ctx);
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::vector<CellState> cells = buildMappedCellAtlases(scene, graph, params, cellOf, global, ctx);
  linkPortals(graph, cells);  // refuses a degenerate portal now rather than in a job

  CellJobPlan plan;
  plan.bakeSettings = std::move(bakeSettings);
  plan.workingDir = fs::current_path().string();
  plan.maxRounds = params.maxRounds;
  plan.globalPatches = global.patches.size();
  for (size_t c = 0; c < cells.size(); ++c) {
    plan.cells.push_back(graph.cells[c].name);
    plan.texels.push_back(cells[c].atlas.texelCount());
    plan.neighbours.push_back(neighboursOf(graph, int(c)));
    plan.stopSurfaces.push_back(cellStopSurfaces(cells[c]));
  }
  plan.maxAmbientShare = params.maxAmbientShare;
  plan.openings = cellOpenings(graph);
  plan.firstShotGroups = firstShotGroups(scene, firstShotReceivers(global, cellOf), cellOf);
  plan.triangleDensity = params.atlas.triangleDensity;
  fs::create_directories(dir);
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.is_directory() && e.path().filename().string().rfind("round-", 0) == 0) fs::remove_all(e.path());
  fs::remove(dir / "plan.json");
  fs::remove(dir / "first-shot.cell");
  fs::remove_all(dir / "first-shot");
  fs::create_directories(dir / "first-shot");
  writeCellJobPlan(dir, plan);  // last: its presence marks a complete plan
  return plan;
}

namespace {

// The emitter groups of this scene and these cells, which must be the plan's (same scene, same options).
std::vector<FirstShotGroup> checkedGroups(const fs::path& dir, const CellJobPlan& plan, const Scene& scene,
                                          const CellGraph& graph, const LightmapAtlas& global,
                                          LightmapAtlas* receivers) {
  if (graph.cells.size() != plan.cells.size())
    throw InputError((dir / "plan.json").string(), "the plan's cells are not the scene's");
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  LightmapAtlas black = firstShotReceivers(global, cellOf);
  std::vector<FirstShotGroup> groups = firstShotGroups(scene, black, cellOf);
  bool same = groups.size() == plan.firstShotGroups.size();
  for (size_t g = 0; same && g < groups.size(); ++g)
    same = groups[g].cell == plan.firstShotGroups[g].cell &&
           groups[g].patches == plan.firstShotGroups[g].patches;
  if (!same || global.patches.size() != plan.globalPatches)
    throw InputError(
        (dir / "plan.json").string(),
        "its first-shot groups are not this scene's (another scene or other options than the plan's?)");
  if (receivers) *receivers = std::move(black);
  return groups;
}

}  // namespace

void runFirstShotJobs(const fs::path& dir, const CellJobPlan& plan, const std::vector<int>& run,
                      const Scene& scene, const CellGraph& graph, const LightmapAtlas& global,
                      const CellSolveParams& params, ShotEngine& engine, Context& ctx) {
  requireSupported(params);
  LightmapAtlas receivers;
  const std::vector<FirstShotGroup> groups = checkedGroups(dir, plan, scene, graph, global, &receivers);
  for (int g : run)
    if (g < 0 || g >= int(groups.size()))
      throw InputError("first shot", "no emitter group " + std::to_string(g) + " (the plan has " +
                                         std::to_string(groups.size()) + ")");
  fs::create_directories(dir / "first-shot");
  for (int g : run) {
    auto t = ctx.time("cells: first shot");
    const FirstShotContribution c =
        shootFirstShotGroup(scene, receivers, groups, size_t(g), params.solver, engine, ctx);
    writeFirstShotGroup(firstShotGroupFile(dir, g), g, groups[size_t(g)].cell, global.texelCount(), c);
  }
}

CellJobPlan sumFirstShotJobs(const fs::path& dir, const CellJobPlan& given, const Scene& scene,
                             const CellGraph& graph, const LightmapAtlas& global,
                             const CellSolveParams& params, Context& ctx) {
  requireSupported(params);
  const std::vector<FirstShotGroup> groups = checkedGroups(dir, given, scene, graph, global, nullptr);
  std::vector<FirstShotContribution> parts;
  for (size_t g = 0; g < groups.size(); ++g)
    parts.push_back(
        readFirstShotGroup(firstShotGroupFile(dir, int(g)), int(g), groups[g].cell, global.texelCount()));
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::vector<CellState> cells = buildMappedCellAtlases(scene, graph, params, cellOf, global, ctx);
  const CellFirstShot first = landFirstShot(scene, global, sumFirstShot(parts, global.texelCount()), cells);
  SolveResult result = startBookkeeping(graph, cells, global);
  addFirstShotBookkeeping(first, result);

  CellJobPlan plan = given;
  plan.firstShotSummed = true;
  plan.emitted = result.energy.emitted;
  plan.target = params.solver.unshotFraction * plan.emitted;
  fs::remove_all(roundDir(dir, 0));
  fs::create_directories(roundDir(dir, 0));
  writeFirstShot(dir / "first-shot.cell",
                 FirstShotRecord{first.emitted, first.landed, first.absorbed, first.emission});
  for (size_t c = 0; c < cells.size(); ++c) {
    CellRoundSummary s;
    s.figures = waitingCellRound(c, cells[c]);
    writeCellState(cellStateFile(dir, 0, int(c)), 0, s.figures);
    s.figures.kept.clear(), s.figures.carried.clear();
    writeSummary(cellSummaryFile(dir, 0, int(c)), s);
  }
  writeCellJobPlan(dir, plan);  // last: the plan now says the first shot is summed
  return plan;
}

namespace {

// What a round of some cells is solved on: the cells kept, their atlases and portal links. A one-shot
// job builds it for its own cells and the two rings around them; a server for the whole graph, once.
struct JobCells {
  SubGraph sub;
  std::vector<CellState> cells;  ///< sub order
  std::vector<PortalLink> links;
};

JobCells buildJobCells(const Scene& scene, const CellGraph& graph, const std::vector<int>& keep,
                       const CellSolveParams& params, Context& ctx) {
  JobCells j;
  j.sub = subGraph(graph, keep);
  {
    auto t = ctx.time("cells: atlases");
    std::vector<int32_t> localIndex;
    j.cells = buildCellAtlases(scene, j.sub.graph, params, localIndex, ctx);
  }
  j.links = linkPortals(j.sub.graph, j.cells);
  return j;
}

// The cells run, their neighbours (whose atlases the portal links need) and the neighbours' neighbours:
// a cell's atlas holds a patch for each of its portals, so a neighbour's is the whole graph's only when
// every cell across its portals is there too.
std::vector<int> cellsAround(const CellJobPlan& plan, const std::vector<int>& run) {
  std::vector<int> keep = run;
  for (int ring = 0; ring < 2; ++ring) {
    const std::vector<int> inner = keep;
    for (int c : inner)
      keep.insert(keep.end(), plan.neighbours[size_t(c)].begin(), plan.neighbours[size_t(c)].end());
    std::sort(keep.begin(), keep.end());
    keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  }
  return keep;
}

// How round `round` solves: towards which unshot power, with which budget.
struct RoundSettings {
  double target = 0.0;
  SolverParams settings;
  SolveControls controls;
  ShotShape shape;
};

// The stop replayed from the summaries of rounds 1..through, as solveCells's loop left it before asking
// about round through + 1. Finished rounds do not change (a rerun writes the same figures), so a server keeps
// it from job to job and reads only the rounds it has not replayed, for as long as the plan starts the same.
struct StopReplay {
  double emitted = 0.0, target = 0.0;  ///< the plan's, at the start of the replay
  RoundStop stop;
  double before = 0.0;  ///< W unshot after round `through` (the emitted power for 0)
  int through = 0;
};

StopReplay startReplay(const CellJobPlan& plan) {
  return {plan.emitted, plan.target, planStop(plan), plan.emitted, 0};
}

// Refuses a round the plan cannot run yet or needs no more, then replays the rounds before it from their
// summaries, on from `replay` when it is of this plan and not past them (else from the start; `replay` is
// left at round − 1): the unshot power and the stop's target now.
RoundSettings roundSettings(const fs::path& dir, const CellJobPlan& plan, int round, const CellGraph& graph,
                            const CellSolveParams& params, std::optional<StopReplay>& replay) {
  requireSupported(params);
  if (graph.cells.size() != plan.cells.size())
    throw InputError((dir / "plan.json").string(), "the plan has " + std::to_string(plan.cells.size()) +
                                                       " cells, the scene's graph " +
                                                       std::to_string(graph.cells.size()));
  if (round < 1) throw InputError("round", "cell job rounds count from 1");
  requireFirstShotSummed(dir, plan);
  const bool reusable = replay && replay->emitted == plan.emitted && replay->target == plan.target &&
                        replay->through <= round - 1;
  StopReplay r = reusable ? *replay : startReplay(plan);  // replay is only set once the rounds were read
  bool needed = true;
  for (; r.through < round - 1 && needed; ++r.through) {
    needed = roundNeeded(plan, r.through + 1, r.before, r.stop);
    if (needed) r.before = addRoundToStop(dir, plan, r.through + 1, r.stop);
  }
  if (needed) replay = r;
  RoundStop stop = r.stop;  // asking about `round` may lower the target: the replay stays before it
  if (!needed || !roundNeeded(plan, round, r.before, stop))
    throw InputError(roundDir(dir, round).string(), "the solve needs no round " + std::to_string(round) +
                                                        " (converged, or past the maximum rounds): gather");
  RoundSettings s;
  s.target = stop.target();
  s.controls.readTransfer = true;
  s.settings = roundBudget(params, s.target, r.before, plan.emitted, s.controls, s.shape, plan.globalPatches);
  return s;
}

// Round `round` of the cells `run` (graph indices, each kept in `j`): gathers, solves or waits, and
// writes each cell's files, its summary last.
void solveJobCells(const fs::path& dir, const CellJobPlan& plan, int round, const std::vector<int>& run,
                   JobCells& j, const RoundSettings& r, const PortalTransfer& transfer, ShotEngine& engine,
                   Context& ctx) {
  fs::create_directories(roundDir(dir, round));
  for (int c : run) {
    const auto start = std::chrono::steady_clock::now();
    const size_t k = size_t(j.sub.subOf[size_t(c)]);
    CellState& s = j.cells[k];
    if (s.atlas.texelCount() != plan.texels[size_t(c)])
      throw InputError((dir / "plan.json").string(),
                       "cell " + plan.cells[size_t(c)] + " has " + std::to_string(s.atlas.texelCount()) +
                           " texels here, " + std::to_string(plan.texels[size_t(c)]) + " in the plan");
    // Everything of the state a round reads is set here from the files (pending light, carried part,
    // moments, bins, and for a solve the emission from the pending light), as solveCells sets it each
    // round: a served cell keeps nothing of an earlier job but its atlas.
    gatherFromFiles(dir, plan, round, c, s);
    CellRound cr;
    if (cellSolvesRound(s, r.target)) {
      for (size_t i = 0; i < s.pending.size(); ++i) s.atlas.emission[i] = s.pending[i];
      auto t = ctx.time("cells: solve");
      const SolveResult solved = transfer.solve(k, s, r.settings, r.controls, r.shape, engine, ctx);
      cr = cellRoundOf(k, s, solved, j.links, j.cells, transfer.binRays());
    } else {
      cr = waitingCellRound(k, s);
    }
    toGraphIndices(cr, j.sub);
    writeCellState(cellStateFile(dir, round, c), round, cr);
    CellRoundSummary summary;
    summary.round = round;
    for (int n : plan.neighbours[size_t(c)])
      summary.portalBytes += writePortalLight(portalLightFile(dir, round, c, n), round, cr, n);
    summary.figures = std::move(cr);
    summary.figures.kept.clear(), summary.figures.carried.clear(), summary.figures.radiosity.clear();
    for (PortalSend& send : summary.figures.sends) send.exitance.clear();
    summary.jobSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeSummary(cellSummaryFile(dir, round, c), summary);  // last: the job for this cell is done
  }
}

}  // namespace

void runCellJobs(const fs::path& dir, const CellJobPlan& plan, int round, const std::vector<int>& run,
                 const Scene& scene, const CellGraph& graph, const CellSolveParams& params,
                 ShotEngine& engine, Context& ctx) {
  std::optional<StopReplay> replay;
  const RoundSettings settings = roundSettings(dir, plan, round, graph, params, replay);
  JobCells cells = buildJobCells(scene, graph, cellsAround(plan, run), params, ctx);
  const std::unique_ptr<PortalTransfer> transfer = makePortalTransfer(params);
  solveJobCells(dir, plan, round, run, cells, settings, *transfer, engine, ctx);
}

struct CellJobServer::Kept {
  const CellGraph& graph;
  CellSolveParams params;
  JobCells cells;
  std::unique_ptr<PortalTransfer> transfer;
  std::optional<StopReplay> replay;
};

CellJobServer::CellJobServer(const Scene& scene, const CellGraph& graph, const CellSolveParams& params,
                             Context& ctx) {
  requireSupported(params);
  std::vector<int> all(graph.cells.size());
  for (size_t c = 0; c < all.size(); ++c) all[c] = int(c);
  kept_.reset(
      new Kept{graph, params, buildJobCells(scene, graph, all, params, ctx), makePortalTransfer(params), {}});
}

CellJobServer::~CellJobServer() = default;

void CellJobServer::runRound(const fs::path& dir, const CellJobPlan& plan, int round,
                             const std::vector<int>& run, ShotEngine& engine, Context& ctx) {
  const RoundSettings settings = roundSettings(dir, plan, round, kept_->graph, kept_->params, kept_->replay);
  solveJobCells(dir, plan, round, run, kept_->cells, settings, *kept_->transfer, engine, ctx);
}

namespace {

// Round `round`'s figures from its summaries, fed to `stop`; `unshot` becomes the power unshot after it.
CellJobRoundStatus finishedRound(const fs::path& dir, const CellJobPlan& plan, int round, RoundStop& stop,
                                 double& unshot) {
  std::vector<CellRoundSummary> summaries;
  CellJobRoundStatus r;
  r.target = stop.target();
  unshot = addRoundToStop(dir, plan, round, stop, &summaries);
  r.round = round;
  r.unshot = unshot;
  for (const CellRoundSummary& s : summaries) {
    r.solved += s.figures.solved;
    r.shots += s.figures.shots;
    r.jobSeconds += s.jobSeconds;
    r.maxJobSeconds = std::max(r.maxJobSeconds, s.jobSeconds);
    r.portalBytes += s.portalBytes;
  }
  return r;
}

}  // namespace

CellJobStatus cellJobStatus(const fs::path& dir, const CellJobPlan& plan, CellJobStatusKept* kept) {
  CellJobStatus status;
  for (size_t g = 0; g < plan.firstShotGroups.size(); ++g)
    if (!fs::exists(firstShotGroupFile(dir, int(g)))) status.firstShotMissing.push_back(int(g));
  status.firstShotSummed = plan.firstShotSummed;
  if (!plan.firstShotSummed) return status;
  const bool reusable = kept && kept->stop && kept->emitted == plan.emitted && kept->target == plan.target;
  double unshot = reusable ? kept->unshot : plan.emitted;
  RoundStop stop = reusable ? *kept->stop : planStop(plan);
  if (reusable) status.rounds = kept->rounds;
  for (int round = int(status.rounds.size()) + 1;; ++round) {
    if (!roundNeeded(plan, round, unshot, stop)) {
      status.nextRound = 0;
      return status;
    }
    status.nextRound = round;
    for (size_t c = 0; c < plan.cells.size(); ++c)
      if (!fs::exists(cellSummaryFile(dir, round, int(c)))) status.missing.push_back(int(c));
    if (!status.missing.empty()) return status;
    status.rounds.push_back(finishedRound(dir, plan, round, stop, unshot));
    if (kept) *kept = CellJobStatusKept{plan.emitted, plan.target, status.rounds, stop, unshot};
  }
}

namespace {

// Every cell's state of round `round`, read side by side (the files are independent; reading and checking
// them is most of a gather's work).
std::vector<CellRound> readRoundStates(const fs::path& dir, int round, size_t cells) {
  std::vector<CellRound> states(cells);
  tbb::parallel_for(size_t(0), cells, [&](size_t c) {
    states[c] = readCellState(cellStateFile(dir, round, int(c)), round, int(c));
  });
  return states;
}

}  // namespace

SolveResult gatherCellJobs(const fs::path& dir, const CellJobPlan& plan, const Scene& scene,
                           const CellGraph& graph, const LightmapAtlas& global, const CellSolveParams& params,
                           Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  requireSupported(params);
  requireFirstShotSummed(dir, plan);
  if (graph.cells.size() != plan.cells.size())
    throw InputError((dir / "plan.json").string(), "the plan's cells are not the scene's");
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::vector<CellState> cells = buildMappedCellAtlases(scene, graph, params, cellOf, global, ctx);
  auto t = ctx.time("gather: rounds");
  // The pending light of the first round, from round 0: the first shot's landing (each cell's emitted power).
  tbb::parallel_for(size_t(0), cells.size(),
                    [&](size_t c) { gatherFromFiles(dir, plan, 1, int(c), cells[c]); });
  SolveResult result = startBookkeeping(graph, cells, global);
  const FirstShotRecord shot = readFirstShot(dir / "first-shot.cell");
  if (shot.absorbed.size() != cells.size() || shot.emission.size() != global.texelCount())
    throw InputError((dir / "first-shot.cell").string(), "made for another scene or atlas than the plan's");
  addFirstShotBookkeeping(CellFirstShot{shot.absorbed, shot.landed, shot.emitted, shot.emission}, result);
  double unshot = plan.emitted;
  int& rounds = result.perCell->rounds;
  RoundStop stop = planStop(plan);
  while (roundNeeded(plan, rounds + 1, unshot, stop)) {
    const int round = ++rounds;
    std::vector<CellRoundSummary> summaries;
    unshot = addRoundToStop(dir, plan, round, stop, &summaries);
    std::vector<CellRound> states = readRoundStates(dir, round, cells.size());
    for (size_t c = 0; c < cells.size(); ++c) {  // in cell order, as solveCells adds them
      CellRound& r = summaries[c].figures;       // the figures, with the state's radiosity
      r.radiosity = std::move(states[c].radiosity);
      addCellRound(r, cells[c], graph, result);
    }
  }
  // Only the light left pending after the last round counts (finishBookkeeping's unshot, the ambient term):
  // a round's states hold its radiosity, so the rounds before need no pending light of their own.
  if (rounds > 0)
    tbb::parallel_for(size_t(0), cells.size(),
                      [&](size_t c) { gatherFromFiles(dir, plan, rounds + 1, int(c), cells[c]); });
  result.stopChecks = stop.checks();
  finishBookkeeping(cells, global, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace cpgi
