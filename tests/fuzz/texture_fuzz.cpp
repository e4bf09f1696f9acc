// libFuzzer target: a texture image's bytes straight into the decoders (core/texture_image.h: libpng and
// libjpeg-turbo behind the magic-byte check), without a glTF around them, so that mutations reach the
// image data. The limit is lowered to keep each run fast; only InputError is an acceptable outcome.
#include "core/error.h"
#include "core/texture_image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cpgi::meanTextureColour(data, size, "scene.glb", "texture image 0", cpgi::TextureDecodeLimits{1u << 20});
  } catch (const cpgi::InputError&) {
  }
  return 0;
}
