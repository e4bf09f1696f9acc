// libFuzzer target: a .gltf (JSON, buffers as data URIs or files beside it) through loadScene.
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cpgi::fuzz::load(cpgi::fuzz::write("scene.gltf", data, size));
  return 0;
}
