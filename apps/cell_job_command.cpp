// `cpgi cell-job PLAN (--round R [--cell NAME]... | --status [--json] | --gather) [-q]`: the cell jobs of a
// plan made by `cpgi bake SCENE -o DIR --method cells --plan PLAN` (radiosity/cells/cell_jobs.h,
// docs/cell-jobs.md). A round or the gather runs the bake command again on the arguments kept in
// PLAN/plan.json, so a job takes exactly the plan's scene and options; --status reads only the plan's
// small files and says which round comes next (what a driver such as cpgi-dask waits on).
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/error.h"
#include "radiosity/cells/cell_jobs.h"

namespace cpgi::cli {
namespace {

struct CellJobOptions {
  std::string plan;
  int round = 0;
  std::vector<std::string> cells;
  bool status = false, json = false, gather = false, quiet = false;
};

int printStatus(const CellJobOptions& o, const CellJobPlan& plan) {
  const CellJobStatus s = cellJobStatus(o.plan, plan);
  if (o.json) {
    nlohmann::json rounds = nlohmann::json::array(), missing = nlohmann::json::array();
    for (const CellJobRoundStatus& r : s.rounds)
      rounds.push_back({{"round", r.round},
                        {"unshot_w", r.unshot},
                        {"solved_cells", r.solved},
                        {"shots", r.shots},
                        {"job_seconds", r.jobSeconds},
                        {"max_job_seconds", r.maxJobSeconds},
                        {"portal_bytes", r.portalBytes}});
    for (int c : s.missing) missing.push_back(plan.cells[size_t(c)]);
    std::cout << nlohmann::json{{"cells", plan.cells.size()}, {"emitted_w", plan.emitted},
                                {"target_w", plan.target},    {"rounds", rounds},
                                {"next_round", s.nextRound},  {"missing", missing}}
                     .dump()
              << "\n";
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

// The bake command on the plan's arguments plus the job's own.
int runThroughBake(const CellJobOptions& o, const CellJobPlan& plan) {
  std::vector<std::string> args = {"bake"};
  args.insert(args.end(), plan.bakeArgs.begin(), plan.bakeArgs.end());
  args.insert(args.end(), {"--plan", o.plan});
  if (o.gather) {
    args.push_back("--gather");
  } else {
    args.insert(args.end(), {"--job-round", std::to_string(o.round)});
    std::string list;
    for (const std::string& c : o.cells) list += (list.empty() ? "" : ",") + c;
    if (!list.empty()) args.insert(args.end(), {"--job-cells", list});
  }
  if (o.quiet) args.push_back("-q");
  CLI::App app;
  CommandFn selected;
  addBakeCommand(app, selected);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw InputError((std::filesystem::path(o.plan) / "plan.json").string(),
                     std::string("its bake arguments do not parse: ") + e.what());
  }
  return selected ? selected() : 1;
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
  auto* status = sub->add_flag("--status", o->status, "Print the finished rounds and the next one");
  sub->add_flag("--json", o->json, "With --status: as one JSON line")->needs(status);
  auto* gather =
      sub->add_flag("--gather", o->gather,
                    "Assemble the lightmap and the bake's other files (its -o folder) from the rounds");
  round->excludes(status)->excludes(gather);
  status->excludes(gather);
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary");
  sub->callback([&selected, o] {
    selected = [o] {
      if (!o->status && !o->gather && o->round == 0)
        throw InputError("cell-job", "give --round R, --status or --gather");
      o->plan = std::filesystem::absolute(o->plan).string();
      const CellJobPlan plan = readCellJobPlan(o->plan);
      // The bake's relative paths (scene, -o) are the plan maker's; a job may start anywhere.
      std::error_code ec;
      if (!o->status && std::filesystem::is_directory(plan.workingDir, ec))
        std::filesystem::current_path(plan.workingDir);
      return o->status ? printStatus(*o, plan) : runThroughBake(*o, plan);
    };
  });
}

}  // namespace cpgi::cli
