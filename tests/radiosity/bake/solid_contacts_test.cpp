// Faces that run through other solids (scenes/contact_scenes.h; mapAtlas's sides): the side a solid closes
// off stays black, at one level and at two, on the GL engine and on the rays.
#include <string>

#include <gtest/gtest.h>

#include "core/sky.h"
#include "radiosity/bake/bake.h"
#include "scenes/contact_scenes.h"
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

}  // namespace
}  // namespace cpgi
