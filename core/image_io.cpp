// OpenEXR (linear float, exact) and PNG (sRGB, 8 bit) images.
#include "core/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <half.h>

// Static, so that these symbols cannot clash with the copy libtinygltf pulls in through libstb.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

#include "core/error.h"
#include "core/output_dir.h"

namespace cpgi {
namespace {

void checkImage(const ImageRGB& image, const char* who) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height)
    throw std::invalid_argument(std::string(who) + ": image size does not match its pixels");
}

// The most pixels an OpenEXR read allocates (a 16384 × 8192 lightmap or view: 1.6 GB as float RGB), and
// the most its pixels may unpack to per byte of the file: zlib, EXR's usual compression, cannot do better
// than about 1 032 to 1, so a 10 KB file whose header announces 20 000² pixels lies about its size.
constexpr int64_t kMaxExrPixels = int64_t(1) << 27;
constexpr int64_t kMaxExrExpansion = 4096;
constexpr int kMaxExrSide = 1 << 17;

// Before anything is allocated: the data window's pixels against the limit and against the file's size.
void checkExrSize(const std::string& path, const Imath::Box2i& dw, int channels) {
  const int64_t width = int64_t(dw.max.x) - dw.min.x + 1, height = int64_t(dw.max.y) - dw.min.y + 1;
  if (width <= 0 || height <= 0) throw InputError(path, "OpenEXR data window is empty");
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width > kMaxExrSide || height > kMaxExrSide || width * height > kMaxExrPixels)
    throw InputError(path, "OpenEXR data window " + size + " holds more than the " +
                               std::to_string(kMaxExrPixels) + " pixels cpgi reads");
  std::error_code ec;
  const uintmax_t fileBytes = std::filesystem::file_size(path, ec);
  const double unpacked = double(width) * double(height) * channels * sizeof(float);
  if (!ec && unpacked > double(fileBytes) * kMaxExrExpansion)
    throw InputError(path, "OpenEXR data window " + size + " cannot be held in a file of " +
                               std::to_string(fileBytes) + " bytes (truncated, or its header lies)");
}

// OpenEXR reads a typed attribute by its type, not by its declared size (a box2i is 16 bytes whatever the
// size says; a channel list runs to its empty name; a preview allocates width × height × 4 bytes): where
// the two disagree, its reading and the walk in checkExrHeader part ways. So the declared size must be
// the one the type gives; a preview is refused, and a type OpenEXR does not know is read by its size.
void checkExrAttributeSize(const std::string& path, const std::string& name, const std::string& type,
                           const std::string& data) {
  static const std::pair<const char*, size_t> fixed[] = {
      {"box2i", 16},   {"box2f", 16},      {"v2i", 8},       {"v2f", 8},     {"v2d", 16},
      {"v3i", 12},     {"v3f", 12},        {"v3d", 24},      {"int", 4},     {"float", 4},
      {"double", 8},   {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},  {"deepImageState", 1},
      {"m33f", 36},    {"m33d", 72},       {"m44f", 64},     {"m44d", 128},  {"chromaticities", 32},
      {"keycode", 28}, {"timecode", 8},    {"rational", 8},  {"tiledesc", 9}};
  bool fits = true;
  for (const auto& [kind, bytes] : fixed)
    if (type == kind) fits = data.size() == bytes;
  if (type == "preview") fits = false;
  if (type == "chlist") {
    size_t at = 0;  // each channel: its name, a NUL, 16 bytes of type and sampling; a NUL ends the list
    while (at < data.size() && data[at] != '\0') {
      const size_t end = data.find('\0', at);
      at = end == std::string::npos ? data.size() + 1 : end + 17;
    }
    fits = at + 1 == data.size();
  }
  if (!fits)
    throw InputError(path, "OpenEXR header attribute '" + printable(name) + "' of type '" + printable(type) +
                               "' has a size its type does not give");
}

// What checkExrHeader reads of a header before OpenEXR opens the file.
struct ExrHeaderFacts {
  Imath::Box2i dataWindow;
  int channels = 0;
};

// OpenEXR allocates each header attribute at the size the file declares, and its table of chunk offsets
// from the data window, before it reads either: a 500-byte file may ask for gigabytes. The header is
// walked here first: every attribute must fit in what is left of the file, and the data window is read
// for checkExrSize. Tiled, deep and multi-part files (version flags 0x200, 0x800, 0x1000) are not images
// cpgi writes, and are refused.
ExrHeaderFacts checkExrHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uint64_t fileBytes = std::filesystem::file_size(path, ec);
  unsigned char start[8] = {};
  if (ec || !in.read(reinterpret_cast<char*>(start), 8) || start[0] != 0x76 || start[1] != 0x2f ||
      start[2] != 0x31 || start[3] != 0x01)
    throw InputError(path, "not an OpenEXR file (no magic number)");
  if (start[5] & 0x1a)
    throw InputError(path,
                     "a tiled, deep or multi-part OpenEXR file; cpgi reads single-part scanline images");
  auto readName = [&](std::string& name) {
    name.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return true;
      if (name.size() == 255) return false;
      name += c;
    }
    return false;
  };
  ExrHeaderFacts facts;
  bool window = false;
  for (std::string name, type;;) {
    if (!readName(name)) throw InputError(path, "OpenEXR header is truncated or malformed");
    if (name.empty()) break;  // the end of the header
    int32_t size = 0;
    if (!readName(type) || !in.read(reinterpret_cast<char*>(&size), 4) || size < 0 ||
        uint64_t(size) > fileBytes - uint64_t(in.tellg()))
      throw InputError(path,
                       "OpenEXR header attribute '" + printable(name) + "' runs past the end of the file");
    std::string data(size_t(size), '\0');
    if (!in.read(data.data(), size)) throw InputError(path, "OpenEXR header is truncated");
    checkExrAttributeSize(path, name, type, data);
    if (name == "dataWindow" && type == "box2i") {
      int32_t box[4];  // xMin yMin xMax yMax, little-endian as the file
      std::memcpy(box, data.data(), 16);
      facts.dataWindow = Imath::Box2i(Imath::V2i(box[0], box[1]), Imath::V2i(box[2], box[3]));
      window = true;
    } else if (name == "channels" && type == "chlist") {
      // Each channel: its name, a NUL, 16 bytes of type and sampling; a NUL ends the list.
      for (size_t at = 0; at < data.size() && data[at] != '\0'; ++facts.channels) {
        const size_t end = data.find('\0', at);
        if (end == std::string::npos) break;
        at = end + 17;
      }
    }
  }
  if (!window) throw InputError(path, "OpenEXR header has no data window");
  return facts;
}

float linearToSrgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

void writeExr(const std::string& path, const ImageRGB& image, const std::vector<ExrChannel>& extra,
              ExrPrecision precision) {
  checkImage(image, "writeExr");
  const size_t n = image.pixels.size();
  for (const ExrChannel& c : extra)
    if (c.values.size() != n || c.name.empty() || c.name == "R" || c.name == "G" || c.name == "B")
      throw std::invalid_argument("writeExr: channel '" + c.name + "' has the wrong size or a reserved name");

  const Imf::PixelType type = precision == ExrPrecision::Half ? Imf::HALF : Imf::FLOAT;
  Imf::Header header(image.width, image.height);
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(type));
  for (const ExrChannel& c : extra) header.channels().insert(c.name, Imf::Channel(type));
  header.compression() = Imf::ZIP_COMPRESSION;

  Imf::FrameBuffer frame;
  // Half pixels are converted here, each channel a plane of its own (R, G, B, then the extra ones).
  std::vector<Imath::half> halves;
  if (precision == ExrPrecision::Half) {
    halves.resize(n * (3 + extra.size()));
    auto toHalf = [](float v) { return Imath::half(std::isnan(v) ? v : std::clamp(v, -65504.0f, 65504.0f)); };
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) halves[size_t(c) * n + i] = toHalf(image.pixels[i][c]);
    for (size_t k = 0; k < extra.size(); ++k)
      for (size_t i = 0; i < n; ++i) halves[(3 + k) * n + i] = toHalf(extra[k].values[i]);
  }
  auto slice = [&](size_t plane, const char* floatBase, size_t floatStride) {
    if (precision == ExrPrecision::Float)
      return Imf::Slice(Imf::FLOAT, const_cast<char*>(floatBase), floatStride, floatStride * image.width);
    return Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + plane * n), sizeof(Imath::half),
                      sizeof(Imath::half) * image.width);
  };
  const char* base = reinterpret_cast<const char*>(image.pixels.data());
  const char* names[] = {"R", "G", "B"};
  for (size_t c = 0; c < 3; ++c)
    frame.insert(names[c], slice(c, base + c * sizeof(float), sizeof(glm::vec3)));
  for (size_t k = 0; k < extra.size(); ++k)
    frame.insert(extra[k].name,
                 slice(3 + k, reinterpret_cast<const char*>(extra[k].values.data()), sizeof(float)));

  std::ostringstream bytes;
  try {
    Imf::StdOSStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }
    bytes << stream.str();
  } catch (const std::exception& e) {
    throw SystemError(path + ": cannot encode OpenEXR: " + e.what());
  }
  writeFileAtomically(path, bytes.str());
}

ImageRGB readExr(const std::string& path, std::vector<ExrChannel>* extra) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not an image");
  try {
    // OpenEXR sizes its table of chunk offsets from the header as it opens the file: the header's own
    // sanity check refuses sides past the limit there, before that table is allocated.
    Imf::Header::setMaxImageSize(kMaxExrSide, kMaxExrSide);
    Imf::Header::setMaxTileSize(kMaxExrSide, kMaxExrSide);
    const ExrHeaderFacts facts = checkExrHeader(path);
    checkExrSize(path, facts.dataWindow, extra ? std::max(facts.channels, 3) : 3);
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const Imf::ChannelList& channels = file.header().channels();
    for (const char* c : {"R", "G", "B"})
      if (!channels.findChannel(c))
        throw InputError(path, std::string("OpenEXR file has no ") + c + " channel");
    if (dw != facts.dataWindow) throw InputError(path, "OpenEXR header read two ways differs");
    ImageRGB image;
    image.width = dw.max.x - dw.min.x + 1;
    image.height = dw.max.y - dw.min.y + 1;
    image.pixels.assign(size_t(image.width) * image.height, glm::vec3(0.0f));

    // Slices are addressed from the data window's origin, which need not be (0, 0).
    const ptrdiff_t origin = ptrdiff_t(dw.min.x) + ptrdiff_t(dw.min.y) * image.width;
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(image.pixels.data()) - origin * ptrdiff_t(sizeof(glm::vec3));
    const size_t xStride = sizeof(glm::vec3), yStride = xStride * image.width;
    for (int c = 0; c < 3; ++c)
      frame.insert(c == 0   ? "R"
                   : c == 1 ? "G"
                            : "B",
                   Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
    if (extra) {
      extra->clear();
      for (auto it = channels.begin(); it != channels.end(); ++it) {
        const std::string name = it.name();
        if (name == "R" || name == "G" || name == "B") continue;
        extra->push_back({name, std::vector<float>(image.pixels.size(), 0.0f)});
      }
      for (ExrChannel& c : *extra)
        frame.insert(c.name,
                     Imf::Slice(Imf::FLOAT,
                                reinterpret_cast<char*>(c.values.data()) - origin * ptrdiff_t(sizeof(float)),
                                sizeof(float), sizeof(float) * image.width));
    }
    file.setFrameBuffer(frame);
    file.readPixels(dw.min.y, dw.max.y);
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::string msg = e.what();
    if (const size_t nl = msg.find('\n'); nl != std::string::npos) msg.resize(nl);
    throw InputError(path, "not a readable OpenEXR file: " + msg);
  }
}

std::string encodePng(const ImageRGB& image, float exposure) {
  checkImage(image, "encodePng");
  std::vector<unsigned char> rgb(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = image.pixels[i][c] * exposure;
      rgb[3 * i + c] =
          static_cast<unsigned char>(std::lround(255.0f * linearToSrgb(std::isnan(v) ? 0.0f : v)));
    }
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, image.width, image.height, 3, rgb.data(), image.width * 3))
    throw SystemError("encodePng: PNG encoding failed");
  return out;
}

std::string encodePng8(int width, int height, int channels, const std::vector<uint8_t>& pixels) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      pixels.size() != size_t(width) * size_t(height) * size_t(channels))
    throw std::invalid_argument("encodePng8: the pixels do not match the size");
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, width, height, channels, pixels.data(), width * channels))
    throw SystemError("encodePng8: PNG encoding failed");
  return out;
}

void writePng(const std::string& path, const ImageRGB& image, float exposure) {
  writeFileAtomically(path, encodePng(image, exposure));
}

}  // namespace cpgi
