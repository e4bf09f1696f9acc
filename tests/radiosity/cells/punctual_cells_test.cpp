// KHR_lights_punctual in a cell-by-cell solve: each cell gets the lights' direct light that lands in it
// (through the whole scene, so the lamp in A lights B through the door directly, not through the portal's
// re-emission), every cell's energy balances, and the result matches a global solve per cell.
#include <numbers>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "scenes/stability_scenes.h"
#include "tests/radiosity/cells/cell_energy_check.h"

namespace cpgi {
namespace {

// Σ B a over the texels of each cell (by the first component of the texel's node path, as the
// generated scenes name them).
std::vector<double> powerPerCell(const SeedScene& s, const LightmapAtlas& atlas,
                                 const std::vector<glm::vec3>& radiosity) {
  std::vector<double> out(s.cells.cells.size(), 0.0);
  const std::vector<int> cellOf = s.cells.cellOfTriangle(s.scene.triangles.size());
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    const int c = cellOf[size_t(atlas.patches[size_t(atlas.patch[i])].triangles[0])];
    if (c >= 0) out[size_t(c)] += double(radiosity[i].r + radiosity[i].g + radiosity[i].b) * atlas.area[i];
  }
  return out;
}

TEST(PunctualCells, PointLampInOneRoomLightsBothAsTheGlobalSolveDoes) {
  const SeedScene s = makePointLightRooms();
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellSolveParams params;
  params.atlas.density = 4.0f;
  params.solver.unshotFraction = 1e-3;
  params.solver.itemBuffer = 256;
  const LightmapAtlas atlas = buildAtlas(s.scene, findQuads(s.scene), params.atlas, ctx);
  const SolveResult cells = solveCells(s.scene, s.cells, atlas, params, gl, ctx);
  testing::expectConserved(cells);
  const double power = 3.0 * 4.0 * std::numbers::pi * 8.0;
  EXPECT_NEAR(cells.energy.emitted, power, power * 1e-5);
  // The lamp's light reaches B directly through the door: B emits (is lit) without any portal.
  ASSERT_EQ(cells.perCell->cells.size(), 2u);
  EXPECT_GT(cells.perCell->cells[1].emitted, 0.01 * power);
  EXPECT_GT(cells.perCell->cells[0].emitted, cells.perCell->cells[1].emitted);

  const SolveResult global = solveProgressive(s.scene, atlas, params.solver, gl, ctx);
  EXPECT_NEAR(global.energy.emitted, power, power * 1e-6);
  const std::vector<double> a = powerPerCell(s, atlas, cells.radiosity),
                            b = powerPerCell(s, atlas, global.radiosity);
  for (size_t c = 0; c < a.size(); ++c) {
    SCOPED_TRACE(s.cells.cells[c].name);
    EXPECT_GT(b[c], 0.0);
    EXPECT_NEAR(a[c] / b[c], 1.0, 0.08);
  }
}

}  // namespace
}  // namespace cpgi
