// The sky gather drawn towards the openings (radiosity/lightmap/sky_openings.h): the spherical rectangle's
// solid angle against its closed form and its directions inside it; a wall that sees the sky through two
// aligned doors (the IFC house's kitchen, issue 46) as smooth as a many-ray gather where 256 cosine rays
// are blotchy; and the openings' gather unbiased: the hole in a ceiling's form factor per texel, and the
// two doors' light the cosine gather's at many rays.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/lightmap/sky_light.h"
#include "radiosity/lightmap/sky_openings.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/radiosity/test_sky_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;
using testing::atlasAtDensity;

constexpr double kPi = std::numbers::pi;

// A wall in the plane z = `z` across x in [0, 3], y in [0, 2.5], with a door x in [1.2, 1.8], y in [0, 2];
// its normal +z (`towardsPlusZ`) or −z.
void addWallWithDoor(Scene& s, float z, bool towardsPlusZ, uint32_t m) {
  auto rect = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v) {
    towardsPlusZ ? addRect(s, o, u, v, m) : addRect(s, o, v, u, m);
  };
  rect({0, 0, z}, {1.2f, 0, 0}, {0, 2.5f, 0});
  rect({1.8f, 0, z}, {1.2f, 0, 0}, {0, 2.5f, 0});
  rect({1.2f, 2, z}, {0.6f, 0, 0}, {0, 0.5f, 0});
}

// Two rooms in a row, each 3 × 2.5 × 4 m, all faces inward: the front door (z = 0) opens onto the sky,
// the inner door (z = 4) lines up with it, and room B's back wall (z = 8) sees the outside only through
// both, in about 0.6 % of its cosine directions (the house's kitchen wall: 0.48 %). A uniform sky and
// ground of radiance 1.
struct TwoDoors {
  Scene scene;
  Scene backWall;  ///< room B's back wall alone: the texels gathered (the whole scene occludes)
  CellGraph rooms;
  TwoDoors() {
    const uint32_t m = addMaterial(scene, glm::vec3(0.5f));
    addWallWithDoor(scene, 0.0f, true, m);
    addWallWithDoor(scene, 4.0f, false, m);
    addWallWithDoor(scene, 4.0f, true, m);
    addRect(scene, {0, 0, 8}, {0, 2.5f, 0}, {3, 0, 0}, m);  // back wall, normal −z
    addRect(scene, {0, 0, 0}, {0, 2.5f, 0}, {0, 0, 8}, m);  // x = 0, normal +x
    addRect(scene, {3, 0, 0}, {0, 0, 8}, {0, 2.5f, 0}, m);  // x = 3, normal −x
    addRect(scene, {0, 0, 0}, {0, 0, 8}, {3, 0, 0}, m);     // floor, normal +y
    addRect(scene, {0, 2.5f, 0}, {3, 0, 0}, {0, 0, 8}, m);  // ceiling, normal −y
    addRect(backWall, {0, 0, 8}, {0, 2.5f, 0}, {3, 0, 0}, addMaterial(backWall, glm::vec3(0.5f)));
    scene.sky.kind = Sky::Kind::Uniform;
    scene.sky.zenithRadiance = scene.sky.groundRadiance = 1.0f;
    // The rooms' graph as the automatic decomposition gives it: the front door a portal from room A to
    // the outside, the inner door one from A to B.
    rooms.cells.resize(3);
    rooms.cells[0].name = "a", rooms.cells[1].name = "b", rooms.cells[2].name = "outside";
    PortalQuad front{.name = "portal:a:outside", .cellA = 0, .cellB = 2};
    front.corners = {glm::vec3(1.2f, 0, 0), glm::vec3(1.8f, 0, 0), glm::vec3(1.8f, 2, 0),
                     glm::vec3(1.2f, 2, 0)};
    computePortalFrame(front);
    if (front.normal.z > 0.0f) std::swap(front.corners[1], front.corners[3]), computePortalFrame(front);
    PortalQuad inner{.name = "portal:a:b", .cellA = 0, .cellB = 1};
    inner.corners = {glm::vec3(1.2f, 0, 4), glm::vec3(1.8f, 0, 4), glm::vec3(1.8f, 2, 4),
                     glm::vec3(1.2f, 2, 4)};
    computePortalFrame(inner);
    rooms.portals = {front, inner};
  }
};

const TwoDoors& twoDoors() {
  static const TwoDoors scene;
  return scene;
}

// The back wall's sky light per texel, gathered with `rays` directions a texel, drawn towards `openings`.
std::vector<float> backWallLight(const LightmapAtlas& atlas, int rays,
                                 const std::vector<SkyOpening>& openings) {
  Scene lit = twoDoors().scene;
  lit.sky.gatherRays = rays;
  Context ctx;
  DirectLight d;
  addSkyLight(lit.sky, RayScene(lit), atlas, d, ctx, std::chrono::steady_clock::time_point::max(), openings);
  std::vector<float> out;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (atlas.patch[t] >= 0) out.push_back(d.irradiance[t].g);
  return out;
}

// The root mean square of `got` − `truth` over the texels `truth` lights, relative to their mean light.
double relativeRmse(const std::vector<float>& got, const std::vector<float>& truth) {
  double square = 0.0, sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    if (truth[i] > 0.0f) square += std::pow(double(got[i]) - truth[i], 2.0), sum += truth[i], ++n;
  return n > 0 ? std::sqrt(square / double(n)) / (sum / double(n)) : 0.0;
}

double mean(const std::vector<float>& v) {
  double sum = 0.0;
  for (float x : v) sum += x;
  return v.empty() ? 0.0 : sum / double(v.size());
}

TEST(SkyOpenings, TheOutsidesPortalsFaceOutOfTheBuilding) {
  const std::vector<SkyOpening> openings = skyOpeningsOf(twoDoors().rooms, 0.05);
  ASSERT_EQ(openings.size(), 1u);  // the inner door joins two rooms
  const SkyOpening& o = openings[0];
  EXPECT_NEAR(o.outward.z, -1.0, 1e-9);
  EXPECT_NEAR(glm::length(o.edgeU) * glm::length(o.edgeV), 0.7 * 2.1, 1e-5);  // grown 5 cm a side
  EXPECT_NEAR(glm::dot(o.corner, o.outward), 0.0, 1e-6);                      // in the door's plane
  EXPECT_TRUE(skyOpeningsOf(CellGraph{}).empty());
}

// A rectangle 2a × 2b seen from a distance d on its axis subtends 4 asin(ab / √((a² + d²)(b² + d²))); the
// directions drawn land inside it, uniformly: as many in each quarter of its solid angle.
TEST(SkyOpenings, TheSphericalRectangleIsUniformInItsSolidAngle) {
  const double a = 0.3, b = 1.0, d = 4.0;
  const SkyOpening o{
      .corner = {-a, -b, 0}, .edgeU = {2 * a, 0, 0}, .edgeV = {0, 2 * b, 0}, .outward = {0, 0, 1}};
  const glm::dvec3 eye(0, 0, -d);
  const SphericalRectangle rect(eye, o);
  EXPECT_NEAR(rect.solidAngle(), 4.0 * std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d))), 1e-9);
  int quarter[4] = {0, 0, 0, 0};
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 dir = rect.sample((i + 0.5) / n, std::fmod(i * 0.6180339887, 1.0));
    ASSERT_TRUE(crosses(o, eye, dir)) << i;
    ++quarter[(dir.x > 0.0 ? 1 : 0) + (dir.y > 0.0 ? 2 : 0)];
  }
  for (int q : quarter) EXPECT_NEAR(q, n / 4, n / 40);
  EXPECT_FALSE(crosses(o, eye, glm::normalize(glm::dvec3(0.5, 0, 1))));
  EXPECT_FALSE(crosses(o, eye, glm::dvec3(0, 0, -1)));  // behind the eye
}

// The wall behind two aligned doors: 256 cosine rays give each lit texel 1 or 2 rays' worth of sky, a
// relative RMSE of 78 % against 4 096 rays; 256 drawn half towards the front door, 2.3 %.
TEST(SkyOpenings, AWallBehindTwoDoorsIsSmoothAt256Rays) {
  const std::vector<SkyOpening> openings = skyOpeningsOf(twoDoors().rooms);
  const LightmapAtlas atlas = atlasAtDensity(twoDoors().backWall, 8.0f);
  const std::vector<float> truth = backWallLight(atlas, 4096, openings);
  const double cosine = relativeRmse(backWallLight(atlas, 256, {}), truth);
  const double towards = relativeRmse(backWallLight(atlas, 256, openings), truth);
  EXPECT_GT(cosine, 0.4);
  EXPECT_LT(towards, 0.1);
  // The lit band is where lines through both doors meet the wall (x in 0.6–2.4 m): light there, none at
  // the wall's sides.
  size_t lit = 0;
  for (float e : truth) lit += e > 0.0f;
  EXPECT_GT(lit, truth.size() / 4);
  EXPECT_LT(lit, truth.size());
}

// Drawn towards the openings or by the cosine alone, the back wall gets the same light (the doors' clip of
// the front door costs rays, not light): 0.00699 and 0.00698 W/m² here; 16 384 cosine rays a texel hold
// the mean to about 1 %.
TEST(SkyOpenings, TheOpeningsGatherIsUnbiased) {
  const LightmapAtlas atlas = atlasAtDensity(twoDoors().backWall, 4.0f);
  const double cosine = mean(backWallLight(atlas, 16384, {}));
  const double towards = mean(backWallLight(atlas, 1024, skyOpeningsOf(twoDoors().rooms)));
  ASSERT_GT(cosine, 0.0);
  EXPECT_NEAR(towards, cosine, 0.03 * cosine);
}

// The floor of a box lit through a hole in its ceiling against π Lz F(point → hole) at 64 rays a texel:
// drawn towards the hole, a relative RMSE of 2.6 % (0.9 % at 256 rays, 0.3 % at 1 024); by the cosine
// alone 25 % (9 % at 256, 3 % at 1 024); the mean within 0.1 % either way; the same light every run.
TEST(SkyOpenings, ThroughAHoleInTheCeilingTheFloorIsTheFormFactorsAtFewRays) {
  Scene s = testing::boxOpenToTheSky(0.5f);
  s.sky.kind = Sky::Kind::Uniform, s.sky.zenithRadiance = 3.0f, s.sky.gatherRays = 64;
  const std::array<glm::dvec3, 4> hole = testing::skyHole();
  const std::vector<SkyOpening> openings = {
      {.corner = hole[0], .edgeU = hole[1] - hole[0], .edgeV = hole[3] - hole[0], .outward = {0, 1, 0}}};
  const LightmapAtlas atlas = atlasAtDensity(s, 8.0f);
  std::vector<float> exact;
  testing::forEachTexelOf(atlas, 0, [&](size_t t) {
    // F(point → square above it, facing it): Lambert's contour formula for a receiver of normal +y.
    const glm::dvec3 x(atlas.position[t]);
    double sum = 0.0;
    for (size_t i = 0; i < 4; ++i) {
      const glm::dvec3 a = hole[i] - x, b = hole[(i + 1) % 4] - x, c = glm::cross(a, b);
      sum += std::atan2(glm::length(c), glm::dot(a, b)) * c.y / glm::length(c);
    }
    exact.push_back(float(3.0 * std::abs(sum) / 2.0));  // π Lz F, F = |Σ| / 2π
  });
  auto floorLight = [&](const std::vector<SkyOpening>& towards) {
    Context ctx;
    DirectLight d;
    addSkyLight(s.sky, RayScene(s), atlas, d, ctx, std::chrono::steady_clock::time_point::max(), towards);
    std::vector<float> out;
    testing::forEachTexelOf(atlas, 0, [&](size_t t) { out.push_back(d.irradiance[t].r); });
    return out;
  };
  const std::vector<float> drawn = floorLight(openings);
  EXPECT_LT(relativeRmse(drawn, exact), 0.05);
  EXPECT_NEAR(mean(drawn), mean(exact), 0.01 * mean(exact));
  EXPECT_GT(relativeRmse(floorLight({}), exact), 0.15);
  EXPECT_EQ(floorLight(openings), drawn);  // the same directions every run, whatever the threads
}

// A texel under 96 skylights (a 12 × 8 grid of 1 m squares 1.5 m apart, 3 m over it), as a map's rooms open
// onto its sky through a hundred portals: only the openings whose bound on their weight could beat the 8
// kept set up their spherical rectangle (all 96 did: 7 µs a texel a pass on oa_dm2), and the openings and
// odds kept are those of setting up every one: the density of each direction the same.
TEST(SkyOpenings, AnOpeningThatCannotBeAmongTheKeptIsNotSetUp) {
  std::vector<SkyOpening> openings;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 8; ++j)
      openings.push_back({.corner = {i * 1.5 - 8.0, 3.0, j * 1.5 - 5.0},
                          .edgeU = {0, 0, 1},
                          .edgeV = {1, 0, 0},
                          .outward = {0, 1, 0}});
  const glm::dvec3 eye(0.2, 0.0, 0.3), normal(0, 1, 0);
  const TexelOpenings towards(openings, eye, normal);
  EXPECT_LT(towards.rectanglesSetUp(), 32);
  // Every opening set up, the 8 of the largest solid angle × rise kept.
  std::vector<std::pair<double, size_t>> weights;
  for (size_t i = 0; i < openings.size(); ++i) {
    const SkyOpening& o = openings[i];
    double rise = -1.0;
    for (const glm::dvec3& c : {o.corner, o.corner + o.edgeU, o.corner + o.edgeV,
                                o.corner + o.edgeU + o.edgeV, o.corner + 0.5 * (o.edgeU + o.edgeV)})
      rise = std::max(rise, glm::dot(glm::normalize(c - eye), normal));
    weights.push_back({SphericalRectangle(eye, o).solidAngle() * std::max(rise, 0.1), i});
  }
  std::sort(weights.begin(), weights.end(), [](auto& a, auto& b) { return a.first > b.first; });
  weights.resize(TexelOpenings::kMostOpenings);
  double total = 0.0;
  for (const auto& w : weights) total += w.first;
  auto pdfOfAll = [&](const glm::dvec3& dir) {
    double p = 0.0;
    for (const auto& [w, i] : weights)
      if (crosses(openings[i], eye, dir)) p += w / total / SphericalRectangle(eye, openings[i]).solidAngle();
    return p;
  };
  int through = 0;
  for (int k = 0; k < 400; ++k) {
    const double u = (k + 0.5) / 400.0, v = std::fmod(k * 0.6180339887, 1.0),
                 w = std::fmod(k * 0.7548776662, 1.0);
    const glm::dvec3 drawn = towards.sample(u, v, w);
    // and a direction over the whole hemisphere, most of them through no kept opening
    const double phi = 2.0 * kPi * v, r = std::sqrt(w);
    const glm::dvec3 any(r * std::cos(phi), std::sqrt(1.0 - w), r * std::sin(phi));
    for (const glm::dvec3& dir : {drawn, any}) {
      const double expected = pdfOfAll(dir);
      through += expected > 0.0;
      EXPECT_NEAR(towards.pdf(dir), expected, 1e-9 * (1.0 + expected)) << k;
    }
  }
  EXPECT_GT(through, 400);
}

}  // namespace
}  // namespace cpgi
