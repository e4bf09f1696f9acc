// The contact cuts of the load (core/contact_cuts.h) on scene files, as a Markdown table: triangles before
// and after, faces cut, pieces dropped and their area, faces left whole, and the cut's CPU seconds, with
// the feet of standing solids cut (the default) and with through-cuts only (minFootprint beyond any foot).
//   cpgi_contact_cuts_bench SCENE...
#include <cstdio>
#include <ctime>
#include <limits>

#include "core/contact_cuts.h"
#include "core/scene_io.h"

namespace {

void row(const char* path, const char* what, const cpgi::LoadedScene& loaded,
         const cpgi::ContactCutParams& params) {
  cpgi::Scene scene = loaded.scene;
  cpgi::CellGraph cells = loaded.cells;
  const std::clock_t start = std::clock();
  const cpgi::ContactCuts c = cpgi::cutAtContacts(scene, cells, params);
  const double cpu = double(std::clock() - start) / CLOCKS_PER_SEC;
  std::printf("| %s | %s | %zu | %zu | %zu | %zu | %.3f | %zu | %.2f |\n", path, what, c.trianglesBefore,
              c.trianglesAfter, c.facesCut, c.buriedPieces, c.buriedArea, c.leftWhole, cpu);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf(
      "| scene | cuts | triangles | after | faces cut | pieces dropped | m² dropped | left whole | CPU s "
      "|\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (int k = 1; k < argc; ++k) {
    cpgi::LoadOptions options;
    options.cutContacts = false;
    const cpgi::LoadedScene loaded = cpgi::loadScene(argv[k], options);
    cpgi::ContactCutParams throughOnly;
    throughOnly.minFootprint = std::numeric_limits<double>::infinity();
    row(argv[k], "through only", loaded, throughOnly);
    row(argv[k], "through + feet", loaded, {});
  }
}
