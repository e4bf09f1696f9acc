// Each view-NAME.png is exposed for what its camera sees: in seed1 the middle room, lit only through its
// doors, reads as well as the rooms with lamps (the 90th percentile of its lit pixels near 0.8 before the
// sRGB curve), while the EXRs keep the radiance. And --view-size.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

// The 90th percentile, over pixels that are not black, of the largest of R, G, B (0–255).
double percentile90(const std::string& png) {
  int w = 0, h = 0, n = 0;
  unsigned char* pixels = stbi_load(png.c_str(), &w, &h, &n, 3);
  if (!pixels) return -1.0;
  std::vector<int> values;
  for (int i = 0; i < w * h; ++i) {
    const int v = std::max({pixels[3 * i], pixels[3 * i + 1], pixels[3 * i + 2]});
    if (v > 0) values.push_back(v);
  }
  stbi_image_free(pixels);
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(0.9 * (values.size() - 1)), values.end());
  return values[size_t(0.9 * (values.size() - 1))];
}

TEST(ViewExposure, DimRoomReadsAsWellAsLitOnes) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb", out = dir / "out";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  BakeSettings s;  // in process: --texels-per-quad 8 --unshot 0.05
  s.input.scene = scene;
  s.output.folder = out;
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 8;
  s.solver.params.unshotFraction = 0.05;
  test::bakeHere(s);
  // 0.8 linear is 231 in sRGB; bilinear edges and rounding leave a few levels either way.
  const double expected = 255.0 * (1.055 * std::pow(0.8, 1.0 / 2.4) - 0.055);
  for (const char* view : {"A", "B", "C"})
    EXPECT_NEAR(percentile90(out + "/view-" + view + ".png"), expected, 8.0) << view;

  // The middle room is much darker in radiance: its exposure, not its light, was raised.
  auto radiance90 = [&](const char* view) {
    const ImageRGB image = readExr(out + "/view-" + view + ".exr");
    std::vector<float> values;
    for (const glm::vec3& p : image.pixels)
      if (std::max({p.x, p.y, p.z}) > 0.0f) values.push_back(std::max({p.x, p.y, p.z}));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(0.9 * (values.size() - 1)),
                     values.end());
    return values[size_t(0.9 * (values.size() - 1))];
  };
  EXPECT_LT(radiance90("B"), 0.5f * radiance90("A"));
}

// --view-size W×H sets the pictures' size (the vertical field of view stays the camera's); a bad size
// fails at once with one line naming the option.
TEST(ViewSize, PicturesHaveTheSizeAskedFor) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb", out = dir / "out";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  BakeSettings s;  // in process: --texels-per-quad 4 --unshot 0.3 --view-size 320x200
  s.input.scene = scene;
  s.output.folder = out;
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 4;
  s.solver.params.unshotFraction = 0.3;
  s.output.views.width = 320;
  s.output.views.height = 200;
  test::bakeHere(s);
  for (const char* view : {"A", "B", "C"}) {
    const ImageRGB image = readExr(out + "/view-" + view + ".exr");
    EXPECT_EQ(image.width, 320) << view;
    EXPECT_EQ(image.height, 200) << view;
  }
  for (const char* bad : {"10x10", "320", "320x200x3", "axb", "320x9000"}) {
    const test::CommandRun b = cpgi(
        dir, "bake " + quote(scene) + " -o " + quote(dir / "bad") + " --view-size " + quote(bad) + " -q");
    EXPECT_EQ(b.status, 1) << bad;
    ASSERT_EQ(b.errLines().size(), 1u) << b.err;
    EXPECT_NE(b.err.find("--view-size"), std::string::npos) << b.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad/report.json")) << bad;
  }
}

}  // namespace
}  // namespace cpgi
