// A cells bake as cell jobs (radiosity/cells/cell_jobs.h, docs/cell-jobs.md) driven from its settings: the
// plan keeps the bake's BakeSettings as JSON in plan.json, and every job and the gather read them back
// from there, load the plan's scene as the plan's bake did, and run the same steps as bake() (bake.h), so
// that the jobs' lightmap is byte for byte the single-process cells bake's.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/context.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/cells/cell_jobs.h"
#include "radiosity/gpu/egl_context.h"

namespace cpgi {

/// The plan of a cells bake with `settings` (BakeMethod::Cells, every cell: no on-demand choice, one
/// level) in `dir`: loads the scene, lays out its atlas (with --density auto after a pilot on a GL
/// context of its own), checks the solve's memory and convergence, and writes plan.json with the settings.
/// Throws InputError.
CellJobPlan planBakeJobs(const std::filesystem::path& dir, const BakeSettings& settings, Context& ctx);

/// The jobs of one plan in one process: the plan's settings and scene, loaded once.
class BakeJobs {
 public:
  /// Reads dir/plan.json's settings and loads their scene and cells (loadBakeScene). Relative paths in
  /// the settings start from the current folder (a driver moves to the plan's workingDir first).
  BakeJobs(std::filesystem::path dir, Context& ctx);
  ~BakeJobs();
  BakeJobs(const BakeJobs&) = delete;
  BakeJobs& operator=(const BakeJobs&) = delete;

  const BakeSettings& settings() const;
  const Scene& scene() const;
  const CellGraph& graph() const;
  /// The cells' parameters of the plan's bake (the plan's densities with --density auto).
  const CellSolveParams& params() const;
  /// The whole scene's atlas as the plan laid it out (built at the first call).
  const LightmapAtlas& globalAtlas(Context& ctx);

  /// The lamps' first shot of emitter groups `groups` (empty: every group of the plan).
  void firstShot(std::vector<int> groups, ShotEngine& engine, Context& ctx);
  /// The groups' shots summed; round 0.
  void firstShotSum(Context& ctx);
  /// Round `round` of `cells` (graph indices; empty: every cell).
  void round(int round, std::vector<int> cells, ShotEngine& engine, Context& ctx);
  /// The bake's result set (settings().output.folder) from every round, as bake() writes it; `run.gl`
  /// may be a server's context.
  BakeResult gather(const BakeRun& run, Context& ctx);

 private:
  struct Loaded;
  std::filesystem::path dir_;
  std::unique_ptr<Loaded> loaded_;
};

}  // namespace cpgi
