// Random plan 22 (the bench's, at the bake's defaults: the interreflection on the rays engine, as on
// llvmpipe) baked globally and cell by cell, each room of the cells bake against the global one, which has
// no portal to shoot.
//  - A portal in a thick wall shoots its light from between the reveals: a receiver off the opening's axis
//    sees a strip of it hidden by a jamb. One eye for a 1 m visibility region gave every receiver that saw
//    the eye the region's whole light, the hidden strip too, and a room lit through two or three doors came
//    out several per cent bright cell by cell: R5, lit through two openings, read +8.6 % against the
//    reference cell by cell and +2.4 % globally (bench/RESULTS.md, "The portals' error").
//  - A binned portal re-emits its light in bins of direction (radiosity/solve/emission_bins.h). R7 is lit
//    through a door in a wall at right angles to its back wall, which sees the door only from 45–90° off
//    its normal; in bins of equal projected solid angle the outermost ring spanned 56–90°, and the back
//    wall showed a band +30 % beside one −30 % (bench/RESULTS.md, "The binned portals' bands").
//  - A portal texel re-emits one distribution of directions from its whole area. At the solve's 0.2 m,
//    R7's back wall still read a strip +30 % at the corner beside the door's wall and a band −15 % beside
//    it, and the room was 3.4 points of RMSE over the global bake's against the reference; with the
//    portals at twice the density, 0.0 (bench/RESULTS.md, "The portals' texels"); the back wall against
//    the global bake texel by texel 0.173 → 0.132, at 2.4× the cells' CPU: not the default.
#include <algorithm>
#include <cmath>
#include <cstdio>
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

class PortalRegions : public testing::Test {
 protected:
  struct Bakes {
    BakeResult global, cells;
  };
  static void SetUpTestSuite() {
    // Written and read back as the bench's plans are: baked as built in memory, the plan's R5 was within
    // 3 % of the global bake with the portals' regions or without (why not is not looked into).
    const std::filesystem::path glb = std::filesystem::path(testing::TempDir()) / "portal_regions_plan22.glb";
    const std::string generate = std::string(CPGI_BINARY) + " generate plan --seed 22 -o " + glb.string();
    ASSERT_EQ(std::system(generate.c_str()), 0);
    const LoadedScene plan = loadScene(glb.string());
    BakeSettings s;
    s.input.scene = "plan 22";
    s.solver.indirect = IndirectSolver::Rays;
    Context ctx;
    bakes_ = new Bakes;
    bakes_->global = bake(plan.scene, plan.cells, s, ctx);
    s.cells.method = BakeMethod::Cells;
    s.cells.params.portals = PortalLight::Binned;
    bakes_->cells = bake(plan.scene, plan.cells, s, ctx);
  }
  static void TearDownTestSuite() { delete bakes_; }
  static const Bakes& bakes() { return *bakes_; }

 private:
  static Bakes* bakes_;
};
PortalRegions::Bakes* PortalRegions::bakes_ = nullptr;

TEST_F(PortalRegions, EveryRoomOfAPlanLitThroughDoorsInThickWallsIsTheGlobalBakesOnTheRaysEngine) {
  ASSERT_EQ(bakes().global.cellNames, bakes().cells.cellNames);
  const std::vector<double> g = roomMeans(bakes().global), c = roomMeans(bakes().cells);
  // The reference's own spread in these rooms is 0.3–0.6 % (compare-light's reference_noise); the global
  // bake is within 2.4 % of it in every room. Before the portals' finer regions R5 read 6.2 % above the
  // global bake; every room is within 1.5 % of it with them.
  for (size_t k = 0; k < g.size(); ++k) {
    ASSERT_GT(g[k], 0.0) << bakes().cells.cellNames[k];
    EXPECT_NEAR(c[k] / g[k], 1.0, 0.03) << "room " << bakes().cells.cellNames[k];
  }
}

TEST_F(PortalRegions, TheWallBesideADoorAtRightAnglesIsTheGlobalBakesTexelByTexel) {
  // R7's back wall: its texels facing −z farthest along +z.
  const BakeResult &g = bakes().global, &c = bakes().cells;
  const auto r7 = std::find(c.cellNames.begin(), c.cellNames.end(), "R7");
  ASSERT_NE(r7, c.cellNames.end());
  const int cell = int(r7 - c.cellNames.begin());
  const LightmapAtlas& a = c.atlas;
  float back = -1e30f;
  for (size_t t = 0; t < a.texelCount(); ++t)
    if (int(c.texelCell[t]) == cell && a.patch[t] >= 0 && a.normal[t].z < -0.99f)
      back = std::max(back, a.position[t].z);
  double err = 0.0, norm = 0.0, wall = 0.0;
  for (size_t t = 0; t < a.texelCount(); ++t) {
    if (int(c.texelCell[t]) != cell || a.patch[t] < 0 || !(a.normal[t].z < -0.99f) ||
        a.position[t].z < back - 0.01f)
      continue;
    const glm::vec3 d = c.radiosity[t] - g.radiosity[t];
    err += double(glm::dot(d, d)) * a.area[t];
    norm += double(glm::dot(g.radiosity[t], g.radiosity[t])) * a.area[t];
    wall += a.area[t];
  }
  ASSERT_GT(wall, 5.0) << "m² of R7's back wall";
  const double rmse = std::sqrt(err / norm);
  std::printf("R7's back wall (%.1f m²): the cells bake's relative RMSE against the global bake %.3f\n", wall,
              rmse);
  // In bins of equal projected solid angle (12 × 12) it read 0.268; in rings of equal angle (18 × 18)
  // 0.173, the portals' texels at the solve's 0.2 m; at twice the density (CellSolveParams::
  // portalDensityScale, not the default) 0.132.
  EXPECT_LT(rmse, 0.21);
}

}  // namespace
}  // namespace cpgi
