// Faces that run through other solids (scenes/contact_scenes.h; mapAtlas's sides): the side a solid closes
// off stays black, at one level and at two, on the GL engine and on the rays.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "core/contact_cuts.h"
#include "core/sky.h"
#include "radiosity/bake/bake.h"
#include "radiosity/lightmap/lightmap_sampling.h"
#include "radiosity/reference/reference_tracer.h"
#include "scenes/contact_scenes.h"
#include "scenes/scene_builder.h"
#include "tests/support/in_process_bake.h"

namespace cpgi {
namespace {

// The centre of texel t's part of its chart: where it lies, whatever point it was lit at.
glm::vec3 texelCentre(const LightmapAtlas& a, size_t t) {
  const Patch& p = a.patches[size_t(a.patch[t])];
  const int i = int(t % size_t(a.width)) - p.x, j = int(t / size_t(a.width)) - p.y;
  return p.origin + (float(i) + 0.5f) * p.texelU + (float(j) + 0.5f) * p.texelV;
}

// Area-weighted mean radiosity (mean of R, G, B) of the valid, non-emissive texels whose centre `dark`
// says lies on the closed-off side, and of the others.
struct Sides {
  double dark = 0.0, lit = 0.0;
};
template <class InDark>
Sides meanLight(const BakeResult& r, InDark dark) {
  double sum[2] = {0.0, 0.0}, area[2] = {0.0, 0.0};
  for (size_t t = 0; t < r.radiosity.size(); ++t) {
    if (r.atlas.patch[t] < 0 || r.atlas.emission[t] != glm::vec3(0.0f)) continue;
    const int side = dark(texelCentre(r.atlas, t)) ? 0 : 1;
    const glm::vec3 b = r.radiosity[t];
    sum[side] += double(b.r + b.g + b.b) / 3.0 * r.atlas.area[t];
    area[side] += r.atlas.area[t];
  }
  return {area[0] > 0.0 ? sum[0] / area[0] : -1.0, area[1] > 0.0 ? sum[1] / area[1] : -1.0};
}

struct Case {
  Backend backend;
  bool twoLevels;
};

std::string caseName(const testing::TestParamInfo<Case>& info) {
  return std::string(info.param.backend == Backend::Gl ? "Gl" : "Rays") +
         (info.param.twoLevels ? "TwoLevels" : "OneLevel");
}

BakeSettings settingsFor(const Case& c) {
  BakeSettings s;
  s.solver.backend = c.backend;
  s.solver.ambient = false;  // the unshot power spread evenly would light the dark side too
  if (!c.twoLevels) s.solver.solveDensity = 0.0f;
  s.output.views.width = 32;
  return s;
}

class SolidContacts : public testing::TestWithParam<Case> {};

// The room behind a 2 cm pane, its reveal running through the pane, under a sun outside: every texel in
// the room (the reveal's room-side strip with it) stays black. Interpolated from the coarse texel that
// straddles the pane, the strip took the sunlit side's light at two levels (0.0043 W/m² over the room
// against 72 outside).
TEST_P(SolidContacts, ARoomBehindAPaneItsRevealRunsThroughStaysBlackUnderTheSun) {
  SeedScene pane = makePaneRoom(true);
  SkyRequest sun;
  sun.towardsSun = glm::vec3(0.3f, 1.0f, 0.2f);
  sun.sunIrradiance = 500.0f;
  applySky(sun, pane.scene);
  const BakeResult r = test::bakeHere(pane.scene, pane.cells, settingsFor(GetParam()));
  const Sides light = meanLight(r, [](const glm::vec3& x) {
    return x.x > 0.0f && x.x < 4.0f && x.y > 0.0f && x.y < 3.0f && x.z > 0.0f && x.z < 4.09f;
  });
  ASSERT_GT(light.lit, 10.0);  // the outside in the sun
  EXPECT_LT(light.dark, 1e-6 * light.lit) << "outside " << light.lit;
}

INSTANTIATE_TEST_SUITE_P(BothEnginesBothLevels, SolidContacts,
                         testing::Values(Case{Backend::Gl, false}, Case{Backend::Gl, true},
                                         Case{Backend::Rays, false}, Case{Backend::Rays, true}),
                         caseName);

// The lightmap as an engine reads it at `x` on the face that faces `normal`: the triangle under the point,
// its atlas coordinates interpolated, the bilinear lookup between texel centres, the gutters filled as the
// written lightmap's are. -1 where no triangle holds the point.
class LookedUp {
 public:
  LookedUp(const Scene& scene, const BakeResult& r) : scene_(scene), r_(r), light_(r.radiosity) {
    dilate(r.atlas, light_);
  }
  double operator()(glm::vec3 x, glm::vec3 normal) const {
    for (size_t i = 0; i < scene_.triangles.size(); ++i) {
      const Triangle& t = scene_.triangles[i];
      if (glm::dot(t.geometricNormal(), normal) < 0.99f || std::abs(glm::dot(x - t.p[0], normal)) > 1e-4f)
        continue;
      const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0], q = x - t.p[0];
      const float d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
      const float d20 = glm::dot(q, e1), d21 = glm::dot(q, e2), den = d00 * d11 - d01 * d01;
      const float v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den, u = 1.0f - v - w;
      if (u < -1e-5f || v < -1e-5f || w < -1e-5f) continue;
      const auto& uv = r_.atlas.triangleUV[i];
      const glm::vec3 b =
          sampleBilinear(r_.atlas.width, r_.atlas.height, light_, u * uv[0] + v * uv[1] + w * uv[2]);
      return double(b.r + b.g + b.b) / 3.0;
    }
    return -1.0;
  }

 private:
  const Scene& scene_;
  const BakeResult& r_;
  std::vector<glm::vec3> light_;
};

// A contact scene baked on the rays at one level, with its faces cut at the contacts or left whole.
BakeResult bakeContacts(SeedScene& s, bool cut) {
  if (cut) cutAtContacts(s.scene, s.cells);
  return test::bakeHere(s.scene, s.cells, settingsFor(Case{Backend::Rays, false}));
}

// The strip along the pane: the reveal's soffit read 1 cm on the room's side of the pane, where the lookup
// of a chart running through the pane mixed the sunlit outside's texels into the black room's (0.3 of the
// outside's light on whole faces). Cut at the pane, the room's piece ends there with its own gutter.
TEST(ContactStrip, TheRevealOnTheRoomsSideOfThePaneStaysBlackUpToThePane) {
  double strip[2] = {0.0, 0.0};
  for (const bool cut : {false, true}) {
    SeedScene pane = makePaneRoom(true);
    SkyRequest sun;
    sun.towardsSun = glm::vec3(0.3f, 1.0f, 0.2f);
    sun.sunIrradiance = 500.0f;
    applySky(sun, pane.scene);
    const BakeResult r = bakeContacts(pane, cut);
    const LookedUp at(pane.scene, r);
    const glm::vec3 soffit(0.0f, -1.0f, 0.0f);
    const double lit = at({2.0f, 2.0f, 4.16f}, soffit), nearLine = at({2.0f, 2.0f, 4.08f}, soffit),
                 away = at({2.0f, 2.0f, 4.03f}, soffit);
    ASSERT_GT(lit, 10.0) << "cut " << cut;  // the outside in the sun
    strip[cut] = nearLine / lit;
    std::printf("pane-through, cut %d: soffit 1 cm from the pane %.4g, 6 cm %.4g, outside %.4g W/m2\n", cut,
                nearLine, away, lit);
    if (cut) {
      EXPECT_LT(nearLine, 1e-3 * lit) << "6 cm from the pane " << away;
    }
  }
  EXPECT_GT(strip[0], 0.05) << "the whole reveal's lookup no longer crosses the pane: the test shows nothing";
}

// The value of the texel whose centre lies nearest `x` on the face facing `normal`, among those `keep` takes.
template <class Keep>
double nearestTexel(const BakeResult& r, glm::vec3 x, glm::vec3 normal, Keep keep) {
  double best = 1e30, value = -1.0;
  for (size_t t = 0; t < r.radiosity.size(); ++t) {
    if (r.atlas.patch[t] < 0 || glm::dot(r.atlas.normal[t], normal) < 0.99f) continue;
    const glm::vec3 c = texelCentre(r.atlas, t);
    if (std::abs(glm::dot(c - x, normal)) > 1e-3f || !keep(c)) continue;
    if (const double d = glm::length(c - x); d < best)
      best = d, value = double(r.radiosity[t].r + r.radiosity[t].g + r.radiosity[t].b) / 3.0;
  }
  return value;
}

// The strips where a wall runs through a slab: the fin's face 2 cm under the lower ceiling read as an engine
// reads it, against its nearest texel in the room (whole, the lookup took the black of the texels centred
// inside the slab into a band under the ceiling), and 2 cm above the upper floor, where the storey stays
// black.
TEST(ContactStrip, TheFinThroughTheSlabHasNoBandAtTheCeilingAndNoLightAboveTheFloor) {
  double band[2] = {0.0, 0.0};
  for (const bool cut : {false, true}) {
    SeedScene slab = makeStoreysThroughSlab();
    const BakeResult r = bakeContacts(slab, cut);
    const LookedUp at(slab.scene, r);
    const glm::vec3 fin(-1.0f, 0.0f, 0.0f), under(1.95f, 2.98f, 2.0f);
    const double looked = at(under, fin), above = at({1.95f, 3.22f, 2.0f}, fin);
    const double texel = nearestTexel(r, under, fin, [](const glm::vec3& c) { return c.y < 3.0f; });
    ASSERT_GT(texel, 0.5) << "cut " << cut;
    band[cut] = looked / texel;
    std::printf(
        "slab-through, cut %d: fin 2 cm under the ceiling %.4g, its nearest texel in the room %.4g, "
        "2 cm above the floor %.4g W/m2\n",
        cut, looked, texel, above);
    if (cut) {
      EXPECT_LT(above, 1e-3 * texel);
    }
  }
  EXPECT_GT(band[1], 0.95);
  EXPECT_LT(band[0], 0.85)
      << "the whole fin's lookup no longer reaches into the slab: the test shows nothing";
}

// A 4 x 2.6 x 4 m room lit by a 1 x 1 m panel under its ceiling, a cabinet standing on its floor and a
// wardrobe against its west wall (x = 0), both boxes without a bottom as furniture comes.
SeedScene makeFurnishedRoom() {
  SeedScene s;
  SceneBuilder b(s.scene);
  const uint32_t white = b.material("white", glm::vec3(0.7f)), wood = b.material("wood", glm::vec3(0.4f));
  const uint32_t lamp = b.material("lamp", glm::vec3(0.8f), glm::vec3(60.0f));
  SceneBuilder::Room room;
  room.name = "room";
  room.hi = {4.0f, 2.6f, 4.0f};
  room.floor = room.ceiling = room.south = room.north = room.west = room.east = white;
  b.room(room);
  b.quad({1.5f, 2.59f, 1.5f}, {1.0f, 0, 0}, {0, 0, 1.0f}, lamp, b.node("room/lamp"));  // facing down
  b.boxOnFloor({2.2f, 0.0f, 1.2f}, {3.2f, 0.8f, 1.8f}, wood, b.node("room/cabinet"));
  b.boxOnFloor({0.0f, 0.0f, 2.4f}, {0.6f, 2.0f, 3.6f}, wood, b.node("room/wardrobe"));
  return s;
}

// The dark halo round a foot: the floor 1, 2 and 5 cm off the cabinet's and the wardrobe's feet and the wall
// 2 cm above the wardrobe, read as an engine reads the lightmap, against the path-traced light at those
// points. A whole floor's lookup there takes the black of its texels under the furniture; cut along the
// foot, the floor's chart ends there with its own gutter.
TEST(ContactStrip, TheFloorRoundAFurnituresFootHasNoDarkHalo) {
  const glm::vec3 up(0, 1, 0), east(1, 0, 0);
  struct Probe {
    glm::vec3 x, normal;
  };
  std::vector<Probe> probes;
  for (const float d : {0.01f, 0.02f, 0.05f, 0.2f}) {
    probes.push_back({{2.7f, 0.0f, 1.8f + d}, up});    // north of the cabinet
    probes.push_back({{0.6f + d, 0.0f, 3.0f}, up});    // east of the wardrobe
    probes.push_back({{0.0f, 2.0f + d, 3.0f}, east});  // the wall above the wardrobe
  }
  SeedScene truth = makeFurnishedRoom();
  std::vector<SamplePoint> points;
  for (const Probe& p : probes) points.push_back({p.x + 1e-4f * p.normal, p.normal, glm::vec3(0.7f)});
  ReferenceParams refParams;
  refParams.spp = 1024;
  Context ctx;
  const ReferenceResult ref = traceReference(truth.scene, points, refParams, ctx);
  double worst[2] = {0.0, 0.0};  // the largest shortfall against the reference, whole and cut
  for (const bool cut : {false, true}) {
    SeedScene room = makeFurnishedRoom();
    if (cut) cutAtContacts(room.scene, room.cells);
    BakeSettings settings = settingsFor(Case{Backend::Rays, false});
    settings.atlas.densityAuto = false;  // 10 texels a metre: a halo of half a texel, 5 cm
    const BakeResult r = test::bakeHere(room.scene, room.cells, settings);
    const LookedUp at(room.scene, r);
    for (size_t k = 0; k < probes.size(); ++k) {
      const double looked = at(probes[k].x, probes[k].normal);
      const double truthAt = double(ref.radiosity[k].r + ref.radiosity[k].g + ref.radiosity[k].b) / 3.0;
      ASSERT_GT(looked, 0.0) << "cut " << cut << ": no face holds probe " << k;
      std::printf(
          "furnished room, cut %d, probe %zu (%.2f, %.2f, %.2f): looked up %.4g, traced %.4g (%.3f)\n", cut,
          k, probes[k].x.x, probes[k].x.y, probes[k].x.z, looked, truthAt, looked / truthAt);
      if (k < 9) worst[cut] = std::max(worst[cut], 1.0 - looked / truthAt);
    }
  }
  EXPECT_GT(worst[0], 0.3) << "the whole floor's lookup shows no halo: the test shows nothing";
  EXPECT_LT(worst[1], 0.15);
}

}  // namespace
}  // namespace cpgi
