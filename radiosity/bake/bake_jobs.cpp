#include "radiosity/bake/bake_jobs.h"

#include <optional>
#include <utility>

#include "core/error.h"
#include "radiosity/bake/bake_steps.h"

namespace cpgi {

CellJobPlan planBakeJobs(const std::filesystem::path& dir, const BakeSettings& settings, Context& ctx) {
  const BakeSettings s = bake_steps::resolved(settings);
  if (s.cells.method != BakeMethod::Cells) throw InputError("--plan", "needs --method cells");
  if (!s.cells.onlyCells.empty() || !s.cells.around.empty())
    throw InputError("--plan", "cell jobs bake the whole cell graph: leave out --only-cells and --around");
  if (s.solver.solveDensity > 0.0f)
    throw InputError("--solve-density", "cell jobs and on-demand bakes solve in one level: leave it out");
  const BakeScene loaded = loadBakeScene(settings, ctx);
  bake_steps::BakeInput in;
  in.scene = &loaded.loaded.scene;
  in.cells = &loaded.graph;
  BakeEngines engines(s.solver.backend, s.solver.indirect, nullptr, ctx);  // the pilot's, with --density auto
  bake_steps::buildBakeAtlas(s, in, s.atlas.densityAuto ? &engines.engines().lamps : nullptr, ctx);
  bake_steps::requireSolveMemory(s, in.atlas);
  bake_steps::requireConvergence(s, *in.scene, in.atlas);
  return planCellJobs(dir, *in.scene, *in.cells, in.atlas, bake_steps::cellSolveParams(s, in),
                      bakeSettingsJson(settings), ctx);
}

struct BakeJobs::Loaded {
  BakeSettings settings;  ///< as the plan keeps them
  BakeScene scene;
  bake_steps::BakeInput in;
  CellSolveParams params;
  bool atlasBuilt = false;
};

BakeJobs::BakeJobs(std::filesystem::path dir, Context& ctx) : dir_(std::move(dir)), loaded_(new Loaded) {
  Loaded& l = *loaded_;
  const CellJobPlan plan = readCellJobPlan(dir_);
  try {
    l.settings = bakeSettingsFromJson(plan.bakeSettings);
  } catch (const InputError& e) {
    throw InputError((dir_ / "plan.json").string(), e.problem());
  }
  l.scene = loadBakeScene(l.settings, ctx);
  l.in.scene = &l.scene.loaded.scene;
  l.in.cells = &l.scene.graph;
  // With --density auto, a job's texel densities are those its plan recorded: every job lays its atlases
  // out alike, and a pilot of its own could choose otherwise (another machine's GPU).
  if (l.settings.atlas.densityAuto) {
    l.in.triangleDensity = plan.triangleDensity;
    if (l.in.triangleDensity.size() != l.in.scene->triangles.size())
      throw InputError((dir_ / "plan.json").string(), "holds no texel density per triangle of " +
                                                          l.settings.input.scene + "; make the plan again");
  }
  l.params = bake_steps::cellSolveParams(bake_steps::resolved(l.settings), l.in);
}

BakeJobs::~BakeJobs() = default;

const BakeSettings& BakeJobs::settings() const {
  return loaded_->settings;
}
const Scene& BakeJobs::scene() const {
  return *loaded_->in.scene;
}
const CellGraph& BakeJobs::graph() const {
  return *loaded_->in.cells;
}
const CellSolveParams& BakeJobs::params() const {
  return loaded_->params;
}

const LightmapAtlas& BakeJobs::globalAtlas(Context& ctx) {
  Loaded& l = *loaded_;
  if (!l.atlasBuilt) bake_steps::buildBakeAtlas(bake_steps::resolved(l.settings), l.in, nullptr, ctx);
  l.atlasBuilt = true;
  return l.in.atlas;
}

void BakeJobs::firstShot(std::vector<int> groups, ShotEngine& engine, Context& ctx) {
  const CellJobPlan plan = readCellJobPlan(dir_);
  if (groups.empty())
    for (int g = 0; g < int(plan.firstShotGroups.size()); ++g) groups.push_back(g);
  runFirstShotJobs(dir_, plan, groups, scene(), graph(), globalAtlas(ctx), params(), engine, ctx);
}

void BakeJobs::firstShotSum(Context& ctx) {
  sumFirstShotJobs(dir_, readCellJobPlan(dir_), scene(), graph(), globalAtlas(ctx), params(), ctx);
}

void BakeJobs::round(int round, std::vector<int> cells, ShotEngine& engine, Context& ctx) {
  if (cells.empty())
    for (int c = 0; c < int(graph().cells.size()); ++c) cells.push_back(c);
  runCellJobs(dir_, readCellJobPlan(dir_), round, cells, scene(), graph(), params(), engine, ctx);
}

BakeResult BakeJobs::gather(const BakeRun& run, Context& ctx) {
  Loaded& l = *loaded_;
  const BakeSettings s = bake_steps::resolved(l.settings);
  const BakeResult r = bake_steps::bakeLoaded(s, l.in, run, ctx, &dir_);
  l.atlasBuilt = false;  // bakeLoaded's result took the atlas
  return r;
}

}  // namespace cpgi
