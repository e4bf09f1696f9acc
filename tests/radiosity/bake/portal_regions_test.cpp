// A portal in a thick wall shoots its light from between the reveals: a receiver off the opening's axis
// sees a strip of it hidden by a jamb. On the rays engine (the interreflection's at the defaults on
// llvmpipe) one eye for a 1 m visibility region gave every receiver that saw the eye the region's whole
// light, the hidden strip too, and a room lit through two or three doors came out several per cent bright
// cell by cell, where the global bake has no portal to shoot. Random plan 22 (the bench's, at the bake's
// defaults): its R5, lit through two openings, read +8.6 % against the reference cell by cell and +2.4 %
// globally (bench/RESULTS.md, "The portals' error").
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/scene_io.h"
#include "radiosity/bake/bake.h"

namespace cpgi {
namespace {

// Per room, the area-weighted mean radiosity (R + G + B) of its texels that do not emit.
std::vector<double> roomMeans(const BakeResult& r) {
  std::vector<double> light(r.cellNames.size(), 0.0), area(r.cellNames.size(), 0.0);
  for (size_t t = 0; t < r.radiosity.size(); ++t) {
    const int c = int(r.texelCell[t]);
    if (c < 0 || r.atlas.patch[t] < 0 || glm::length(r.atlas.emission[t]) > 0.0f) continue;
    const glm::vec3 b = r.radiosity[t];
    light[size_t(c)] += (double(b.r) + b.g + b.b) * r.atlas.area[t];
    area[size_t(c)] += r.atlas.area[t];
  }
  for (size_t c = 0; c < light.size(); ++c) light[c] = area[c] > 0.0 ? light[c] / area[c] : 0.0;
  return light;
}

TEST(PortalRegions, EveryRoomOfAPlanLitThroughDoorsInThickWallsIsTheGlobalBakesOnTheRaysEngine) {
  // Written and read back as the bench's plans are: baked as built in memory, the plan's R5 was within 3 %
  // of the global bake with the portals' regions or without (why not is not looked into).
  const std::filesystem::path glb = std::filesystem::path(testing::TempDir()) / "portal_regions_plan22.glb";
  const std::string generate = std::string(CPGI_BINARY) + " generate plan --seed 22 -o " + glb.string();
  ASSERT_EQ(std::system(generate.c_str()), 0);
  const LoadedScene plan = loadScene(glb.string());
  BakeSettings s;
  s.input.scene = "plan 22";
  s.solver.indirect = IndirectSolver::Rays;
  Context ctx;
  const BakeResult global = bake(plan.scene, plan.cells, s, ctx);
  s.cells.method = BakeMethod::Cells;
  s.cells.params.portals = PortalLight::Binned;
  const BakeResult cells = bake(plan.scene, plan.cells, s, ctx);
  ASSERT_EQ(global.cellNames, cells.cellNames);
  const std::vector<double> g = roomMeans(global), c = roomMeans(cells);
  // The reference's own spread in these rooms is 0.3–0.6 % (compare-light's reference_noise); the global
  // bake is within 2.4 % of it in every room. Before the portals' finer regions R5 read 6.2 % above the
  // global bake; every room is within 1.5 % of it with them.
  for (size_t k = 0; k < g.size(); ++k) {
    ASSERT_GT(g[k], 0.0) << cells.cellNames[k];
    EXPECT_NEAR(c[k] / g[k], 1.0, 0.03) << "room " << cells.cellNames[k];
  }
}

}  // namespace
}  // namespace cpgi
