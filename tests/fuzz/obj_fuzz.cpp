// libFuzzer target: an OBJ and its MTL through loadScene. The input is the OBJ text, optionally followed
// by a line "#MTL" and the text of scene.mtl (which the seeds' `mtllib scene.mtl` names).
#include <cstring>

#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("\n#MTL\n");
  const std::string obj = text.substr(0, split);
  const std::string mtl = split == std::string::npos ? std::string() : text.substr(split + 6);
  cpgi::fuzz::write("scene.mtl", reinterpret_cast<const uint8_t*>(mtl.data()), mtl.size());
  cpgi::fuzz::load(cpgi::fuzz::write("scene.obj", reinterpret_cast<const uint8_t*>(obj.data()), obj.size()));
  return 0;
}
