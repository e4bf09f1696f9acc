// Small coplanar patches shot together (radiosity/cpu/shooter_clusters.h): which patches a cluster holds,
// and that one shot of a cluster gives each receiver the light of its patches shot one by one.
#include "radiosity/cpu/shooter_clusters.h"

#include <array>
#include <map>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/radiosity/test_sky_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

struct Court {
  Scene scene = testing::tiledCourt(8, 0.6f);
  Context ctx;
  LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.density = 8.0f}, ctx);
};

glm::vec3 chartCentre(const Patch& p) {
  return p.origin + 0.5f * (float(p.w) * p.texelU + float(p.h) * p.texelV);
}

// The corners of a patch's chart.
std::array<glm::vec3, 4> chartCorners(const Patch& p) {
  const glm::vec3 u = float(p.w) * p.texelU, v = float(p.h) * p.texelV;
  return {p.origin, p.origin + u, p.origin + v, p.origin + u + v};
}

// Every cluster's patches face one way on one plane, in a box of half-diagonal at most the radius; the
// 0.25 m tiles group by blocks of their neighbours; an excluded patch (a portal) shoots alone.
TEST(ShooterClusters, SmallCoplanarNeighboursWithinTheRadius) {
  const Court c;
  ASSERT_EQ(c.atlas.patches.size(), 320u);
  std::vector<uint8_t> exclude(c.atlas.patches.size(), 0);
  exclude[5] = 1;
  const ShooterClusterParams params;
  const ShooterClusters clusters = clusterShooters(c.atlas, params, exclude);
  ASSERT_EQ(clusters.clusterOf.size(), c.atlas.patches.size());
  EXPECT_LT(clusters.members.size(), c.atlas.patches.size() / 3);
  EXPECT_EQ(clusters.members[size_t(clusters.clusterOf[5])], std::vector<int32_t>{5});
  size_t members = 0;
  for (size_t k = 0; k < clusters.members.size(); ++k) {
    const std::vector<int32_t>& m = clusters.members[k];
    members += m.size();
    const Patch& first = c.atlas.patches[size_t(m.front())];
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (int32_t q : m) {
      EXPECT_EQ(clusters.clusterOf[size_t(q)], int32_t(k));
      const Patch& p = c.atlas.patches[size_t(q)];
      EXPECT_GT(glm::dot(p.normal, first.normal), params.normalCosine);
      EXPECT_LE(std::abs(glm::dot(first.normal, chartCentre(p) - chartCentre(first))), params.planeGap);
      for (const glm::vec3& corner : chartCorners(p)) lo = glm::min(lo, corner), hi = glm::max(hi, corner);
    }
    EXPECT_LE(0.5f * glm::length(hi - lo), params.radius + 1e-5f);
  }
  EXPECT_EQ(members, c.atlas.patches.size());
  // Radius 0: every patch alone.
  EXPECT_EQ(clusterShooters(c.atlas, {.radius = 0.0f}).members.size(), c.atlas.patches.size());
}

// The floor lit evenly; one cluster of floor tiles shot at once against its tiles shot one by one: each
// wall gathers the same light within 3 % (averaged over eight eye draws each), the whole within 1 %.
TEST(ShooterClusters, AClusterShotGivesEachWallTheLightOfItsPatchesShotAlone) {
  const Court c;
  const RayScene rays(c.scene);
  const RayShotScene shots(c.scene, c.atlas, rays);
  const auto layouts = layoutShooters(c.scene, c.atlas, {});
  const ShooterClusters clusters = clusterShooters(c.atlas, {});
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  // The largest cluster of floor tiles.
  std::vector<int32_t> cluster;
  for (const std::vector<int32_t>& m : clusters.members)
    if (glm::dot(c.atlas.patches[size_t(m.front())].normal, up) > 0.9f && m.size() > cluster.size())
      cluster = m;
  ASSERT_GE(cluster.size(), 4u);
  std::vector<glm::vec3> residual(c.atlas.texelCount(), glm::vec3(0.0f));
  for (size_t t = 0; t < c.atlas.texelCount(); ++t)
    if (c.atlas.patch[t] >= 0 && glm::dot(c.atlas.normal[t], up) > 0.9f) residual[t] = glm::vec3(1.0f);

  // Per wall (by its normal), the power gathered (R), summed over `draws` shots' averages.
  using Walls = std::map<std::tuple<int, int, int>, double>;
  const auto addGain = [&](const RayShotGain& g, double weight, Walls& walls) {
    for (size_t k = 0; k < shots.texels.size(); ++k) {
      const uint32_t t = shots.texels[k];
      const glm::ivec3 n = glm::ivec3(glm::round(c.atlas.normal[t]));
      walls[{n.x, n.y, n.z}] += weight * double(g.irradiance[k].r) * c.atlas.area[t];
    }
  };
  const int draws = 8;
  Walls together, alone;
  std::vector<ShotMember> members;
  for (int32_t q : cluster) members.push_back({q, &layouts[size_t(q)]});
  for (int d = 0; d < draws; ++d) {
    addGain(shootByRays(shots, members, residual, uint32_t(d + 1), {}), 1.0 / draws, together);
    for (int32_t q : cluster)
      addGain(shootByRays(shots, q, layouts[size_t(q)], residual, uint32_t(d + 1), {}), 1.0 / draws, alone);
  }
  double sumTogether = 0.0, sumAlone = 0.0;
  int walls = 0;
  for (const auto& [n, power] : alone) {
    if (std::get<1>(n) != 0) continue;  // the floor: coplanar with the shooters, nothing
    ++walls;
    EXPECT_NEAR(together[n] / power, 1.0, 0.03)
        << "wall facing " << std::get<0>(n) << ", " << std::get<1>(n) << ", " << std::get<2>(n);
    sumTogether += together[n], sumAlone += power;
  }
  EXPECT_EQ(walls, 4);
  EXPECT_NEAR(sumTogether / sumAlone, 1.0, 0.01);
}

}  // namespace
}  // namespace cpgi
