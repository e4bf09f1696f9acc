// The cells solve as jobs that share nothing but files (issue 16; docs/cell-jobs.md): a plan, then for
// each round one job per cell or group of cells, then a gather. Any engine that can run a command on a
// machine that sees the plan folder can drive them (cpgi-dask, a Slurm job array); a job reads only
// files of the round before and writes only its own, each atomically, so rerunning a job (a lost
// worker) rewrites the same bytes.
//
//   planCellJobs     the set-up of solveCells (CPU): writes plan.json, with the first shot's emitter
//                    groups (first_shot_groups.h).
//   runFirstShotJobs some emitter groups shot over the whole scene (GPU), one file per group.
//   sumFirstShotJobs the groups' files added in their fixed order and landed in the cells (CPU): writes
//                    first-shot.cell and round 0 (every cell's pending light), then marks the plan summed.
//   runCellJobs      round R of some cells: each gathers its pending light from round R − 1 (its own
//                    state and the portal light its neighbours sent it), solves it on the GPU when it holds
//                    enough (cell_round.h, as solveCells does), and writes its state, the portal light it
//                    sends each neighbour and its summary (last: its presence marks the job done).
//   CellJobServer    runCellJobs for one job after another in one process, the cells' atlases, the GPU
//                    programs and the shot engine kept between them (`cpgi cell-job PLAN --serve`).
//   cellJobStatus    which round comes next, from plan.json and the summaries alone (cheap).
//   gatherCellJobs   every round applied in order, as solveCells applies them: the same SolveResult.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/cells/first_shot_groups.h"
#include "radiosity/cells/round_stop.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/shot_engine.h"

namespace cpgi {

/// 3: the stop per cell's figures (round_stop.h); 4: the texel densities of bake --density auto; 5: the
/// bake's settings as JSON instead of its command line
inline constexpr int kCellJobPlanVersion = 5;

/// plan.json: what every job and the gather need besides the scene and the bake's options.
struct CellJobPlan {
  int version = kCellJobPlanVersion;
  /// The bake's settings (radiosity/bake/bake_settings.h, bakeSettingsJson): every job and the gather
  /// bake with them. Kept as JSON here: the cells know nothing of a bake above them.
  nlohmann::json bakeSettings;
  std::string workingDir;             ///< where the plan was made: the bake's relative paths start there
  bool firstShotSummed = false;       ///< the first shot's groups are summed: round 0 is there
  double emitted = 0.0;               ///< W (R + G + B) after the first shot's bookkeeping (once summed)
  double target = 0.0;                ///< unshot power at which the rounds stop (W; once summed)
  int maxRounds = 0;
  size_t globalPatches = 0;                  ///< patches of the whole scene's atlas (for roundBudget)
  std::vector<std::string> cells;            ///< graph order
  std::vector<size_t> texels;                ///< per cell, valid texels of its atlas (a job checks its own)
  std::vector<std::vector<int>> neighbours;  ///< per cell, the cells across its portals (ascending)
  std::vector<FirstShotGroup> firstShotGroups;  ///< the first shot's emitter groups, in summing order
  /// The stop per cell (radiosity/cells/round_stop.h): its share (0: the target alone), each cell's
  /// surfaces and the openings between cells, so that the driver decides it from the summaries alone.
  double maxAmbientShare = 0.0;
  std::vector<CellStopSurfaces> stopSurfaces;  ///< per cell
  std::vector<AmbientOpening> openings;
  /// bake --density auto: per scene triangle the texels per metre its pilot chose (AtlasParams::
  /// triangleDensity), which every job's atlases follow rather than shooting a pilot of their own. Empty:
  /// the bake's fixed density.
  std::vector<float> triangleDensity;
};

void writeCellJobPlan(const std::filesystem::path& dir, const CellJobPlan& plan);
/// Throws InputError naming dir/plan.json when it is missing, unreadable or of another version.
CellJobPlan readCellJobPlan(const std::filesystem::path& dir);

/// Files of the plan folder.
std::filesystem::path roundDir(const std::filesystem::path& dir, int round);
std::filesystem::path cellStateFile(const std::filesystem::path& dir, int round, int cell);
std::filesystem::path cellSummaryFile(const std::filesystem::path& dir, int round, int cell);
std::filesystem::path portalLightFile(const std::filesystem::path& dir, int round, int from, int to);
std::filesystem::path firstShotGroupFile(const std::filesystem::path& dir, int group);

/// Writes the plan into `dir` (created; an earlier plan's first shot and rounds there are removed).
/// On-demand cells are refused (InputError).
CellJobPlan planCellJobs(const std::filesystem::path& dir, const Scene& scene, const CellGraph& graph,
                         const LightmapAtlas& global, const CellSolveParams& params,
                         nlohmann::json bakeSettings, Context& ctx);

/// The first shot of emitter groups `groups` (indices into plan.firstShotGroups), one after the other on
/// `engine`; each writes its group's file. InputError when the scene's groups are not the plan's.
void runFirstShotJobs(const std::filesystem::path& dir, const CellJobPlan& plan,
                      const std::vector<int>& groups, const Scene& scene, const CellGraph& graph,
                      const LightmapAtlas& global, const CellSolveParams& params, ShotEngine& engine,
                      Context& ctx);

/// Adds every group's file in the plan's order, lands the sum in the cells, writes first-shot.cell and
/// round 0, then plan.json with the emitted and target power (InputError when a group's file is missing).
CellJobPlan sumFirstShotJobs(const std::filesystem::path& dir, const CellJobPlan& plan, const Scene& scene,
                             const CellGraph& graph, const LightmapAtlas& global,
                             const CellSolveParams& params, Context& ctx);

/// Round `round` (>= 1) of `cells` (graph indices): needs round − 1 complete for them and their
/// neighbours, and the round to be one the solve still needs (InputError otherwise).
void runCellJobs(const std::filesystem::path& dir, const CellJobPlan& plan, int round,
                 const std::vector<int>& cells, const Scene& scene, const CellGraph& graph,
                 const CellSolveParams& params, ShotEngine& engine, Context& ctx);

/// Round jobs served by one long-lived process (`cpgi cell-job PLAN --serve`, docs/cell-jobs.md): the whole
/// graph's cell atlases and portal links are built once, and the portal model are kept between jobs (the
/// caller keeps its shot engine, with its compiled programs), so that a job costs its cells' work and files
/// alone. A served round of some cells writes the bytes runCellJobs writes (the job seconds aside): a cell's
/// atlas and links are the whole graph's in both, and each job starts from its cells' atlases as built.
/// `graph` must outlive it.
class CellJobServer {
 public:
  CellJobServer(const Scene& scene, const CellGraph& graph, const CellSolveParams& params, Context& ctx);
  ~CellJobServer();
  CellJobServer(const CellJobServer&) = delete;
  CellJobServer& operator=(const CellJobServer&) = delete;

  /// As runCellJobs, on the kept cells.
  void runRound(const std::filesystem::path& dir, const CellJobPlan& plan, int round,
                const std::vector<int>& cells, ShotEngine& engine, Context& ctx);

 private:
  struct Kept;
  std::unique_ptr<Kept> kept_;
};

/// One finished round in figures.
struct CellJobRoundStatus {
  int round = 0;
  double unshot = 0.0;  ///< W after it
  double target = 0.0;  ///< the unshot power (W) it was run towards (lowered by the stop per cell)
  int solved = 0, shots = 0;
  double jobSeconds = 0.0, maxJobSeconds = 0.0;  ///< Σ and max over cells
  uint64_t portalBytes = 0;
};
struct CellJobStatus {
  std::vector<int> firstShotMissing;       ///< emitter groups whose first-shot file is not there yet
  bool firstShotSummed = false;            ///< false: the first shot's groups, then its sum, come first
  std::vector<CellJobRoundStatus> rounds;  ///< complete rounds, 1 on
  int nextRound = 1;                       ///< 0: converged (or at --max-rounds): gather
  std::vector<int> missing;                ///< cells whose round nextRound is not done yet
};
/// The finished rounds as cellJobStatus found them, kept by a process that asks again (a cell-job server
/// answering every round's barrier): finished rounds do not change (a rerun writes the same figures), so the
/// next call reads only the summaries of the rounds after them, for as long as the plan's emitted and
/// target power are the same (a plan made again and summed again gives the same rounds). One per plan folder.
struct CellJobStatusKept {
  double emitted = 0.0, target = 0.0;  ///< the plan's when kept
  std::vector<CellJobRoundStatus> rounds;
  std::optional<RoundStop> stop;  ///< the stop after `rounds`; unset: nothing kept
  double unshot = 0.0;            ///< W unshot after `rounds`
};
/// From plan.json and the summaries alone (no scene, no GPU); with `kept`, on from the rounds kept there.
CellJobStatus cellJobStatus(const std::filesystem::path& dir, const CellJobPlan& plan,
                            CellJobStatusKept* kept = nullptr);

/// Every round of the plan applied in order (InputError unless the rounds are complete up to the stop).
SolveResult gatherCellJobs(const std::filesystem::path& dir, const CellJobPlan& plan, const Scene& scene,
                           const CellGraph& graph, const LightmapAtlas& global, const CellSolveParams& params,
                           Context& ctx);

}  // namespace cpgi
