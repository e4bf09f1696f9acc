// libFuzzer target: the checks every format shares and the cell graph (finishScene: degenerate and
// duplicate triangles, materials, portal quads and their orientation, validateCells) on scenes built
// straight from the bytes, without a file format in the way. Coordinates sit on a coarse grid so that
// portals and cells meet often enough to reach the deep checks.
#include <string>

#include "core/scene_io_detail.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t next() { return at_ < size_ ? data_[at_++] : 0; }
  bool empty() const { return at_ >= size_; }
  float coordinate() { return float(int(next() % 9) - 2) * 0.5f; }
  cpgi::Triangle triangle() {
    cpgi::Triangle t;
    for (glm::vec3& p : t.p) p = glm::vec3(coordinate(), coordinate(), coordinate());
    return t;
  }

 private:
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace cpgi;
  Bytes in(data, size);
  detail::RawScene raw;
  const int materials = 1 + in.next() % 3;
  for (int m = 0; m < materials; ++m) {
    const float albedo = in.next() / 200.0f, emission = in.next() % 4 == 0 ? in.next() * 10.0f : 0.0f;
    raw.scene.materials.push_back(Material{"m" + std::to_string(m), glm::vec3(albedo), glm::vec3(emission)});
  }
  const int cells = in.next() % 5;
  const uint32_t node = raw.nodeIndex("n");
  const int triangles = in.next() % 64;
  for (int i = 0; i < triangles && !in.empty(); ++i) {
    Triangle t = in.triangle();
    t.material = in.next() % materials;
    t.node = node;
    raw.scene.triangles.push_back(t);
    const int cell = int(in.next() % (cells + 1)) - 1;
    raw.cellOfTriangle.push_back(cell < 0 ? -1 : raw.cellIndex("c" + std::to_string(cell)));
  }
  const int portals = in.next() % 4;
  for (int i = 0; i < portals; ++i) {
    const std::string name =
        "portal:c" + std::to_string(in.next() % 6) + ":c" + std::to_string(in.next() % 6);
    raw.portals.push_back({name, detail::parseCellTag("fuzz", name), {}});
    const int count = 1 + in.next() % 3;
    for (int k = 0; k < count; ++k) raw.portals.back().triangles.push_back(in.triangle());
  }
  if (in.next() % 4 == 0) {
    const std::string name = "cellvolume:c" + std::to_string(in.next() % 6);
    raw.volumes.push_back({name, detail::parseCellTag("fuzz", name), {}});
    const int count = in.next() % 13;
    for (int k = 0; k < count; ++k) raw.volumes.back().triangles.push_back(in.triangle());
  }
  const bool repair = in.next() % 2;
  try {
    detail::finishScene("fuzz", std::move(raw), LoadOptions{.strict = !repair});
  } catch (const InputError&) {
  }
  return 0;
}
