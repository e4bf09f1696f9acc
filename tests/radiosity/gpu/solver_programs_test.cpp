// Programs compiled once and reused (SolverPrograms): solves of different atlases and visibility modes
// interleaved on one program cache give exactly what fresh programs give (no uniform or program of one
// solve leaks into the next).
#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "scenes/seed_scenes.h"

namespace cpgi {
namespace {

TEST(SolverPrograms, ReusedProgramsGiveTheFreshResult) {
  const SeedScene s1 = makeSeedScene(1), s2 = makeSeedScene(2);
  Context ctx;
  EglContext gl(ctx);
  const LightmapAtlas a1 = buildAtlas(s1.scene, findQuads(s1.scene), AtlasParams{.texelsPerQuad = 4}, ctx);
  const LightmapAtlas a2 = buildAtlas(s2.scene, findQuads(s2.scene), AtlasParams{.texelsPerQuad = 3}, ctx);
  SolverParams cube, sphere;
  cube.itemBuffer = sphere.itemBuffer = 128;
  cube.unshotFraction = sphere.unshotFraction = 0.05;
  sphere.visibility = Visibility::Hemisphere;
  struct Case {
    const Scene* scene;
    const LightmapAtlas* atlas;
    const SolverParams* params;
  };
  const Case cases[] = {
      {&s1.scene, &a1, &cube}, {&s2.scene, &a2, &sphere}, {&s2.scene, &a2, &cube}, {&s1.scene, &a1, &sphere}};
  std::vector<SolveResult> fresh;
  for (const Case& c : cases) fresh.push_back(solveProgressive(*c.scene, *c.atlas, *c.params, gl, ctx));
  EXPECT_NE(fresh[0].radiosity, fresh[3].radiosity);  // the two modes differ, so mixing them would show
  // One engine keeps its programs from solve to solve.
  GlShotEngine engine(gl);
  for (int pass = 0; pass < 2; ++pass)
    for (size_t i = 0; i < std::size(cases); ++i) {
      const SolveResult r = solveProgressive(*cases[i].scene, *cases[i].atlas, *cases[i].params, engine, ctx);
      EXPECT_EQ(r.shots, fresh[i].shots) << i;
      EXPECT_EQ(r.shooters, fresh[i].shooters) << i;
      EXPECT_TRUE(r.radiosity == fresh[i].radiosity) << "case " << i << ", pass " << pass;
    }
}

}  // namespace
}  // namespace cpgi
