// Texture images (issue 49, items 1-3): PNG and JPEG of every kind a glTF may hold decode through libpng
// and libjpeg-turbo to the right linear mean; other formats (the 16-bit PGM that made stb 2.27 over-read,
// the truncated run-length HDR that made it loop forever), truncated data and sizes over the limit are
// refused in one line naming the file and the image; an image used by a hundred materials decodes once.
// Every image is encoded here, by the same libraries' encoders.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include <jpeglib.h>
#include <png.h>

#include "core/error.h"
#include "core/scene_io.h"
#include "core/texture_image.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

// A PNG of `width` × `height` pixels whose samples are `samples` (row-major, as PNG lays them out for
// `colorType` and `bitDepth`; 16-bit samples big-endian).
std::string encodePng(int width, int height, int bitDepth, int colorType,
                      const std::vector<unsigned char>& samples, bool interlaced = false,
                      const std::vector<png_color>& palette = {}) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    ADD_FAILURE() << "libpng could not encode the test image";
    return {};
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep data, size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(data), n);
      },
      nullptr);
  png_set_IHDR(png, info, width, height, bitDepth, colorType,
               interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
  png_write_info(png, info);
  const size_t rowBytes = samples.size() / height;
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < height; ++y) rows[y] = const_cast<png_bytep>(samples.data() + rowBytes * y);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

// A JPEG of 8-bit RGB (or grey with components 1) pixels at the highest quality.
std::string encodeJpeg(int width, int height, int components, const std::vector<unsigned char>& pixels,
                       bool progressive = false) {
  jpeg_compress_struct c{};
  jpeg_error_mgr errors{};
  c.err = jpeg_std_error(&errors);
  jpeg_create_compress(&c);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &buffer, &size);
  c.image_width = width, c.image_height = height, c.input_components = components;
  c.in_color_space = components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 100, TRUE);
  if (progressive) jpeg_simple_progression(&c);
  jpeg_start_compress(&c, TRUE);
  while (c.next_scanline < c.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(pixels.data() + size_t(c.next_scanline) * width * components);
    jpeg_write_scanlines(&c, &row, 1);
  }
  jpeg_finish_compress(&c);
  std::string out(reinterpret_cast<char*>(buffer), size);
  jpeg_destroy_compress(&c);
  std::free(buffer);
  return out;
}

double srgbToLinear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

glm::vec3 mean(const std::string& bytes) {
  return meanTextureColour(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "scene.glb",
                           "texture image 0");
}

// The problem of the InputError decoding `bytes`, or "no error".
std::string refusal(const std::string& bytes, TextureDecodeLimits limits = {}) {
  try {
    meanTextureColour(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "scene.glb",
                      "texture image 0", limits);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "scene.glb");
    return e.problem();
  }
  return "no error";
}

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << "channel " << i;
}

// The 16-bit greyscale PGM on which stb_image 2.27 returns w·h·3 bytes (CVE-2021-42716), and a
// run-length HDR cut short, on which it loops forever (CVE-2021-42715).
const std::string kPgm16 = "P5 64 64 65535\n" + std::string(64 * 64 * 2, '\x7f');
const std::string kTruncatedHdr =
    "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 64 +X 64\n" + std::string("\x02\x02\x00\x40\x80", 5);

// 4 × 2 pixels: two red, two green, two blue, two grey 128 (8-bit sRGB).
const std::vector<unsigned char> kRgb8 = {255, 0, 0,   255, 0, 0,   0,   255, 0,   0,   255, 0,
                                          0,   0, 255, 0,   0, 255, 128, 128, 128, 128, 128, 128};
glm::vec3 rgb8Mean() {
  const float grey = float(srgbToLinear(128 / 255.0));
  return glm::vec3(2 + 2 * grey) / 8.0f;
}

TEST(TextureImage, PngOfEveryLayoutDecodesToItsLinearMean) {
  expectNear(mean(encodePng(4, 2, 8, PNG_COLOR_TYPE_RGB, kRgb8)), rgb8Mean(), 1e-5f);
  expectNear(mean(encodePng(4, 2, 8, PNG_COLOR_TYPE_RGB, kRgb8, true)), rgb8Mean(), 1e-5f);  // Adam7

  // 16 bits a channel: read at 8 (the high byte).
  std::vector<unsigned char> rgb16;
  for (unsigned char v : kRgb8) rgb16.insert(rgb16.end(), {v, 0x40});
  expectNear(mean(encodePng(4, 2, 16, PNG_COLOR_TYPE_RGB, rgb16)), rgb8Mean(), 1e-5f);

  // Alpha is left out of the colour; grey is grey in every channel; a palette is looked up.
  std::vector<unsigned char> rgba;
  for (size_t i = 0; i < kRgb8.size(); i += 3)
    rgba.insert(rgba.end(), {kRgb8[i], kRgb8[i + 1], kRgb8[i + 2], 7});
  expectNear(mean(encodePng(4, 2, 8, PNG_COLOR_TYPE_RGBA, rgba)), rgb8Mean(), 1e-5f);
  const float grey = float(srgbToLinear(128 / 255.0));
  expectNear(mean(encodePng(2, 1, 8, PNG_COLOR_TYPE_GRAY_ALPHA, {128, 0, 128, 255})), glm::vec3(grey), 1e-5f);
  expectNear(mean(encodePng(2, 2, 1, PNG_COLOR_TYPE_GRAY, {0x80, 0x40})), glm::vec3(0.5f), 1e-5f);  // 1 bit
  expectNear(mean(encodePng(2, 1, 8, PNG_COLOR_TYPE_PALETTE, {0, 1}, false, {{255, 0, 0}, {0, 0, 255}})),
             glm::vec3(0.5f, 0, 0.5f), 1e-5f);
}

TEST(TextureImage, JpegBaselineProgressiveAndGreyDecodeToTheirLinearMean) {
  // Flat colours survive JPEG within a level or two.
  std::vector<unsigned char> flat;
  for (int i = 0; i < 16 * 16; ++i) flat.insert(flat.end(), {200, 100, 50});
  const glm::vec3 expected(srgbToLinear(200 / 255.0), srgbToLinear(100 / 255.0), srgbToLinear(50 / 255.0));
  expectNear(mean(encodeJpeg(16, 16, 3, flat)), expected, 0.01f);
  expectNear(mean(encodeJpeg(16, 16, 3, flat, true)), expected, 0.01f);
  expectNear(mean(encodeJpeg(8, 8, 1, std::vector<unsigned char>(64, 128))),
             glm::vec3(srgbToLinear(128 / 255.0)), 0.01f);
}

TEST(TextureImage, OtherFormatsAreRefusedByName) {
  EXPECT_EQ(refusal(kPgm16), "texture image 0 is a PBM/PGM/PPM image; a glTF texture is PNG or JPEG");
  EXPECT_EQ(refusal(kTruncatedHdr), "texture image 0 is a Radiance HDR image; a glTF texture is PNG or JPEG");
  EXPECT_NE(refusal("BM" + std::string(60, '\0')).find("a BMP image"), std::string::npos);
  EXPECT_NE(refusal("GIF89a").find("a GIF image"), std::string::npos);
  EXPECT_NE(refusal("hello").find("an unknown format"), std::string::npos);
  EXPECT_NE(refusal("").find("an unknown format"), std::string::npos);
}

TEST(TextureImage, TruncatedOrCorruptDataIsRefused) {
  const std::string png = encodePng(4, 2, 8, PNG_COLOR_TYPE_RGB, kRgb8);
  for (size_t keep : {size_t(8), size_t(20), size_t(33), png.size() - 20}) {
    const std::string problem = refusal(png.substr(0, keep));
    EXPECT_NE(problem.find("texture image 0: cannot decode the PNG"), std::string::npos)
        << keep << ": " << problem;
  }
  std::string badCrc = png;
  badCrc[29] ^= 1;  // the header's CRC
  EXPECT_NE(refusal(badCrc).find("cannot decode the PNG"), std::string::npos) << refusal(badCrc);
  std::string jpeg = encodeJpeg(16, 16, 3, std::vector<unsigned char>(16 * 16 * 3, 90));
  EXPECT_NE(refusal(jpeg.substr(0, 40)).find("cannot decode the JPEG"), std::string::npos)
      << refusal(jpeg.substr(0, 40));
}

// A PNG header that lies about its size: refused from the header, before a row is allocated.
TEST(TextureImage, SizeIsCheckedFromTheHeaderBeforeDecoding) {
  const std::string png = encodePng(4, 2, 8, PNG_COLOR_TYPE_RGB, kRgb8);
  EXPECT_EQ(refusal(png, {7}), "texture image 0: the PNG is 4x2, more than the 7 texels cpgi decodes");
  const std::string jpeg = encodeJpeg(16, 16, 3, std::vector<unsigned char>(16 * 16 * 3, 90));
  EXPECT_EQ(refusal(jpeg, {16 * 16 - 1}),
            "texture image 0: the JPEG is 16x16, more than the 255 texels cpgi decodes");
  EXPECT_EQ(refusal(jpeg, {15 * 15}),
            "texture image 0: the JPEG is 16x16, more than the 15x15 texels cpgi decodes");
}

// One image shared by a hundred materials (the round's 8192² PNG took 68-98 s, decoded once each).
TEST(TextureImage, AnImageUsedByManyMaterialsIsDecodedOnce) {
  test::GlbBuilder g;
  const std::string png = encodePng(4, 2, 8, PNG_COLOR_TYPE_RGB, kRgb8);
  g.doc["images"] =
      json::array({{{"bufferView", g.addView(png.data(), png.size())}, {"mimeType", "image/png"}}});
  g.doc["textures"] = json::array({{{"source", 0}}, {{"source", 0}}});
  for (int m = 0; m < 100; ++m) {
    const int material =
        g.addMaterial({{"name", "m" + std::to_string(m)},
                       {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", m % 2}}}}}});
    const float x = float(m);
    g.addNode({{"mesh", g.addMesh({x, 0, 0, x + 1, 0, 0, x, 1, 0}, {}, material)}});
  }
  test::TempDir dir;
  g.writeGlb(dir / "scene.glb");
  const uint64_t before = textureImagesDecoded();
  const LoadedScene loaded = loadScene(dir / "scene.glb");
  EXPECT_EQ(textureImagesDecoded() - before, 1u);
  ASSERT_EQ(loaded.scene.materials.size(), 100u);
  for (const Material& m : loaded.scene.materials) expectNear(m.albedo, rgb8Mean(), 1e-5f);
}

// Through the loader: the 720-byte GLB of the round (a 16-bit PGM base colour) and the truncated HDR are
// refused in one line naming the file, the material and the image.
TEST(TextureImage, SceneWithAnImageOfAnotherFormatIsRefusedNamingIt) {
  for (const std::string& image : {kPgm16, kTruncatedHdr}) {
    test::GlbBuilder g;
    g.doc["images"] =
        json::array({{{"bufferView", g.addView(image.data(), image.size())}, {"mimeType", "image/png"}}});
    g.doc["textures"] = json::array({{{"source", 0}}});
    const int m =
        g.addMaterial({{"name", "wall"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
    g.addNode({{"mesh", g.addMesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {}, m)}});
    test::TempDir dir;
    g.writeGlb(dir / "scene.glb");
    try {
      loadScene(dir / "scene.glb");
      ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), dir / "scene.glb");
      EXPECT_NE(e.problem().find("material 'wall': texture image 0 is a "), std::string::npos) << e.problem();
      EXPECT_NE(e.problem().find("; a glTF texture is PNG or JPEG"), std::string::npos) << e.problem();
    }
  }
}

}  // namespace
}  // namespace cpgi
