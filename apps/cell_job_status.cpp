#include "apps/cell_job_status.h"

namespace cpgi::cli {

const char* cellJobNextStep(const CellJobStatus& s) {
  if (!s.firstShotSummed) return s.firstShotMissing.empty() ? "first-shot-sum" : "first-shot";
  return s.nextRound == 0 ? "gather" : "round";
}

nlohmann::json cellJobStatusJson(const CellJobPlan& plan, const CellJobStatus& s) {
  nlohmann::json rounds = nlohmann::json::array(), missing = nlohmann::json::array();
  for (const CellJobRoundStatus& r : s.rounds)
    rounds.push_back({{"round", r.round},
                      {"unshot_w", r.unshot},
                      {"target_w", r.target},
                      {"solved_cells", r.solved},
                      {"shots", r.shots},
                      {"job_seconds", r.jobSeconds},
                      {"max_job_seconds", r.maxJobSeconds},
                      {"portal_bytes", r.portalBytes}});
  for (int c : s.missing) missing.push_back(plan.cells[size_t(c)]);
  const nlohmann::json firstShot = {{"groups", plan.firstShotGroups.size()},
                                    {"missing_groups", s.firstShotMissing},
                                    {"summed", s.firstShotSummed}};
  return {{"cells", plan.cells.size()},
          {"emitted_w", plan.emitted},
          {"target_w", plan.target},
          {"first_shot", firstShot},
          {"next_step", cellJobNextStep(s)},
          {"rounds", rounds},
          {"next_round", s.firstShotSummed ? s.nextRound : 1},
          {"missing", missing}};
}

}  // namespace cpgi::cli
