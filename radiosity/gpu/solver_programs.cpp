// The GL engine's GLSL programs (gl_shot_engine.h, SolverPrograms): their #defines per solve's settings
// and their compilation, once per set of #defines.
#include <algorithm>
#include <functional>

#include "radiosity/gpu/gl_shot_backend.h"
#include "radiosity/gpu/shader_library.h"

namespace cpgi {
namespace gl_engine {

ProgramDefines programDefines(const SolveConfig& params) {
  ProgramDefines d;
  if (params.visibility == Visibility::Hemisphere) d.item = d.receive = {"HEMISPHERE"};
  if (params.directionalEmission) d.receive.push_back("DIRECTIONAL"), d.pyramid.push_back("DIRECTIONAL");
  // Binned emission in programs of its own, used for binned shooters only: in every shot the larger
  // program cost openings' cells bake 1.3× the CPU (directional portals on it: 52 → 69 CPU s), and the
  // lobes' programs stay as they were, whose float rounding a lamp shot's resampling decision is
  // sensitive to (EmissionLobes' wall beside an emitter).
  if (params.directionalEmission && !params.emissionBins.empty())
    d.receive.push_back("BINNED"), d.pyramid.push_back("BINNED");
  return d;
}

}  // namespace gl_engine

SolverPrograms::Set::Set(const gl_engine::ProgramDefines& d, std::chrono::steady_clock::time_point deadline) {
  const bool hemisphere = std::find(d.item.begin(), d.item.end(), "HEMISPHERE") != d.item.end();
  const std::vector<std::string> itemShaders =
      hemisphere
          ? std::vector<std::string>{"item.vert", "item_hemisphere.tesc", "item_hemisphere.tese", "item.frag"}
          : std::vector<std::string>{"item.vert", "item.frag"};
  const std::pair<gl::Program*, std::function<gl::Program()>> steps[] = {
      {&item, [&] { return buildProgram(itemShaders, d.item); }},
      {&compact, [] { return buildProgram({"compact.comp"}); }},
      {&finish, [] { return buildProgram({"finish_lists.comp"}); }},
      {&pyramid, [&] { return buildProgram({"shooter_pyramid.comp"}, d.pyramid); }},
      {&receive, [&] { return buildProgram({"receive.comp"}, d.receive); }},
      {&stats, [] { return buildProgram({"patch_stats.comp"}); }},
      {&tileStats, [] { return buildProgram({"tile_stats.comp"}); }},
      {&select, [] { return buildProgram({"select_shooter.comp"}); }},
      {&pickEyes, [] { return buildProgram({"pick_eyes.comp"}); }},
      {&rescale, [] { return buildProgram({"rescale_shot.comp"}); }},
      {&coverage, [&] { return buildProgram({"shot_coverage.comp"}, d.item); }},
      {&cull[0], [] { return buildProgram({"item_cull.comp"}, {"PASS 0"}); }},
      {&cull[1], [] { return buildProgram({"item_cull.comp"}, {"PASS 1"}); }},
      {&cull[2], [] { return buildProgram({"item_cull.comp"}, {"PASS 2"}); }}};
  for (const auto& [program, build] : steps) {
    if (std::chrono::steady_clock::now() >= deadline) return;
    *program = build();
  }
  complete = true;
}

SolverPrograms::SolverPrograms() = default;
SolverPrograms::~SolverPrograms() = default;

const SolverPrograms::Set* SolverPrograms::get(const SolverParams& settings, bool directionalEmission,
                                               bool binnedEmission,
                                               std::chrono::steady_clock::time_point deadline) {
  gl_engine::SolveConfig config{settings};
  config.directionalEmission = directionalEmission;
  const float oneBin = 1.0f;
  if (binnedEmission) config.emissionBins = std::span<const float>(&oneBin, 1);
  const gl_engine::ProgramDefines defines = gl_engine::programDefines(config);
  std::unique_ptr<Set>& set = sets_[defines.key()];
  if (!set) {
    auto made = std::make_unique<Set>(defines, deadline);
    if (!made->complete) return nullptr;  // compiled again, whole, by the next solve that gets the time
    set = std::move(made);
  }
  return set.get();
}

}  // namespace cpgi
