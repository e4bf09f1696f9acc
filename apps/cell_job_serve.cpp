#include "apps/cell_job_serve.h"

#include <chrono>
#include <functional>
#include <istream>
#include <optional>
#include <ostream>

#include <nlohmann/json.hpp>

#include "apps/cell_job_status.h"
#include "core/error.h"
#include "radiosity/cells/cell_jobs.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/gpu/gl_shot_engine.h"

namespace cpgi::cli {
namespace {

struct ServeRequest {
  enum class Kind { Round, FirstShot, Status, Gather } kind = Kind::Round;
  int round = 0;               ///< a round job's round
  std::string cells;           ///< a round job's "A,B" (cellsByName's list), empty: every cell
  std::vector<int> firstShot;  ///< a first-shot job's emitter groups
};

// {"first_shot": [G, ...]}: emitter group numbers, at least one.
std::vector<int> firstShotGroups(const nlohmann::json& j) {
  if (!j.is_array() || j.empty())
    throw InputError("request", "\"first_shot\" must be a list of emitter groups");
  std::vector<int> groups;
  for (const nlohmann::json& g : j) {
    if (!g.is_number_integer() || g.get<int>() < 0)
      throw InputError("request", "\"first_shot\" must be a list of emitter groups");
    groups.push_back(g.get<int>());
  }
  return groups;
}

// `id` (echoed in the answer; null: none) is set as soon as the line is a JSON object, so that a refused
// request is answered with it too.
ServeRequest parseRequest(const std::string& line, nlohmann::json& id) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(line);
  } catch (const nlohmann::json::exception&) {
    throw InputError("request", "not one JSON object a line: " + line.substr(0, 80));
  }
  if (!j.is_object()) throw InputError("request", "not a JSON object: " + line.substr(0, 80));
  ServeRequest r;
  id = j.value("id", nlohmann::json());
  const int kinds = int(j.contains("first_shot")) + int(j.contains("round")) + int(j.contains("status")) +
                    int(j.contains("gather"));
  if (kinds != 1)
    throw InputError("request",
                     "give one of \"round\" (and \"cells\"), \"first_shot\", \"status\" or \"gather\"");
  for (const char* flag : {"status", "gather"})
    if (j.contains(flag)) {
      if (j[flag] != true) throw InputError("request", std::string("\"") + flag + "\" must be true");
      r.kind = j.contains("status") ? ServeRequest::Kind::Status : ServeRequest::Kind::Gather;
      return r;
    }
  if (j.contains("first_shot")) {
    r.kind = ServeRequest::Kind::FirstShot;
    r.firstShot = firstShotGroups(j["first_shot"]);
    return r;
  }
  if (!j.contains("round") || !j["round"].is_number_integer() || j["round"].get<int>() < 1)
    throw InputError("request", "\"round\" must be a round number (1, 2, ...)");
  r.round = j["round"].get<int>();
  if (j.contains("cells")) {
    if (!j["cells"].is_array() || j["cells"].empty())
      throw InputError("request", "\"cells\" must be a list of cell names");
    for (const nlohmann::json& name : j["cells"]) {
      if (!name.is_string()) throw InputError("request", "\"cells\" must be a list of cell names");
      r.cells += (r.cells.empty() ? "" : ",") + name.get<std::string>();
    }
  }
  return r;
}

void answer(std::ostream& out, nlohmann::json a, const nlohmann::json& id) {
  if (!id.is_null()) a["id"] = id;
  out << a.dump() << "\n" << std::flush;  // the client waits on this line
}

std::vector<int> requestedCells(const CellGraph& graph, const std::string& list) {
  if (!list.empty()) return cellsByName(graph, list, "cells");
  std::vector<int> all(graph.cells.size());
  for (size_t c = 0; c < all.size(); ++c) all[c] = int(c);
  return all;
}

}  // namespace

int serveCellJobs(const std::filesystem::path& dir, BakeJobs& jobs, const EglContext& gl, Context& ctx,
                  std::istream& in, std::ostream& out) {
  const nlohmann::json settings = bakeSettingsJson(jobs.settings());
  GlShotEngine engine(gl);              // its programs kept from job to job
  std::optional<CellJobServer> server;  // built at the first request: a server may start before the sum
  CellJobStatusKept statusKept;         // the finished rounds, so that a status reads only the new ones
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    nlohmann::json id;
    try {
      const auto start = std::chrono::steady_clock::now();
      const ServeRequest request = parseRequest(line, id);
      // plan.json is re-read for every job: the first shot's sum rewrites it (summed, target power).
      const CellJobPlan plan = readCellJobPlan(dir);
      if (bakeSettingsJson(bakeSettingsFromJson(plan.bakeSettings)) != settings) {
        answer(
            out,
            {{"ok", false},
             {"error", (dir / "plan.json").string() + ": the plan was made again with other bake arguments "
                                                      "than this server's; start a new one"}},
            id);
        return 1;
      }
      nlohmann::json done = {{"ok", true}};
      if (request.kind == ServeRequest::Kind::Status) {
        done["status"] = cellJobStatusJson(plan, cellJobStatus(dir, plan, &statusKept));
      } else if (request.kind == ServeRequest::Kind::Gather) {
        // As `cpgi cell-job PLAN --gather`, with a context of its own (the report's timings are the
        // gather's) and nothing on stdout (the answers are there).
        Context gatherCtx;
        BakeRun run;
        run.gl = &gl;
        jobs.gather(run, gatherCtx);
        done["gather"] = true;
      } else if (request.kind == ServeRequest::Kind::FirstShot) {
        jobs.firstShot(request.firstShot, engine, ctx);
        done["first_shot"] = request.firstShot;
      } else {
        const std::vector<int> cells = requestedCells(jobs.graph(), request.cells);
        if (!server) server.emplace(jobs.scene(), jobs.graph(), jobs.params(), ctx);
        server->runRound(dir, plan, request.round, cells, engine, ctx);
        done["round"] = request.round, done["cells"] = cells.size();
      }
      done["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      answer(out, done, id);
    } catch (const InputError& e) {
      answer(out, {{"ok", false}, {"error", e.what()}}, id);
    } catch (const std::exception& e) {
      answer(out, {{"ok", false}, {"error", e.what()}}, id);
      throw;  // the GPU or the disk failed: the server's state is not to be trusted; main reports it
    }
  }
  return 0;
}

}  // namespace cpgi::cli
