// libFuzzer target: a binary .glb (header, JSON chunk, BIN chunk) through loadScene.
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cpgi::fuzz::load(cpgi::fuzz::write("scene.glb", data, size));
  return 0;
}
