// The cells' stop per cell (radiosity/cells/round_stop.h): the ambient term's series in closed form, the
// stop refused while a cell's light is mostly the ambient term's, and on spot-door, whose lamp room is lit
// mostly by what comes back through the door, a cells solve stopped at the scene's unshot target alone
// left that room 3–4.5 % bright; with the stop per cell it is within 1 % of a converged solve of the whole
// scene.
#include "radiosity/cells/round_stop.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/solve/progressive_loop.h"

#include <cstdio>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/solve/ambient.h"
#include "scenes/stability_scenes.h"
#include "tests/radiosity/cells/cell_energy_check.h"

namespace cpgi {
namespace {

TEST(AmbientLanded, ClosedRoomReceivesItsUnshotPowerOverEveryBounce) {
  const std::vector<glm::dvec3> landed =
      ambientLanded({AmbientRoom{10.0, glm::dvec3(5.0, 2.5, 0.0), glm::dvec3(3.0)}}, {});
  ASSERT_EQ(landed.size(), 1u);
  EXPECT_NEAR(landed[0].r, 3.0 / (1.0 - 0.5), 1e-6);  // Σ ρⁿ
  EXPECT_NEAR(landed[0].g, 3.0 / (1.0 - 0.25), 1e-6);
  EXPECT_NEAR(landed[0].b, 3.0, 1e-9);  // black: only the first landing
}

TEST(AmbientLanded, AnOpeningPassesItsShareOfTheEnclosure) {
  // Black rooms: what leaves room 0 lands once, 9 m² of its surfaces against a 1 m² opening.
  const std::vector<glm::dvec3> landed = ambientLanded({AmbientRoom{9.0, glm::dvec3(0.0), glm::dvec3(1.0)},
                                                        AmbientRoom{9.0, glm::dvec3(0.0), glm::dvec3(0.0)}},
                                                       {AmbientOpening{0, 1, 1.0}});
  EXPECT_NEAR(landed[0].r, 0.9, 1e-12);
  EXPECT_NEAR(landed[1].r, 0.1, 1e-12);
}

CellStopSurfaces greyCell(double area, double albedo) {
  return CellStopSurfaces{area, glm::dvec3(albedo * area), glm::dvec3(albedo * area), true};
}

TEST(RoundStop, WithoutAShareTheTargetAloneStops) {
  RoundStop stop(1.0, 0.0, {greyCell(1.0, 0.5)}, {});
  EXPECT_TRUE(stop.another(2.0));
  CellRound r;
  r.keptRgb = glm::dvec3(10.0);  // nearly all of the cell's light still unshot: no matter
  stop.addRound({&r});
  EXPECT_FALSE(stop.another(1.0));
  EXPECT_EQ(stop.checks(), 0);
}

TEST(RoundStop, RefusesWhileTheAmbientTermIsMuchOfACellsLight) {
  RoundStop stop(1.0, 0.1, {greyCell(1.0, 0.5), greyCell(1.0, 0.5)}, {});
  EXPECT_TRUE(stop.another(10.0));  // above the target: no question asked
  EXPECT_EQ(stop.checks(), 0);
  CellRound lit, dark;
  lit.cell = 0, dark.cell = 1;
  lit.reflectorGain = 100.0;
  dark.reflectorGain = 0.3;
  // Cell 1 holds 0.1 W a channel: 0.2 W lands over the bounces, ρ × 0.2 = 0.1 a channel is added to its
  // 0.3 W of light (R + G + B): the ambient term would be half of it.
  PortalSend send;
  send.from = 0, send.to = 1;
  send.arrivingRgb = glm::dvec3(0.1);
  lit.sends = {send};
  stop.addRound({&lit, &dark});
  EXPECT_NEAR(stop.shares()[1], 0.5, 1e-9);
  EXPECT_LT(stop.shares()[0], 1e-12);
  EXPECT_TRUE(stop.another(0.5));  // at the target, but refused
  EXPECT_EQ(stop.checks(), 1);
  EXPECT_DOUBLE_EQ(stop.target(), 0.5 * kStopRecheck);
  EXPECT_TRUE(stop.another(0.4));  // above the lowered target: goes on without asking
  EXPECT_EQ(stop.checks(), 1);
  // The next round shoots that light in cell 1 and leaves little unshot: the stop is accepted.
  CellRound lit2, dark2;
  lit2.cell = 0, dark2.cell = 1;
  dark2.reflectorGain = 5.0;
  dark2.keptRgb = glm::dvec3(0.01);
  stop.addRound({&lit2, &dark2});
  EXPECT_LT(stop.shares()[1], 0.1);
  EXPECT_FALSE(stop.another(0.03));
  EXPECT_EQ(stop.checks(), 2);
}

TEST(RoundStop, ABoundaryCellNeverHoldsTheStop) {
  CellStopSurfaces boundary = greyCell(1.0, 0.5);
  boundary.written = false;
  RoundStop stop(1.0, 0.1, {boundary}, {});
  CellRound r;
  r.keptRgb = glm::dvec3(0.1);  // all its light ambient, but nobody sees it
  stop.addRound({&r});
  EXPECT_FALSE(stop.another(0.5));
}

TEST(RoundStop, ACellLitOnlyByALeakNeverHoldsTheStop) {
  // Cell 1 has 3e-5 of cell 0's light per m², nearly all of it the ambient term's: a closed room behind a
  // wall, lit by what crosses it. Held to the share, the rounds went on to 1e-6 of the light.
  RoundStop stop(1.0, 0.1, {greyCell(1.0, 0.5), greyCell(1.0, 0.5)}, {});
  CellRound lit, leak;
  lit.cell = 0, leak.cell = 1;
  lit.reflectorGain = 100.0;
  leak.reflectorGain = 1e-4;
  leak.keptRgb = glm::dvec3(1e-3);
  stop.addRound({&lit, &leak});
  EXPECT_EQ(stop.shares()[1], 0.0);
  EXPECT_FALSE(stop.another(0.5));
  // The same cell lit at 4e-3 of cell 0's light per m² is a dark room, and holds it.
  leak.reflectorGain = 0.1;
  leak.keptRgb = glm::dvec3(0.1);
  RoundStop dim(1.0, 0.1, {greyCell(1.0, 0.5), greyCell(1.0, 0.5)}, {});
  dim.addRound({&lit, &leak});
  EXPECT_GT(dim.shares()[1], 0.1);
  EXPECT_TRUE(dim.another(0.5));
}

TEST(AmbientShareOfLitCells, PerSquareMetreAgainstTheWholeScene) {
  // The scene: 101 W over 21 m². Cell 1 at 2e-5 W/m², under 1e-4 of its 4.8 W/m² (a leak); cell 2 at
  // 0.1 W/m² (dim, kept); cell 3 without area.
  const std::vector<double> share =
      ambientShareOfLitCells({10.0, 1e-4, 0.5, 1.0}, {100.0, 2e-4, 1.0, 1.0}, {1.0, 10.0, 10.0, 0.0});
  ASSERT_EQ(share.size(), 4u);
  EXPECT_DOUBLE_EQ(share[0], 0.1);
  EXPECT_EQ(share[1], 0.0);
  EXPECT_DOUBLE_EQ(share[2], 0.5);
  EXPECT_EQ(share[3], 0.0);
  EXPECT_EQ(ambientShareOfLitCells({0.0}, {0.0}, {1.0})[0], 0.0);  // nothing lit at all
  EXPECT_THROW(ambientShareOfLitCells({0.0}, {0.0, 1.0}, {1.0}), std::invalid_argument);
}

// Mean radiosity (R + G + B) over the texels of cell `cell` that do not emit.
double cellMean(const LightmapAtlas& a, const ExrChannel& cells, int cell, const std::vector<glm::vec3>& b) {
  double sum = 0.0, area = 0.0;
  for (size_t i = 0; i < a.texelCount(); ++i) {
    if (a.patch[i] < 0 || int(cells.values[i]) != cell || a.emission[i] != glm::vec3(0.0f)) continue;
    sum += (double(b[i].r) + b[i].g + b[i].b) * a.area[i];
    area += a.area[i];
  }
  return sum / area;
}

TEST(RoundStop, LampRoomLitByWhatComesBackIsRightAtTheDefaultStop) {
  const SeedScene s = makeBuiltinScene("spot-door");
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  AtlasParams ap;
  ap.density = 10.0f;
  const LightmapAtlas atlas = buildAtlas(s.scene, findQuads(s.scene), ap, ctx);
  const ExrChannel cells = cellChannel(atlas, s.scene, s.cells);
  const int lampRoom = s.cells.findCell("A");
  ASSERT_GE(lampRoom, 0);
  SolverParams converged;
  converged.lampRays = 64;
  converged.unshotFraction = 1e-4;
  const SolveResult global = solveProgressive(s.scene, atlas, converged, gl, ctx);
  const double truth = cellMean(atlas, cells, lampRoom, global.radiosity);

  double ratio[2] = {0.0, 0.0};
  int checks[2] = {0, 0};
  for (int withStop = 0; withStop < 2; ++withStop) {
    CellSolveParams p;
    p.atlas = ap;
    p.solver = SolverParams{};
    p.solver.lampRays = 64;  // the default unshot stop, 1 %
    p.portals = PortalLight::Binned;
    p.maxAmbientShare = withStop ? kDefaultAmbientShare : 0.0;
    SolveResult r = solveCells(s.scene, s.cells, atlas, p, gl, ctx);
    addAmbient(atlas, r.residual, glm::dvec3(r.energy.unshot / 3.0), cells.values, s.cells, r.radiosity);
    ratio[withStop] = cellMean(atlas, cells, lampRoom, r.radiosity) / truth;
    checks[withStop] = r.stopChecks;
    testing::expectConserved(r);
  }
  std::printf(
      "lamp room A of the converged whole scene's solve: unshot stop alone %.3f, per cell %.3f (%d asks)\n",
      ratio[0], ratio[1], checks[1]);
  // What the stop per cell is for: 1.029 here, 1.045 against `cpgi reference`; per cell 0.991 (1.005).
  EXPECT_GT(ratio[0], 1.02);
  EXPECT_NEAR(ratio[1], 1.0, 0.015);
  EXPECT_EQ(checks[0], 0);
  EXPECT_GE(checks[1], 1);
}

}  // namespace
}  // namespace cpgi
