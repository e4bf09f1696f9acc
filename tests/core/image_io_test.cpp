// EXR round trips bit-exactly (extra channels too); PNG applies exposure and the sRGB curve.
#include <algorithm>
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

// A small valid EXR whose header then lies about its data window (issue 49, item 9: a 10 KB lightmap.exr
// announcing 20000² pixels made view and compare-light allocate 4.7 GB before reading one).
std::string exrClaiming(const test::TempDir& dir, int32_t maxX, int32_t maxY) {
  writeExr(dir / "small.exr", gradient(4, 4), {{"area", std::vector<float>(16, 1.0f)}});
  std::ifstream in(dir / "small.exr", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string attribute("dataWindow\0box2i\0", 17);
  const size_t at = bytes.find(attribute);
  EXPECT_NE(at, std::string::npos);
  const size_t box = at + attribute.size() + 4;  // after the attribute's size: xMin yMin xMax yMax
  std::memcpy(&bytes[box + 8], &maxX, 4);
  std::memcpy(&bytes[box + 12], &maxY, 4);
  // Room for the table of chunk offsets the new size implies (16 rows a chunk), as in the round's 10 KB file,
  // so that OpenEXR opens it rather than stopping at a short table.
  bytes.append(std::min<size_t>(8 * (size_t(uint32_t(maxY)) / 16 + 1), 1 << 16), '\0');
  const std::string path = dir / "lying.exr";
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(ImageIo, ExrDataWindowIsCheckedAgainstALimitAndTheFileSizeBeforeAllocating) {
  test::TempDir dir;
  for (const bool withExtra : {false, true}) {
    std::vector<ExrChannel> extra;
    try {
      readExr(exrClaiming(dir, 7999, 7999), withExtra ? &extra : nullptr);
      ADD_FAILURE() << "read";
    } catch (const InputError& e) {
      EXPECT_NE(e.problem().find("OpenEXR data window 8000x8000 cannot be held in a file of "),
                std::string::npos)
          << e.problem();
    }
  }
  // Within the limit of pixels, but not in a file of 5 KB: the file's size tells the lie. Past the limit
  // (the round's 20000²), whatever the file's size: refused as OpenEXR opens it, or by cpgi's own count.
  try {
    readExr(exrClaiming(dir, 19999, 19999));
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "OpenEXR data window 20000x20000 holds more than the 134217728 pixels cpgi reads");
  }
  for (const auto& [x, y] :
       {std::pair{1 << 20, 0}, std::pair{20000, 20000}, std::pair{int32_t(2147483000), 3}}) {
    try {
      readExr(exrClaiming(dir, x, y));
      ADD_FAILURE() << x << " " << y;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), dir / "lying.exr");
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  EXPECT_EQ(readExr(dir / "small.exr").width, 4);
}

// OpenEXR allocates a header attribute at its declared size before reading it: a 500-byte file declaring
// an attribute of 2 GB (found by the exr fuzz target) is refused from the header walk, as are tiled files.
TEST(ImageIo, ExrHeaderAttributesMustFitInTheFile) {
  test::TempDir dir;
  writeExr(dir / "small.exr", gradient(4, 4));
  std::ifstream in(dir / "small.exr", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string lying = bytes;
  const std::string attribute("pixelAspectRatio\0float\0", 23);
  const size_t at = lying.find(attribute);
  ASSERT_NE(at, std::string::npos);
  const int32_t huge = 0x7ffff000;
  std::memcpy(&lying[at + attribute.size()], &huge, 4);
  std::ofstream(dir / "lying.exr", std::ios::binary) << lying;
  try {
    readExr(dir / "lying.exr");
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "OpenEXR header attribute 'pixelAspectRatio' runs past the end of the file");
  }
  std::string tiled = bytes;
  tiled[5] |= 0x02;
  std::ofstream(dir / "tiled.exr", std::ios::binary) << tiled;
  try {
    readExr(dir / "tiled.exr");
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("a tiled, deep or multi-part OpenEXR file"), std::string::npos) << e.problem();
  }
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
