// libFuzzer target: an OpenEXR file through readExr, as `view` and `compare-light` read a bake's
// lightmap.exr and view EXRs (issue 49, item 9: a header that lies about its data window). Only
// InputError is an acceptable outcome.
#include "core/image_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = cpgi::fuzz::write("lightmap.exr", data, size);
  for (bool extra : {false, true}) {
    std::vector<cpgi::ExrChannel> channels;
    try {
      cpgi::readExr(path, extra ? &channels : nullptr);
    } catch (const cpgi::InputError&) {
    }
  }
  return 0;
}
