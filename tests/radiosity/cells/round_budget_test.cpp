// A round's solves measure each shot's coverage with kCellCoverageRays (cell_round.h, roundBudget): a
// room's shot has a thousandth of a building's receivers, and the scene's 1 024 coverage rays a region were
// a tenth of the cells' gather. A smaller number asked for the whole scene stays.
#include "radiosity/cells/cell_round.h"

#include <gtest/gtest.h>

namespace cpgi {
namespace {

TEST(RoundBudget, ACellsShotsMeasureTheirCoverageWithTheCellsRays) {
  CellSolveParams params;
  params.solver.coverageRays = 1024;
  SolveControls controls;
  ShotShape shape;
  const SolverParams round = roundBudget(params, 1.0, 10.0, 100.0, controls, shape, 500);
  EXPECT_EQ(round.coverageRays, kCellCoverageRays);
  EXPECT_LT(kCellCoverageRays, 1024);
  params.solver.coverageRays = 64;
  EXPECT_EQ(roundBudget(params, 1.0, 10.0, 100.0, controls, shape, 500).coverageRays, 64);
}

}  // namespace
}  // namespace cpgi
