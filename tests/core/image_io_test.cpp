// EXR round trips bit-exactly (extra channels too); PNG applies exposure and the sRGB curve.
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>
// A private decoder to check the PNG bytes independently of the encoder.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include "core/error.h"
#include "core/image_io.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

ImageRGB gradient(int w, int h) {
  ImageRGB img;
  img.width = w, img.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.pixels.push_back(glm::vec3(x * 0.37f + 1e-7f, y * 1234.5f, -0.125f * (x + y)));
  return img;
}

TEST(ImageIo, ExrRoundTripIsExactWithExtraChannels) {
  test::TempDir dir;
  const ImageRGB img = gradient(7, 5);
  ExrChannel area{"area", {}};
  for (int i = 0; i < 35; ++i) area.values.push_back(0.001f * i * i);
  writeExr(dir / "a.exr", img, {area});
  std::vector<ExrChannel> extra;
  const ImageRGB back = readExr(dir / "a.exr", &extra);
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  EXPECT_EQ(std::memcmp(back.pixels.data(), img.pixels.data(), img.pixels.size() * sizeof(glm::vec3)), 0);
  EXPECT_EQ(back.at(3, 0), img.at(3, 0));  // row 0 stays at the top
  ASSERT_EQ(extra.size(), 1u);
  EXPECT_EQ(extra[0].name, "area");
  EXPECT_EQ(extra[0].values, area.values);
}

TEST(ImageIo, ReadExrErrorsNameTheFile) {
  test::TempDir dir;
  std::ofstream(dir / "junk.exr") << "this is not an exr";
  for (const std::string& name : {std::string("junk.exr"), std::string("missing.exr")}) {
    try {
      readExr(dir / name);
      FAIL() << name;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), dir / name);
    }
  }
  try {
    readExr(dir.path().string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "is a directory, not an image");
  }
}

TEST(ImageIo, PngAppliesExposureAndSrgbCurve) {
  ImageRGB img;
  img.width = 4, img.height = 1;
  img.pixels = {glm::vec3(0.0f), glm::vec3(0.25f), glm::vec3(0.5f), glm::vec3(2.0f)};
  const std::string png = encodePng(img, 2.0f);
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                            int(png.size()), &w, &h, &n, 3);
  ASSERT_NE(px, nullptr);
  ASSERT_EQ(w, 4);
  ASSERT_EQ(h, 1);
  // exposure 2: 0 → 0; 0.25 → 0.5 → sRGB 0.7354 → 188; 0.5 → 1 → 255; 2 → clamped 255.
  EXPECT_EQ(px[0], 0);
  EXPECT_EQ(px[3], 188);
  EXPECT_EQ(px[6], 255);
  EXPECT_EQ(px[9], 255);
  stbi_image_free(px);

  test::TempDir dir;
  writePng(dir / "p.png", img);
  std::ifstream in(dir / "p.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes, encodePng(img));
}

}  // namespace
}  // namespace cpgi
