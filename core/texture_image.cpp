#include "core/texture_image.h"

#include <atomic>
#include <cmath>
#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE
#include <cstring>
#include <vector>

#include <jpeglib.h>
#include <png.h>

#include "core/error.h"

namespace cpgi {
namespace {

std::atomic<uint64_t> decodedImages{0};

// "8192x8192" for a square count, else the number.
std::string texelCount(uint64_t texels) {
  const auto side = uint64_t(std::llround(std::sqrt(double(texels))));
  return side * side == texels ? std::to_string(side) + "x" + std::to_string(side) : std::to_string(texels);
}

bool startsWith(const unsigned char* bytes, size_t size, const char* magic, size_t length) {
  return size >= length && std::memcmp(bytes, magic, length) == 0;
}

// Sums of linear colour over the texels, from 8-bit sRGB-encoded RGB rows.
class LinearSum {
 public:
  LinearSum() {
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      lut_[i] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    }
  }
  void addRow(const unsigned char* rgb, size_t width) {
    for (size_t x = 0; x < width; ++x, rgb += 3) sum_ += glm::dvec3(lut_[rgb[0]], lut_[rgb[1]], lut_[rgb[2]]);
    texels_ += width;
  }
  glm::vec3 mean() const { return texels_ ? glm::vec3(sum_ / double(texels_)) : glm::vec3(1.0f); }

 private:
  double lut_[256];
  glm::dvec3 sum_{0.0};
  uint64_t texels_ = 0;
};

// --- PNG (libpng). Its errors longjmp back to the setjmp in decodePng, whose frame holds no object with
// a destructor; everything that owns memory lives in meanPngColour's frame and is cleaned up there.

struct PngSource {
  const unsigned char* bytes;
  size_t size, at;
  std::string error;
  uint64_t maxTexels;
};

void pngRead(png_structp png, png_bytep out, size_t length) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->size - source->at) png_error(png, "the file ends inside the image (truncated)");
  std::memcpy(out, source->bytes + source->at, length);
  source->at += length;
}

void pngError(png_structp png, png_const_charp message) {
  static_cast<PngSource*>(png_get_error_ptr(png))->error =
      std::string("cannot decode the PNG: ") + (message ? message : "unknown error");
  png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}  // ancillary-chunk problems: the pixels still decode

struct PngHandles {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngHandles() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

// The header's size is checked before `rows` (the caller's) is sized; false with source.error set on
// any error. Interlaced images need every row (each pass fills in some); others are read a row at a time.
bool decodePng(PngHandles& h, PngSource& source, std::vector<unsigned char>& rows, LinearSum& sum) {
  if (setjmp(png_jmpbuf(h.png))) return false;
  png_set_read_fn(h.png, &source, pngRead);
  png_set_user_limits(h.png, 1u << 16, 1u << 16);
  png_set_chunk_malloc_max(h.png, 8u << 20);  // a compressed text or ICC chunk cannot unpack to gigabytes
  png_read_info(h.png, h.info);
  const png_uint_32 width = png_get_image_width(h.png, h.info), height = png_get_image_height(h.png, h.info);
  if (uint64_t(width) * height > source.maxTexels) {
    source.error = "the PNG is " + std::to_string(width) + "x" + std::to_string(height) + ", more than the " +
                   texelCount(source.maxTexels) + " texels cpgi decodes";
    return false;
  }
  png_set_expand(h.png);  // palette to RGB, grey under 8 bits to 8, tRNS to alpha
  png_set_strip_16(h.png);
  png_set_strip_alpha(h.png);
  png_set_gray_to_rgb(h.png);
  const int passes = png_set_interlace_handling(h.png);
  png_read_update_info(h.png, h.info);
  const size_t rowBytes = png_get_rowbytes(h.png, h.info);
  if (rowBytes != size_t(width) * 3) png_error(h.png, "unexpected row layout after conversion to RGB");
  rows.assign(passes > 1 ? rowBytes * height : rowBytes, 0);
  for (int pass = 0; pass < passes; ++pass)
    for (png_uint_32 y = 0; y < height; ++y) {
      unsigned char* row = rows.data() + (passes > 1 ? rowBytes * y : 0);
      png_read_row(h.png, row, nullptr);
      if (passes == 1) sum.addRow(row, width);
    }
  if (passes > 1)
    for (png_uint_32 y = 0; y < height; ++y) sum.addRow(rows.data() + rowBytes * y, width);
  return true;
}

uint32_t bigEndian32(const unsigned char* b) {
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | b[3];
}

glm::vec3 meanPngColour(const unsigned char* bytes, size_t size, const std::string& where,
                        const std::string& what, uint64_t maxTexels) {
  // The size straight from the header chunk, which comes first: libpng reads on to the next chunk before
  // it reports the header, and a file that is all header would be called truncated rather than too large.
  if (size >= 24 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
    const uint32_t width = bigEndian32(bytes + 16), height = bigEndian32(bytes + 20);
    if (uint64_t(width) * height > maxTexels)
      throw InputError(where, what + ": the PNG is " + std::to_string(width) + "x" + std::to_string(height) +
                                  ", more than the " + texelCount(maxTexels) + " texels cpgi decodes");
  }
  PngSource source{bytes, size, 0, {}, maxTexels};
  PngHandles h;
  h.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, pngError, pngWarning);
  if (h.png) h.info = png_create_info_struct(h.png);
  if (!h.png || !h.info) throw SystemError(where + ": " + what + ": out of memory for the PNG decoder");
  std::vector<unsigned char> rows;
  LinearSum sum;
  if (!decodePng(h, source, rows, sum)) throw InputError(where, what + ": " + source.error);
  return sum.mean();
}

// --- JPEG (libjpeg-turbo), the same pattern: error_exit longjmps back into decodeJpeg.

// A progressive JPEG may hold thousands of scans, each a pass over every coefficient (a known
// decompression bomb); real encoders write about ten. libjpeg-turbo's own tools stop at 500.
constexpr int kMaxJpegScans = 500;

struct JpegErrors {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX + 64];  // libjpeg's message and what cpgi puts before it
};

void jpegErrorExit(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  char message[JMSG_LENGTH_MAX];
  (*info->err->format_message)(info, message);
  std::snprintf(errors->message, sizeof errors->message, "cannot decode the JPEG: %s", message);
  std::longjmp(errors->jump, 1);
}

void jpegMessage(j_common_ptr, int) {}  // warnings (a few extraneous bytes): the pixels still decode

void jpegProgress(j_common_ptr info) {
  auto* d = reinterpret_cast<j_decompress_ptr>(info);
  if (d->input_scan_number > kMaxJpegScans) {
    auto* errors = reinterpret_cast<JpegErrors*>(info->err);
    std::snprintf(errors->message, sizeof errors->message, "the JPEG has more than %d scans", kMaxJpegScans);
    std::longjmp(errors->jump, 1);
  }
}

struct JpegDecoder {
  jpeg_decompress_struct info{};
  JpegErrors errors{};
  jpeg_progress_mgr progress{};
  bool created = false;
  ~JpegDecoder() {
    if (created) jpeg_destroy_decompress(&info);
  }
};

bool decodeJpeg(JpegDecoder& d, const unsigned char* bytes, size_t size, uint64_t maxTexels,
                std::vector<unsigned char>& row, LinearSum& sum) {
  if (setjmp(d.errors.jump)) return false;
  jpeg_create_decompress(&d.info);
  d.created = true;
  d.progress.progress_monitor = jpegProgress;
  d.info.progress = &d.progress;
  jpeg_mem_src(&d.info, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&d.info, TRUE);
  if (uint64_t(d.info.image_width) * d.info.image_height > maxTexels) {
    std::snprintf(d.errors.message, sizeof d.errors.message,
                  "the JPEG is %ux%u, more than the %s texels cpgi decodes", d.info.image_width,
                  d.info.image_height, texelCount(maxTexels).c_str());
    return false;
  }
  d.info.out_color_space = JCS_RGB;  // from grey or YCbCr; CMYK cannot be, and is refused
  // Coefficients of a progressive 8192² image with four components take 512 MB; no more is allowed.
  d.info.mem->max_memory_to_use = 640L << 20;
  jpeg_start_decompress(&d.info);
  if (d.info.output_components != 3) {
    std::snprintf(d.errors.message, sizeof d.errors.message, "the JPEG decodes to %d channels, not RGB",
                  d.info.output_components);
    return false;
  }
  row.assign(size_t(d.info.output_width) * 3, 0);
  while (d.info.output_scanline < d.info.output_height) {
    JSAMPROW rows[1] = {row.data()};
    if (jpeg_read_scanlines(&d.info, rows, 1) != 1) return false;  // suspended: no more data
    sum.addRow(row.data(), d.info.output_width);
  }
  jpeg_abort_decompress(&d.info);  // what follows the last scanline does not matter
  return true;
}

glm::vec3 meanJpegColour(const unsigned char* bytes, size_t size, const std::string& where,
                         const std::string& what, uint64_t maxTexels) {
  if (size > 0xFFFFFFFFu) throw InputError(where, what + ": JPEG larger than 4 GiB");
  JpegDecoder d;
  d.info.err = jpeg_std_error(&d.errors.manager);
  d.errors.manager.error_exit = jpegErrorExit;
  d.errors.manager.emit_message = jpegMessage;
  std::strcpy(d.errors.message, "cannot decode the JPEG");
  std::vector<unsigned char> row;
  LinearSum sum;
  if (!decodeJpeg(d, bytes, size, maxTexels, row, sum))
    throw InputError(where, what + ": " + std::string(d.errors.message));
  return sum.mean();
}

}  // namespace

ImageFormat imageFormat(const unsigned char* bytes, size_t size, std::string* otherName) {
  if (startsWith(bytes, size, "\x89PNG\r\n\x1a\n", 8)) return ImageFormat::Png;
  if (startsWith(bytes, size, "\xff\xd8\xff", 3)) return ImageFormat::Jpeg;
  if (otherName) {
    static const struct {
      const char* magic;
      size_t length;
      const char* name;
    } known[] = {{"#?RADIANCE", 10, "a Radiance HDR image"},
                 {"#?RGBE", 6, "a Radiance HDR image"},
                 {"P1", 2, "a PBM/PGM/PPM image"},
                 {"P2", 2, "a PBM/PGM/PPM image"},
                 {"P3", 2, "a PBM/PGM/PPM image"},
                 {"P4", 2, "a PBM/PGM/PPM image"},
                 {"P5", 2, "a PBM/PGM/PPM image"},
                 {"P6", 2, "a PBM/PGM/PPM image"},
                 {"BM", 2, "a BMP image"},
                 {"GIF8", 4, "a GIF image"},
                 {"8BPS", 4, "a PSD image"},
                 {"\x76\x2f\x31\x01", 4, "an OpenEXR image"},
                 {"\xabKTX 20\xbb", 8, "a KTX2 image (KHR_texture_basisu)"},
                 {"DDS ", 4, "a DDS image"}};
    *otherName = "an unknown format";
    if (size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0)
      *otherName = "a WebP image (EXT_texture_webp)";
    for (const auto& k : known)
      if (startsWith(bytes, size, k.magic, k.length)) *otherName = k.name;
  }
  return ImageFormat::Other;
}

uint64_t textureImagesDecoded() {
  return decodedImages.load();
}

glm::vec3 meanTextureColour(const unsigned char* bytes, size_t size, const std::string& where,
                            const std::string& what, const TextureDecodeLimits& limits) {
  ++decodedImages;
  std::string other;
  switch (imageFormat(bytes, size, &other)) {
    case ImageFormat::Png:
      return meanPngColour(bytes, size, where, what, limits.maxTexels);
    case ImageFormat::Jpeg:
      return meanJpegColour(bytes, size, where, what, limits.maxTexels);
    case ImageFormat::Other:
      break;
  }
  throw InputError(where, what + " is " + other + "; a glTF texture is PNG or JPEG");
}

}  // namespace cpgi
