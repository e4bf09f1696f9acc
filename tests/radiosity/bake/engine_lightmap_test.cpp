// The engine's lightmap (issue 48, item 1): lightmap_irradiance.exr holds the light arriving, E, so that
// E × albedo (+ emission) gives back lightmap.exr's radiosity per texel within 0.5 %, and its RGBM PNG
// decodes back within its quantisation.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "radiosity/lightmap/engine_lightmap.h"
#include "scenes/seed_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

TEST(EngineLightmap, IrradianceTimesAlbedoIsTheRadiosityOfEveryTexel) {
  test::TempDir dir;
  BakeSettings s = test::quickSeed1();
  s.output.folder = dir / "out";
  const SeedScene seed1 = makeSeedScene(1);
  const BakeResult r = test::bakeHere(seed1.scene, seed1.cells, s);
  const ImageRGB b = readExr(dir / "out/lightmap.exr");
  const ImageRGB e = readExr(dir / "out/lightmap_irradiance.exr");
  ASSERT_EQ(e.width, r.atlas.width);
  ASSERT_EQ(e.height, r.atlas.height);
  size_t checked = 0, emitters = 0;
  double worst = 0.0;
  for (size_t i = 0; i < r.atlas.texelCount(); ++i) {
    if (r.atlas.patch[i] < 0) continue;
    const glm::vec3 back = e.pixels[i] * r.atlas.albedo[i] + r.atlas.emission[i];
    for (int c = 0; c < 3; ++c) {
      const double want = b.pixels[i][c];
      ASSERT_GT(r.atlas.albedo[i][c], 0.0f);  // seed1 has no black surface: every channel is known
      const double error = std::abs(back[c] - want) / std::max(want, 1e-6);
      worst = std::max(worst, error);
      EXPECT_LE(error, 0.005) << "texel " << i << " channel " << c << ": " << back[c] << " against " << want;
    }
    ++checked;
    emitters += r.atlas.emission[i] != glm::vec3(0.0f);
  }
  EXPECT_EQ(checked, r.atlas.validTexels());
  EXPECT_GT(emitters, 0u);  // the lamps' texels are among them: E × ρ + Le
  std::cout << "worst relative difference of E x albedo + Le against B: " << worst << " over " << checked
            << " texels\n";

  std::ifstream in(dir / "out/report.json");
  const nlohmann::json report = nlohmann::json::parse(in)["engine_lightmap"];
  EXPECT_EQ(report["irradiance_exr"], "lightmap_irradiance.exr");
  EXPECT_EQ(report["unknown_irradiance_texels"], 0);
  float largest = 0.0f;
  for (size_t i = 0; i < e.pixels.size(); ++i)
    if (r.atlas.patch[i] >= 0) largest = std::max({largest, e.pixels[i].r, e.pixels[i].g, e.pixels[i].b});
  EXPECT_NEAR(report["max_irradiance"].get<double>(), largest, largest * 1e-3);  // half float's rounding
  // seed1's brightest texel is within RGBM's headroom over the glb's scale: nothing clips.
  EXPECT_NEAR(report["rgbm_range"].get<double>(), largest, largest * 1e-3);
  EXPECT_EQ(report["rgbm_clipped_area_fraction"], 0.0);
  EXPECT_GT(report["glb_lightmap_intensity"].get<double>(), 0.0);
  EXPECT_LE(report["glb_clipped_area_fraction"].get<double>(), 0.006);

  // The RGBM PNG: 8-bit RGBA (PNG colour type 6) of the atlas's size.
  std::ifstream png(dir / "out/lightmap_irradiance_rgbm.png", std::ios::binary);
  std::string header(26, '\0');
  ASSERT_TRUE(png.read(header.data(), 26));
  auto be32 = [&](size_t at) {
    return uint32_t(uint8_t(header[at])) << 24 | uint32_t(uint8_t(header[at + 1])) << 16 |
           uint32_t(uint8_t(header[at + 2])) << 8 | uint32_t(uint8_t(header[at + 3]));
  };
  EXPECT_EQ(be32(16), uint32_t(r.atlas.width));
  EXPECT_EQ(be32(20), uint32_t(r.atlas.height));
  EXPECT_EQ(header[24], 8);
  EXPECT_EQ(header[25], 6);
}

TEST(EngineLightmap, RgbmDecodesWithinItsQuantisation) {
  std::vector<glm::vec3> values;
  for (int i = 0; i < 4096; ++i) {
    const float level = std::pow(10.0f, -4.0f + 5.0f * float(i) / 4095.0f);  // 1e-4 … 10
    values.push_back(level *
                     glm::vec3(1.0f, 0.5f + 0.5f * std::sin(float(i)), 0.1f + 0.9f * float(i % 7) / 6.0f));
  }
  values.push_back(glm::vec3(0.0f));
  const float range = 10.0f;
  const RgbmImage rgbm = encodeRgbm(int(values.size()), 1, values, range);
  for (size_t i = 0; i < values.size(); ++i) {
    const glm::vec3 back = decodeRgbm(rgbm, i);
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(back[c], values[i][c], rgbmTolerance(rgbm, i)) << "value " << i << " channel " << c;
    // The multiplier follows the texel: a texel at a tenth of the range keeps its own 8 bits.
    const float peak = std::max({values[i].r, values[i].g, values[i].b});
    if (peak > range / 255.0f) {
      EXPECT_LE(rgbmTolerance(rgbm, i), peak * 2.1f / 255.0f) << i;
    }
  }
  EXPECT_EQ(decodeRgbm(rgbm, values.size() - 1), glm::vec3(0.0f));
  // Above the range: clipped to it, never wrapped.
  const RgbmImage clipped = encodeRgbm(1, 1, {glm::vec3(50.0f, 5.0f, 0.0f)}, range);
  EXPECT_NEAR(decodeRgbm(clipped, 0).r, range, 1e-5f);
  EXPECT_NEAR(decodeRgbm(clipped, 0).g, 5.0f, rgbmTolerance(clipped, 0));
}

TEST(EngineLightmap, AChannelWithoutAlbedoIsZeroAndCounted) {
  LightmapAtlas atlas;
  atlas.width = 3, atlas.height = 1;
  atlas.patch = {0, 0, -1};
  atlas.albedo = {glm::vec3(0.5f, 0.0f, 0.25f), glm::vec3(0.8f), glm::vec3(0.0f)};
  atlas.emission = {glm::vec3(0.0f), glm::vec3(10.0f, 0.0f, 0.0f), glm::vec3(0.0f)};
  atlas.area = {1.0f, 1.0f, 0.0f};
  const std::vector<glm::vec3> b = {glm::vec3(1.0f, 0.3f, 1.0f), glm::vec3(12.0f, 4.0f, 4.0f),
                                    glm::vec3(7.0f)};
  size_t unknown = 0;
  const std::vector<glm::vec3> e = irradianceFromRadiosity(atlas, b, &unknown);
  EXPECT_EQ(unknown, 1u);
  EXPECT_EQ(e[0], glm::vec3(2.0f, 0.0f, 4.0f));  // green: no albedo, no reading
  EXPECT_EQ(e[1], glm::vec3(2.5f, 5.0f, 5.0f));  // the emitter's own 10 W/m² is not light arriving
  EXPECT_EQ(e[2], glm::vec3(0.0f));              // padding
  const LightmapRange range = lightmapRange(atlas, e, 0.5);
  EXPECT_EQ(range.max, 5.0f);
  EXPECT_EQ(range.ldrScale, 4.0f);
  EXPECT_DOUBLE_EQ(range.clippedArea, 0.5);
  EXPECT_EQ(range.rgbmRange, 5.0f);  // within kRgbmHeadroom × 4
  EXPECT_DOUBLE_EQ(range.rgbmClippedArea, 0.0);
}

}  // namespace
}  // namespace cpgi
