// Texture images as a glTF may hold them: PNG or JPEG, told by their magic bytes, decoded by Debian's
// libpng and libjpeg-turbo (maintained and fuzzed upstream) rather than a bundled stb_image, whose
// Debian 12 copy (2.27) over-reads on 16-bit PGM and loops forever on a truncated run-length HDR
// (CVE-2021-42716, CVE-2021-42715). Any other format is refused, named.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace cpgi {

/// The formats told apart by magic bytes: the two a glTF may hold, and the others named in messages.
enum class ImageFormat { Png, Jpeg, Other };

/// The format of `bytes` by its magic bytes, and for Other a name for messages ("a Radiance HDR image",
/// "a PGM/PPM image", "an unknown format").
ImageFormat imageFormat(const unsigned char* bytes, size_t size, std::string* otherName = nullptr);

struct TextureDecodeLimits {
  /// The most texels decoded (8-bit RGB: 3 bytes each), checked against the header before allocating.
  uint64_t maxTexels = uint64_t(8192) * 8192;
};

/// The mean linear colour of an encoded PNG or JPEG texture (its texels are sRGB-encoded, as glTF colour
/// textures are; alpha is left out, a 16-bit PNG is read at 8 bits a channel). Work and memory are bound
/// by the declared size, checked first. Throws InputError(`where`, `what` + ": " + problem) for another
/// format, a size over the limit, or data the decoder refuses (truncated, corrupt).
/// @param where  the scene file, named first in the message
/// @param what   the image, e.g. "texture image 3 (material 'floor')"
glm::vec3 meanTextureColour(const unsigned char* bytes, size_t size, const std::string& where,
                            const std::string& what, const TextureDecodeLimits& limits = {});

/// How many images meanTextureColour has decoded in this process (a scene decodes each of its images
/// once, however many materials use it; tests count on it).
uint64_t textureImagesDecoded();

}  // namespace cpgi
