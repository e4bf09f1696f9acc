// Every progress report of one bake at the defaults, as CSV, with the wall and CPU seconds it came at:
// what bench/progress_estimate.py compares the solve's time-left estimate (Progress::secondsLeft,
// Progress::cpuSecondsLeft: what the progress line prints) against the time that actually remained.
//
//   cpgi_progress_estimate SCENE DIR CSV [gl]
//
// With `gl`, every shot on the GL engine (bake --backend gl --indirect gpu), the interreflection too.
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <string>

#include "core/progress.h"
#include "radiosity/bake/bake.h"

namespace {

// The status as one CSV field: no commas or quotes inside.
std::string field(std::string text) {
  for (char& c : text)
    if (c == ',' || c == '"' || c == '\n') c = ';';
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const bool gl = argc == 5 && std::string(argv[4]) == "gl";
  if (argc != 4 && !gl) {
    std::fprintf(stderr, "usage: cpgi_progress_estimate SCENE DIR CSV [gl]\n");
    return 1;
  }
  cpgi::BakeSettings settings;  // the defaults of `cpgi bake`
  settings.input.scene = argv[1];
  settings.output.folder = argv[2];
  if (gl) {
    settings.solver.backend = cpgi::Backend::Gl;
    settings.solver.indirect = cpgi::IndirectSolver::Gpu;
  }
  // Written row by row as the reports come, so a bake stopped early (one that outlasts the machine's
  // time) still leaves its solve's history.
  FILE* csv = std::fopen(argv[3], "w");
  if (!csv) {
    std::fprintf(stderr, "cpgi_progress_estimate: %s: cannot write\n", argv[3]);
    return 1;
  }
  std::fprintf(csv,
               "wall_s,cpu_s,stage,fraction,shots,unshot,seconds_left,cpu_seconds_left,shots_left,status\n");
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = cpgi::processCpuSeconds();
  std::mutex mutex;
  cpgi::Context ctx;
  ctx.setProgress([&](const cpgi::Progress& p) {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::lock_guard lock(mutex);
    std::fprintf(csv, "%.4f,%.4f,%s,%.5f,%d,%.6g,%.4f,%.4f,%.1f,%s\n", wall,
                 cpgi::processCpuSeconds() - cpuStart, field(p.stage).c_str(), p.fraction, p.shots, p.unshot,
                 p.secondsLeft, p.cpuSecondsLeft, p.shotsLeft, field(p.status).c_str());
    std::fflush(csv);
  });
  try {
    const cpgi::BakeResult r = cpgi::bake(settings, ctx);
    std::printf("%s: %zu texels, %d shots, %.1f s wall, %.1f CPU s\n", argv[1], r.atlas.validTexels(),
                r.shots, r.seconds, cpgi::processCpuSeconds() - cpuStart);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cpgi_progress_estimate: %s\n", e.what());
    std::fclose(csv);
    return 1;
  }
  return std::fclose(csv) == 0 ? 0 : 1;
}
