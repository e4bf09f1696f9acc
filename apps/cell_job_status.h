// The cell jobs' status as a driver reads it (docs/cell-jobs.md): `cpgi cell-job PLAN --status --json`
// prints it, and a `cpgi cell-job PLAN --serve` process answers a {"status": true} request with the same
// object, so that a driver whose workers keep a server asks there at each round's barrier instead of
// starting a process (and loading cpgi's libraries) for it.
#pragma once

#include <nlohmann/json.hpp>

#include "radiosity/cells/cell_jobs.h"

namespace cpgi::cli {

/// What a driver runs next: "first-shot", "first-shot-sum", "round" or "gather".
const char* cellJobNextStep(const CellJobStatus& s);

/// `--status --json`'s object: cells, emitted and target power, the first shot, next_step, the finished
/// rounds in figures, next_round and the cells it still misses.
nlohmann::json cellJobStatusJson(const CellJobPlan& plan, const CellJobStatus& s);

}  // namespace cpgi::cli
