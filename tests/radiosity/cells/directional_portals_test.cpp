// Portal models (CellSolveParams::portals) and the spot through a door (scenes/stability_scenes.h): the
// lights' first shot goes over the whole scene (radiosity/cells/cell_first_shot.h), so with either model
// the pool of light lands on B's far wall where the solve of the whole scene puts it; directional portals
// keep the energy bookkeeping per cell and per portal of the diffuse ones.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/error.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/solve/emission_lobes.h"
#include "scenes/seed_scenes.h"
#include "scenes/stability_scenes.h"
#include "tests/radiosity/cells/cell_energy_check.h"

namespace cpgi {
namespace {

constexpr int kTexels = 8;
constexpr double kUnshot = 1e-3;

struct SpotDoor {
  SeedScene s = makeSpotThroughDoor();
  Context ctx;
  EglContext context{ctx};
  GlShotEngine gl{context};
  LightmapAtlas atlas;
  std::vector<glm::vec3> global;
  SpotDoor() {
    AtlasParams ap;
    ap.texelsPerQuad = kTexels;
    atlas = buildAtlas(s.scene, findQuads(s.scene), ap, ctx);
    SolverParams sp;
    sp.itemBuffer = 256;
    sp.unshotFraction = kUnshot;
    // The thesis's fixed eyes, where these portal comparisons were measured (as the cells' solves
    // below): they compare the portal modes, not the eyes (bench/RESULTS.md, issue 11).
    sp.jitteredEyes = false;
    global = solveProgressive(s.scene, atlas, sp, gl, ctx).radiosity;
  }
  SolveResult cells(PortalLight portals) {
    CellSolveParams p;
    p.atlas.texelsPerQuad = kTexels;
    p.solver.itemBuffer = 256;
    p.solver.unshotFraction = kUnshot;
    p.solver.jitteredEyes = false;
    p.portals = portals;
    return solveCells(s.scene, s.cells, atlas, p, gl, ctx);
  }
};

// Room B's far wall (x = 8.2 m, facing −x), where the beam lands.
bool farWall(const LightmapAtlas& a, size_t i) {
  return a.patch[i] >= 0 && a.position[i].x > 8.0f && a.normal[i].x < -0.99f;
}

struct Pool {
  double power = 0.0;      ///< W (R + G + B) on the far wall
  glm::dvec2 centre{0.0};  ///< power-weighted (y, z), m
  double relError = 0.0;   ///< area-weighted relative RMSE against `reference` over the far wall
};
Pool pool(const LightmapAtlas& a, const std::vector<glm::vec3>& b, const std::vector<glm::vec3>& reference) {
  Pool p;
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < a.texelCount(); ++i) {
    if (!farWall(a, i)) continue;
    const double w = (double(b[i].r) + b[i].g + b[i].b) * a.area[i];
    p.power += w;
    p.centre += w * glm::dvec2(a.position[i].y, a.position[i].z);
    const glm::dvec3 d = glm::dvec3(b[i]) - glm::dvec3(reference[i]);
    num += glm::dot(d, d) * a.area[i];
    den += glm::dot(glm::dvec3(reference[i]), glm::dvec3(reference[i])) * a.area[i];
  }
  p.centre /= p.power;
  p.relError = std::sqrt(num / den);
  return p;
}

using testing::expectConserved;

TEST(DirectionalPortals, BeamLandsWhereTheWholeSceneSolvePutsIt) {
  SpotDoor d;
  const SolveResult diffuse = d.cells(PortalLight::Diffuse);
  const SolveResult directional = d.cells(PortalLight::Directional);
  const Pool g = pool(d.atlas, d.global, d.global);
  const Pool pd = pool(d.atlas, diffuse.radiosity, d.global);
  const Pool pr = pool(d.atlas, directional.radiosity, d.global);
  std::printf(
      "far wall: global %.3f W at (%.3f, %.3f); diffuse %.3f W at (%.3f, %.3f) err %.3f; "
      "directional %.3f W at (%.3f, %.3f) err %.3f\n",
      g.power, g.centre.x, g.centre.y, pd.power, pd.centre.x, pd.centre.y, pd.relError, pr.power, pr.centre.x,
      pr.centre.y, pr.relError);
  // The same light crosses the door either way (the portal collects it the same way).
  EXPECT_NEAR(directional.perCell->portals[0].aToB, diffuse.perCell->portals[0].aToB,
              0.02 * diffuse.perCell->portals[0].aToB);
  // When the beam crossed the door as portal light, a diffuse portal spread it over room B: on 45483fb
  // diffuse 0.412 W on the far wall against 1.505 W in the whole-scene solve, its centre 0.34 m away
  // (error 0.889), directional 1.173 W 0.016 m away (error 0.266). Shot over the whole scene: measured
  // error 0.010 with either model, power +1.6 %, centre 0.6 cm away.
  for (const Pool& p : {pd, pr}) {
    EXPECT_LT(p.relError, 0.05);
    EXPECT_NEAR(p.power, g.power, 0.05 * g.power);
    EXPECT_LT(glm::length(p.centre - g.centre), 0.03);
  }
  expectConserved(directional);
}

// seed1: the lamp of A seen through the door is a wide cone, fitted as a narrow lobe plus a Lambertian.
// Sampled at texel centres, the narrow part lit door-jamb texels 5 cm from the portal up to 8.5 W/m²
// against 3.2 at most anywhere in the whole-scene solve; averaged over the receiver texel it must not.
TEST(DirectionalPortals, NoHotTexelsBesideTheDoor) {
  const SeedScene s = makeSeedScene(1);
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellSolveParams p;
  p.atlas.texelsPerQuad = kTexels;
  p.solver.itemBuffer = 256;
  p.portals = PortalLight::Directional;
  const LightmapAtlas atlas = buildAtlas(s.scene, findQuads(s.scene), p.atlas, ctx);
  const std::vector<glm::vec3> global = solveProgressive(s.scene, atlas, p.solver, gl, ctx).radiosity;
  const SolveResult cells = solveCells(s.scene, s.cells, atlas, p, gl, ctx);
  float globalMax = 0.0f, cellsMax = 0.0f;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0 && atlas.emission[i] == glm::vec3(0.0f))
      globalMax = std::max(globalMax, global[i].g), cellsMax = std::max(cellsMax, cells.radiosity[i].g);
  EXPECT_LT(cellsMax, 1.3f * globalMax);
  expectConserved(cells);
}

TEST(DirectionalPortals, RejectsABadLobeWidth) {
  const SeedScene s = makeSpotThroughDoor();
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellSolveParams p;
  p.atlas.texelsPerQuad = 4;
  p.portals = PortalLight::Directional;
  const LightmapAtlas atlas = buildAtlas(s.scene, findQuads(s.scene), p.atlas, ctx);
  for (float width : {0.0f, -0.1f, 0.5f}) {
    p.lobeMinWidth = width;
    EXPECT_THROW(solveCells(s.scene, s.cells, atlas, p, gl, ctx), InputError) << width;
  }
}

}  // namespace
}  // namespace cpgi
