// A small random floor plan (scenes/random_plans.h) baked in process, global and cell by cell, against
// the path-traced reference on the same atlas, room by room: the plan has rooms lit only through one and
// two openings, a window and coloured walls, which the project's own seed scenes do not. Coarse texels, a
// short reference and generous limits keep it to seconds; bench/plans_bench.py measures the distribution
// over many plans at the defaults.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "radiosity/bake/bake.h"
#include "radiosity/metrics/cell_metrics.h"
#include "radiosity/metrics/portal_seams.h"
#include "radiosity/reference/reference_tracer.h"
#include "scenes/random_plans.h"

namespace cpgi {
namespace {

// A three-room plan with a room two openings from its one lamp (checked below, so a change of the
// generator that moves it fails here rather than testing less).
constexpr uint64_t kSeed = 4;

BakeSettings coarse() {
  BakeSettings s;
  s.input.scene = "plan";
  s.atlas.densityAuto = false;
  s.atlas.params.density = 4.0f;
  s.solver.params.itemBuffer = 128;
  s.cells.params.portalBinRays = 256;
  return s;
}

// The plan, its global and cells bakes and one reference on their atlas (the same fixed density gives
// both bakes the same atlas), made once for the suite.
class RandomPlanBake : public testing::Test {
 protected:
  struct Runs {
    RandomPlan plan;
    SeedScene scene;
    BakeResult global, cells;
    ReferenceResult reference;
  };
  static void SetUpTestSuite() {
    runs_ = new Runs;
    runs_->plan = randomPlanLayout({kSeed, 3});
    runs_->scene = buildRandomPlan(runs_->plan);
    Context ctx;
    BakeSettings s = coarse();
    runs_->global = bake(runs_->scene.scene, runs_->scene.cells, s, ctx);
    s.cells.method = BakeMethod::Cells;
    runs_->cells = bake(runs_->scene.scene, runs_->scene.cells, s, ctx);
    ReferenceParams params;
    params.spp = 256;
    runs_->reference = traceReference(runs_->scene.scene, runs_->global.atlas, params, ctx);
  }
  static void TearDownTestSuite() { delete runs_; }
  static const Runs& runs() { return *runs_; }

  // Each room's figures against the reference, without the lamps.
  static std::vector<CellError> perRoom(const BakeResult& r) {
    const ReferenceResult& ref = runs().reference;
    std::vector<float> weight = r.atlas.area, sigma(weight.size());
    for (size_t i = 0; i < weight.size(); ++i) {
      if (glm::length(r.atlas.emission[i]) > 0.0f) weight[i] = 0.0f;
      sigma[i] = glm::length(ref.standardError[i]);
    }
    return compareCells(r.radiosity, ref.radiosity, weight, sigma, r.texelCell, {}, r.atlas.validTexels(),
                        r.cellNames);
  }

  static std::vector<PortalSeam> seams(const BakeResult& r, const std::vector<glm::vec3>& values) {
    std::vector<SeamPortal> portals;
    for (const PortalQuad& p : runs().scene.cells.portals) portals.push_back({p.name, p.corners});
    return measurePortalSeams({r.atlas.position, r.atlas.normal, values, r.atlas.area}, portals);
  }

  // Across every door with floor on both sides, `r`'s step is the reference's within their texel noise.
  static void expectStepsAsTheReferences(const BakeResult& r) {
    const std::vector<PortalSeam> bake = seams(r, r.radiosity), truth = seams(r, runs().reference.radiosity);
    int measured = 0;
    for (size_t i = 0; i < bake.size(); ++i) {
      if (!bake[i].measured || !truth[i].measured) continue;
      ++measured;
      EXPECT_LT(std::abs(bake[i].step - truth[i].step), std::max(bake[i].noise, truth[i].noise))
          << bake[i].name << ": " << bake[i].step << " against " << truth[i].step;
    }
    EXPECT_GE(measured, 2);
  }

 private:
  static Runs* runs_;
};
RandomPlanBake::Runs* RandomPlanBake::runs_ = nullptr;

TEST_F(RandomPlanBake, ThePlanHasARoomTwoOpeningsFromItsLampAndBothBakesOneAtlas) {
  const std::vector<int> d = openingsFromLamp(runs().plan);
  EXPECT_EQ(*std::max_element(d.begin(), d.end()), 2);
  ASSERT_EQ(runs().cells.atlas.area, runs().global.atlas.area);
}

// Every room within 6 % of the reference's mean and colour, its RMSE (the reference's noise taken out)
// under 35 %: generous at 4 texels a metre (measured: global +2.5 % and 23 % in R1, two openings from the
// lamp; binned portals -1.9 % and 9 %), but a room the portals starve or flood (the diffuse portal's +12 %
// behind a door, issue 47) or a leak through a wall reads outside it.
TEST_F(RandomPlanBake, EveryRoomOfTheGlobalAndTheCellsBakeIsNearTheReference) {
  for (const BakeResult* r : {&runs().global, &runs().cells}) {
    const std::string method = r->report["method"].get<std::string>();
    const std::vector<CellError> rooms = perRoom(*r);
    ASSERT_EQ(rooms.size(), runs().plan.rooms.size());
    for (const CellError& e : rooms) {
      const std::string what = method + " " + e.name;
      EXPECT_NEAR(e.ratioOfMeans, 1.0, 0.06) << what;
      EXPECT_LT(e.relRmseWithoutNoise, 0.35) << what << " (with the reference's noise " << e.relRmse << ")";
      EXPECT_NEAR(e.redGreenRatio, 1.0, 0.06) << what;
      EXPECT_NEAR(e.blueGreenRatio, 1.0, 0.06) << what;
    }
  }
}

// The seam measure on real bakes: the global bake's floor is one solve, so across every door its step is
// the reference's within their texel noise (the light's own fall-off across a door over a 0.25 m texel is
// in both).
TEST_F(RandomPlanBake, TheGlobalBakesFloorStepsAtTheDoorsAsTheReferences) {
  expectStepsAsTheReferences(runs().global);
}

// The cells bake's two sides of a door are solved in different cells, the floor running through: across
// every door its step is the reference's within their texel noise too (issue 47's seam; at 4 texels a
// metre the half-threshold's texels are too far from the plane for the near portal texels' sub-disks to
// matter: door_rows_test.cpp pins those at 10).
TEST_F(RandomPlanBake, TheCellsBakesFloorStepsAtTheDoorsAsTheReferences) {
  expectStepsAsTheReferences(runs().cells);
}

}  // namespace
}  // namespace cpgi
