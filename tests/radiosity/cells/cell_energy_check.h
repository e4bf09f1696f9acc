// The energy bookkeeping check shared by the cell solver tests (diffuse and directional portals).
#pragma once

#include <algorithm>

#include <gtest/gtest.h>

#include "radiosity/cells/cell_solver.h"

namespace cpgi::testing {

// emitted + received = absorbed + sent + unshot + escaped in every cell, and no cell's solves created
// light; what one cell sends another receives.
inline void expectConserved(const SolveResult& r) {
  ASSERT_TRUE(r.perCell);
  const EnergyTotals& e = r.energy;
  double sent = 0.0, received = 0.0, through = 0.0;
  for (const CellEnergy& c : r.perCell->cells) {
    const double in = c.emitted + c.received;
    EXPECT_NEAR(c.absorbed + c.sent + c.unshot + c.escaped, in, 1e-3 * std::max(in, 1e-3 * e.emitted))
        << c.name;
    EXPECT_LE(c.created, 2e-3 * std::max(in, 1e-3 * e.emitted)) << c.name;
    EXPECT_GE(c.worstShotGain, 0.0) << c.name;
    sent += c.sent, received += c.received;
  }
  for (const PortalEnergy& p : r.perCell->portals) through += p.aToB + p.bToA;
  EXPECT_NEAR(sent, received, 1e-9 * e.emitted);
  EXPECT_NEAR(through, sent, 1e-9 * e.emitted);
  EXPECT_LE(e.created, 2e-3 * e.emitted);
  EXPECT_NEAR(e.absorbed + e.unshot + e.escaped(), e.emitted, 1e-3 * e.emitted);
  EXPECT_NEAR(r.unshotFraction, e.unshot / e.emitted, 1e-12);
}

}  // namespace cpgi::testing
