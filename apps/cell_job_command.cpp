// `cpgi cell-job PLAN (--first-shot [--group G]... | --first-shot-sum | --round R [--cell NAME]... |
// --serve | --status [--json] | --gather) [-q]`: the cell jobs of a plan made by `cpgi bake SCENE -o DIR
// --method cells --plan PLAN` (radiosity/cells/cell_jobs.h, docs/cell-jobs.md). A job or the gather bakes
// with the settings kept in PLAN/plan.json (radiosity/bake/bake_jobs.h), so a job takes exactly the plan's
// scene and options; --status reads only the plan's small files and says which step comes next (what a driver
// such as cpgi-dask waits on); --serve runs round jobs read from stdin in one process
// (apps/cell_job_serve.h), and answers the same status there.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/cell_job_serve.h"
#include "apps/cell_job_status.h"
#include "apps/commands.h"
#include "core/error.h"
#include "core/progress.h"
#include "radiosity/bake/bake_jobs.h"
#include "radiosity/cells/cell_jobs.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/gpu/gl_shot_engine.h"

namespace cpgi::cli {
namespace {

struct CellJobOptions {
  std::string plan;
  int round = 0;
  std::vector<std::string> cells;
  std::vector<int> groups;
  bool firstShot = false, firstShotSum = false, serve = false;
  bool status = false, json = false, gather = false, quiet = false;
};

int printStatus(const CellJobOptions& o, const CellJobPlan& plan) {
  const CellJobStatus s = cellJobStatus(o.plan, plan);
  if (o.json) {
    std::cout << cellJobStatusJson(plan, s).dump() << "\n";
    return 0;
  }
  if (!s.firstShotSummed) {
    if (s.firstShotMissing.empty())
      std::cout << "next: the first shot's sum (cpgi cell-job " << o.plan << " --first-shot-sum)\n";
    else
      std::cout << "next: the first shot of " << s.firstShotMissing.size() << " of "
                << plan.firstShotGroups.size() << " emitter groups (cpgi cell-job " << o.plan
                << " --first-shot [--group G,...])\n";
    return 0;
  }
  for (const CellJobRoundStatus& r : s.rounds)
    std::cout << "round " << r.round << ": " << r.solved << " cells solved, " << r.shots << " shots, unshot "
              << r.unshot / plan.emitted * 100.0 << " %\n";
  if (s.nextRound == 0)
    std::cout << "done: cpgi cell-job " << o.plan << " --gather\n";
  else
    std::cout << "next: round " << s.nextRound << ", " << s.missing.size() << " cells to run\n";
  return 0;
}

// A job of the plan, on the plan's settings (radiosity/bake/bake_jobs.h).
int runJob(const CellJobOptions& o) {
  Context ctx;
  ctx.setProgress(stderrProgress(o.quiet));
  BakeJobs jobs(o.plan, ctx);
  if (o.gather) {
    const BakeResult r = jobs.gather(BakeRun{}, ctx);
    if (!o.quiet)
      std::cout << jobs.settings().output.folder << ": " << r.atlas.validTexels() << " texels, " << r.shots
                << " shots, unshot " << r.unshotFraction * 100.0 << " %, " << r.seconds << " s"
                << (r.partial ? " (partial: stopped at the time limit)" : "") << "\n";
    if (!o.quiet)
      for (const std::string& w : ctx.warnings()) std::cerr << "warning: " << w << "\n";
  } else if (o.firstShotSum) {
    jobs.firstShotSum(ctx);
    if (!o.quiet)
      std::cout << o.plan << ": first shot summed; next: cpgi cell-job " << o.plan << " --round 1\n";
  } else {
    const EglContext gl(ctx);
    if (o.serve) return serveCellJobs(o.plan, jobs, gl, ctx, std::cin, std::cout);
    GlShotEngine engine(gl);
    if (o.firstShot) {
      const size_t groups =
          o.groups.empty() ? readCellJobPlan(o.plan).firstShotGroups.size() : o.groups.size();
      jobs.firstShot(o.groups, engine, ctx);
      if (!o.quiet) std::cout << o.plan << ": first shot of " << groups << " emitter groups done\n";
    } else {
      std::string list;
      for (const std::string& c : o.cells) list += (list.empty() ? "" : ",") + c;
      std::vector<int> cells = list.empty() ? std::vector<int>{} : cellsByName(jobs.graph(), list, "--cell");
      jobs.round(o.round, cells, engine, ctx);
      if (!o.quiet)
        std::cout << o.plan << ": round " << o.round << " of "
                  << (cells.empty() ? jobs.graph().cells.size() : cells.size()) << " cells done\n";
    }
  }
  return 0;
}

}  // namespace

void addCellJobCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<CellJobOptions>();
  CLI::App* sub = app.add_subcommand(
      "cell-job",
      "Run cell jobs of a plan made by `cpgi bake --method cells --plan PLAN` (docs/cell-jobs.md)");
  sub->add_option("plan", o->plan, "The plan folder")->required();
  auto* round =
      sub->add_option("--round", o->round, "Solve this round (1, 2, ...) of the cells given, or of all")
          ->check(CLI::Range(1, 1000000));
  sub->add_option("--cell", o->cells,
                  "A cell of the job (repeatable or comma-separated); default: every cell")
      ->delimiter(',')
      ->needs(round);
  auto* firstShot =
      sub->add_flag("--first-shot", o->firstShot,
                    "Shoot the lamps' emitter groups given over the whole scene (the plan's first shot)");
  sub->add_option("--group", o->groups,
                  "With --first-shot: an emitter group (repeatable or comma-separated); default: every group")
      ->delimiter(',')
      ->check(CLI::Range(0, 100000000))
      ->needs(firstShot);
  auto* firstShotSum = sub->add_flag("--first-shot-sum", o->firstShotSum,
                                     "Add the emitter groups' shots in order and start round 0 from them");
  auto* serve = sub->add_flag(
      "--serve", o->serve,
      "Run jobs read from stdin, one JSON request a line ({\"round\": R, \"cells\": [...]}, "
      "{\"first_shot\": [G, ...]}, {\"status\": true} for --status --json's object, {\"gather\": true}), "
      "answering one line each on stdout, keeping the scene, EGL context and atlases between them");
  auto* status = sub->add_flag("--status", o->status, "Print the finished rounds and the next one");
  sub->add_flag("--json", o->json, "With --status: as one JSON line")->needs(status);
  auto* gather =
      sub->add_flag("--gather", o->gather,
                    "Assemble the lightmap and the bake's other files (its -o folder) from the rounds");
  round->excludes(status)->excludes(gather)->excludes(firstShot)->excludes(firstShotSum);
  status->excludes(gather)->excludes(firstShot)->excludes(firstShotSum);
  gather->excludes(firstShot)->excludes(firstShotSum);
  firstShot->excludes(firstShotSum);
  serve->excludes(round)->excludes(status)->excludes(gather)->excludes(firstShot)->excludes(firstShotSum);
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary");
  sub->callback([&selected, o] {
    selected = [o] {
      if (!o->status && !o->gather && !o->firstShot && !o->firstShotSum && !o->serve && o->round == 0)
        throw InputError("cell-job",
                         "give --first-shot, --first-shot-sum, --round R, --serve, --status or --gather");
      o->plan = std::filesystem::absolute(o->plan).string();
      const CellJobPlan plan = readCellJobPlan(o->plan);
      // The bake's relative paths (scene, -o) are the plan maker's; a job may start anywhere.
      std::error_code ec;
      if (!o->status && std::filesystem::is_directory(plan.workingDir, ec))
        std::filesystem::current_path(plan.workingDir);
      return o->status ? printStatus(*o, plan) : runJob(*o);
    };
  });
}

}  // namespace cpgi::cli
