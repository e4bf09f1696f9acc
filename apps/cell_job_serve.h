// `cpgi cell-job PLAN --serve`: round jobs (and first-shot jobs) of one plan, one request a line on stdin,
// one answer a line on stdout, in one process that keeps the scene, the EGL context, the cells' atlases and
// the compiled GPU programs between jobs (radiosity/cells/cell_jobs.h, CellJobServer; docs/cell-jobs.md).
// What a driver such as cpgi-dask keeps per worker, so that a job no longer pays a process start, a scene
// load and llvmpipe's shader set-up, nor a round's barrier a `cpgi cell-job --status` process, nor the
// gather its own process, scene load and EGL context.
//
//   request  {"round": R, "cells": ["A", "B"], "id": ANY}     cells: default every cell; id: echoed
//            {"first_shot": [G, ...], "id": ANY}              emitter groups of the lamps' first shot
//            {"status": true, "id": ANY}                      which step is next (no GPU, no job)
//            {"gather": true, "id": ANY}                      the bake's -o folder, as --gather writes it
//   answer   {"ok": true, "round": R, "cells": 2, "seconds": 1.25, "id": ANY}
//            {"ok": true, "first_shot": [G, ...], "seconds": 3.5, "id": ANY}
//            {"ok": true, "status": {...}, "seconds": 0.004, "id": ANY}  status: --status --json's object
//            {"ok": true, "gather": true, "seconds": 1.2, "id": ANY}
//            {"ok": false, "error": "one line", "id": ANY}
//
// A refused job (InputError: a file missing or damaged, a round not needed) is answered and the server
// goes on; anything else (the GPU, a write that failed) is answered and ends it with status 1, as does a
// plan remade with other bake settings than the server's. End of input ends it with status 0.
#pragma once

#include <filesystem>
#include <iosfwd>

#include "core/context.h"
#include "radiosity/bake/bake_jobs.h"
#include "radiosity/gpu/egl_context.h"

namespace cpgi::cli {

/// Serves the jobs of the plan in `dir` on `jobs` (its settings, scene and cells, loaded from the plan)
/// until `in` ends. Returns the exit status.
int serveCellJobs(const std::filesystem::path& dir, BakeJobs& jobs, const EglContext& gl, Context& ctx,
                  std::istream& in, std::ostream& out);

}  // namespace cpgi::cli
