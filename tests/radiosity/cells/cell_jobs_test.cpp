// Cell jobs (issue 16): the first shot run one emitter group per job and summed, then the rounds run one
// cell per job from files and gathered give solveCells' result bit for bit, on the 4-room office (two
// storeys joined by a hatch, a lamp in two rooms), also when one server process runs the round jobs one
// after another (CellJobServer); the job files refuse damage.
#include "radiosity/cells/cell_jobs.h"
#include "radiosity/gpu/gl_shot_engine.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "core/quads.h"
#include "radiosity/cells/cell_job_files.h"
#include "scenes/stability_scenes.h"
#include "tests/radiosity/cells/cell_energy_check.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() /
                  ("cpgi-cell-jobs-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                   "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Every file of a round but the summaries (which also record the job's seconds): name → bytes.
std::map<std::string, std::string> roundLight(const fs::path& dir, int round) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(roundDir(dir, round)))
    if (e.path().extension() != ".summary") files[e.path().filename().string()] = fileBytes(e.path());
  return files;
}

// Round `round` of every cell, one cell a job, last cell first: each job its own process's work
// (runCellJobs), or one server's after another (CellJobServer: its atlases, programs and the cells' state
// kept from the jobs before, of this round and the rounds before).
void runRound(const fs::path& dir, const CellJobPlan& plan, int round, const SeedScene& s,
              const CellSolveParams& params, CellJobServer* server, ShotEngine& gl, Context& ctx) {
  for (int c = int(plan.cells.size()) - 1; c >= 0; --c) {  // any order within a round
    if (server)
      server->runRound(dir, plan, round, {c}, gl, ctx);
    else
      runCellJobs(dir, plan, round, {c}, s.scene, s.cells, params, gl, ctx);
  }
}

// A status kept from call to call (a server's, CellJobStatusKept) against one read from every file.
void expectSameStatus(const CellJobStatus& kept, const CellJobStatus& fresh) {
  EXPECT_EQ(kept.firstShotMissing, fresh.firstShotMissing);
  EXPECT_EQ(kept.firstShotSummed, fresh.firstShotSummed);
  EXPECT_EQ(kept.nextRound, fresh.nextRound);
  EXPECT_EQ(kept.missing, fresh.missing);
  ASSERT_EQ(kept.rounds.size(), fresh.rounds.size());
  for (size_t r = 0; r < kept.rounds.size(); ++r) {
    EXPECT_EQ(kept.rounds[r].round, fresh.rounds[r].round);
    EXPECT_EQ(kept.rounds[r].unshot, fresh.rounds[r].unshot) << "round " << r + 1;
    EXPECT_EQ(kept.rounds[r].target, fresh.rounds[r].target) << "round " << r + 1;
    EXPECT_EQ(kept.rounds[r].shots, fresh.rounds[r].shots);
    EXPECT_EQ(kept.rounds[r].solved, fresh.rounds[r].solved);
  }
}

// Every step as its own job from files, against solveCells with the same parameters: bit for bit. With
// `served`, the rounds run on one CellJobServer, and each round's first cell runs again at the end of the
// round (a job rerun after a lost worker), and a cell of the round before too, rewriting the same state
// and portal light.
void expectJobsGiveTheSingleProcessSolve(PortalLight portals, double maxAmbientShare = 0.0,
                                         bool served = false) {
  const SeedScene s = makeBuiltinScene("office-small");
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellSolveParams params;
  params.portals = portals;
  params.maxAmbientShare = maxAmbientShare;
  params.atlas.texelsPerQuad = 6;
  params.solver.itemBuffer = 256;
  const LightmapAtlas atlas = buildAtlas(s.scene, findQuads(s.scene), params.atlas, ctx);
  const SolveResult single = solveCells(s.scene, s.cells, atlas, params, gl, ctx);
  ASSERT_GE(single.perCell->rounds, 2);
  if (maxAmbientShare > 0.0) {
    ASSERT_GE(single.stopChecks, 2);  // refused at least once
  }

  TempDir dir;
  const CellJobPlan made = planCellJobs(dir.path, s.scene, s.cells, atlas, params, {{"unused", true}}, ctx);
  EXPECT_EQ(readCellJobPlan(dir.path).cells, made.cells);
  ASSERT_EQ(made.firstShotGroups.size(), 2u);  // two lamps in two rooms: the sum adds two groups
  EXPECT_THROW(runCellJobs(dir.path, made, 1, {0}, s.scene, s.cells, params, gl, ctx), InputError);
  for (int g = int(made.firstShotGroups.size()) - 1; g >= 0; --g)  // any order, one group per job
    runFirstShotJobs(dir.path, made, {g}, s.scene, s.cells, atlas, params, gl, ctx);
  EXPECT_TRUE(cellJobStatus(dir.path, made).firstShotMissing.empty());
  EXPECT_FALSE(cellJobStatus(dir.path, made).firstShotSummed);
  const CellJobPlan plan = sumFirstShotJobs(dir.path, made, s.scene, s.cells, atlas, params, ctx);
  EXPECT_TRUE(readCellJobPlan(dir.path).firstShotSummed);
  EXPECT_EQ(readCellJobPlan(dir.path).emitted, plan.emitted);
  std::optional<CellJobServer> server;
  if (served) server.emplace(s.scene, s.cells, params, ctx);
  CellJobStatusKept kept;
  for (int round = 1;; ++round) {
    const CellJobStatus status = cellJobStatus(dir.path, plan);
    expectSameStatus(cellJobStatus(dir.path, plan, &kept), status);
    if (round >= 2) {
      EXPECT_EQ(kept.rounds.size(), size_t(round - 1));  // the rounds finished so far, kept
    }
    if (status.nextRound == 0) break;
    ASSERT_EQ(status.nextRound, round);
    runRound(dir.path, plan, round, s, params, server ? &*server : nullptr, gl, ctx);
    if (server) {
      const std::map<std::string, std::string> written = roundLight(dir.path, round);
      server->runRound(dir.path, plan, round, {int(plan.cells.size()) - 1}, gl, ctx);
      EXPECT_EQ(roundLight(dir.path, round), written) << "round " << round << " rerun";
      if (round >= 2) {  // an earlier round after a later one: the server's replay of the stop starts over
        const std::map<std::string, std::string> earlier = roundLight(dir.path, round - 1);
        server->runRound(dir.path, plan, round - 1, {0}, gl, ctx);
        EXPECT_EQ(roundLight(dir.path, round - 1), earlier)
            << "round " << round - 1 << " rerun after " << round;
      }
    }
  }
  const SolveResult gathered = gatherCellJobs(dir.path, plan, s.scene, s.cells, atlas, params, ctx);
  EXPECT_EQ(gathered.perCell->rounds, single.perCell->rounds);
  EXPECT_EQ(gathered.shots, single.shots);
  EXPECT_EQ(gathered.stopChecks, single.stopChecks);
  ASSERT_EQ(gathered.radiosity.size(), single.radiosity.size());
  size_t differ = 0;
  for (size_t i = 0; i < single.radiosity.size(); ++i) differ += gathered.radiosity[i] != single.radiosity[i];
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(gathered.residual, single.residual);
  EXPECT_EQ(gathered.energy.unshot, single.energy.unshot);
  EXPECT_EQ(gathered.energy.absorbed, single.energy.absorbed);
  testing::expectConserved(gathered);
  {
    // The gather reads the cells' files side by side and adds them in cell order: on one thread, the same
    // bits.
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const SolveResult serial = gatherCellJobs(dir.path, plan, s.scene, s.cells, atlas, params, ctx);
    EXPECT_EQ(serial.radiosity, gathered.radiosity);
    EXPECT_EQ(serial.residual, gathered.residual);
    for (auto field : {&EnergyTotals::emitted, &EnergyTotals::shot, &EnergyTotals::received,
                       &EnergyTotals::absorbed, &EnergyTotals::unshot})
      EXPECT_EQ(serial.energy.*field, gathered.energy.*field);
    ASSERT_EQ(serial.perCell->cells.size(), gathered.perCell->cells.size());
    for (size_t c = 0; c < serial.perCell->cells.size(); ++c) {
      EXPECT_EQ(serial.perCell->cells[c].received, gathered.perCell->cells[c].received);
      EXPECT_EQ(serial.perCell->cells[c].unshot, gathered.perCell->cells[c].unshot);
    }
  }

  // A round the solve does not need is refused, naming the round's folder.
  EXPECT_THROW(
      runCellJobs(dir.path, plan, gathered.perCell->rounds + 1, {0}, s.scene, s.cells, params, gl, ctx),
      InputError);
}

TEST(CellJobs, OneCellPerJobGivesTheSingleProcessSolve) {
  expectJobsGiveTheSingleProcessSolve(PortalLight::Diffuse);
}

// Directional portals: the arrival moments go through the files with the light (the state's kept
// moments, the portal light's moments per texel). Dropped there, the lobes would be Lambertian and the
// rooms lit through the hatch and doors would differ from the single process.
TEST(CellJobs, DirectionalPortalsGiveTheSingleProcessSolve) {
  expectJobsGiveTheSingleProcessSolve(PortalLight::Directional);
}

// Binned portals: the bins go through the files too (the state's kept bins, the portal light's bins per
// texel), and each send's rays depend on the portal and texel only, so the jobs' bins are the single
// process's.
TEST(CellJobs, BinnedPortalsGiveTheSingleProcessSolve) {
  expectJobsGiveTheSingleProcessSolve(PortalLight::Binned);
}

// The stop per cell (round_stop.h) decided by the driver from the plan and the summaries alone: the
// same rounds, each towards the same lowered target, as the single process.
TEST(CellJobs, StopPerCellGivesTheSingleProcessSolve) {
  expectJobsGiveTheSingleProcessSolve(PortalLight::Binned, 0.02);
}

// Jobs served one after another by one process (`cpgi cell-job PLAN --serve`), with the binned portals of
// the bake's default and with the directional ones (moments through the files): the single process's
// solve. A served cell that kept anything of the job before (its pending light, its emission, another
// atlas than the whole graph's) would differ.
TEST(CellJobs, ServedJobsGiveTheSingleProcessSolve) {
  expectJobsGiveTheSingleProcessSolve(PortalLight::Binned, 0.0, true);
}
TEST(CellJobs, ServedDirectionalJobsGiveTheSingleProcessSolve) {
  expectJobsGiveTheSingleProcessSolve(PortalLight::Directional, 0.0, true);
}

TEST(CellJobFiles, DamageIsNamedAndRefused) {
  TempDir dir;
  fs::create_directories(dir.path);
  CellRoundSummary s;
  s.round = 2;
  s.figures.cell = 5;
  s.figures.solved = true;
  s.figures.keptPower = 1.5;
  PortalSend send;
  send.portal = 3, send.from = 5, send.to = 6, send.watts = 2.0, send.arriving = 1.9;
  s.figures.sends.push_back(send);
  const fs::path file = dir.path / "cell-0005.summary";
  writeSummary(file, s);
  const CellRoundSummary back = readSummary(file, 2, 5);
  EXPECT_EQ(back.figures.keptPower, 1.5);
  ASSERT_EQ(back.figures.sends.size(), 1u);
  EXPECT_EQ(back.figures.sends[0].arriving, 1.9);

  auto refused = [&](const std::string& expected) {
    try {
      readSummary(file, 2, 5);
      ADD_FAILURE() << "read a damaged file";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  EXPECT_THROW(readSummary(file, 3, 5), InputError);    // another round than asked
  EXPECT_THROW(readCellState(file, 2, 5), InputError);  // another kind

  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto rewrite = [&](const std::string& b) { std::ofstream(file, std::ios::binary | std::ios::trunc) << b; };
  rewrite(bytes.substr(0, bytes.size() - 5));
  refused("truncated");
  std::string flipped = bytes;
  flipped[30] ^= 1;
  rewrite(flipped);
  refused("checksum");
  std::string version = bytes;
  version[8] = 9;
  rewrite(version);
  refused("format 9");
  fs::remove(file);
  refused("cannot read");

  // An emitter group's shot: read back as written, refused for another group or atlas.
  FirstShotContribution shot;
  shot.emitted = 3.0, shot.shots = 1;
  shot.texels = {2, 7}, shot.incident = {glm::vec3(1.0f), glm::vec3(0.5f)};
  const fs::path group = dir.path / "group-0001.shot";
  writeFirstShotGroup(group, 1, 4, 10, shot);
  const FirstShotContribution read = readFirstShotGroup(group, 1, 4, 10);
  EXPECT_EQ(read.texels, shot.texels);
  EXPECT_EQ(read.incident, shot.incident);
  EXPECT_THROW(readFirstShotGroup(group, 2, 4, 10), InputError);
  EXPECT_THROW(readFirstShotGroup(group, 1, 4, 11), InputError);
}

}  // namespace
}  // namespace cpgi
