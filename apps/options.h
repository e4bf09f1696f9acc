// The command line's names for the libraries' parameters, in one place. The libraries speak in fields
// (AtlasParams::texelsPerQuad) and name a parameter in words when it is wrong (InputError("texels per
// quad", ...)); this table binds each parameter to its flag once, with its help, check and default, for
// every command that takes it (bake, reference, decompose, compare-cells --bake, info), and turns a
// library error back into a line that names the flag the user typed.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "apps/help_text.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "decomposition/decompose.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/views.h"
#include "radiosity/reference/noisy_cells.h"

namespace cpgi::cli {

/// The flag that sets `parameter` (a name as the libraries write it in an InputError, e.g. "voxel size"
/// → "--voxel"), or `parameter` itself when no flag sets it.
std::string flagOf(const std::string& parameter);

/// The one line the CLI prints for `e`: its where() as a flag when it names a parameter, and every
/// parameter quoted `like this` in its problem as a flag ("run with `repair`" → "run with --repair").
std::string userMessage(const InputError& e);

/// Prints a warning as bake, decompose, info and reference do: "warning: TEXT" on stderr. The run goes on;
/// an error's line ("cpgi: FILE: PROBLEM") is the last the run prints.
void printWarning(const std::string& text);

/// The scene loader's warnings (LoadedScene::warnings), each naming its file: "warning: FILE: TEXT".
void printLoaderWarnings(const std::string& scene, const std::vector<std::string>& warnings);

/// While one lives, the options added to `cmd` go into the --help group `name` (the group before is
/// restored after), so that each add*Options function below files its flags under its topic.
class OptionGroup {
 public:
  OptionGroup(CLI::App& cmd, std::string_view name);
  ~OptionGroup();
  OptionGroup(const OptionGroup&) = delete;
  OptionGroup& operator=(const OptionGroup&) = delete;

 private:
  CLI::App& cmd_;
  std::string previous_;
};

/// Options added with `needs` set require that option (compare-cells' --bake) and say so in their help.
struct OptionScope {
  CLI::Option* needs = nullptr;
};

/// --texels-per-quad | --density; with `densityAuto`, --density also takes "auto" and sets it
/// (bake: radiosity/solve/auto_density.h); --max-memory into `memoryLimit`, else into atlas.memoryLimit.
void addAtlasOptions(CLI::App& cmd, AtlasParams& atlas, OptionScope scope = {}, bool* densityAuto = nullptr,
                     uint64_t* memoryLimit = nullptr);
/// --max-memory SIZE into `limit` (default: defaultMemoryLimit()); addAtlasOptions adds it for the atlas.
void addMemoryOption(CLI::App& cmd, uint64_t& limit, OptionScope scope = {});
/// --unshot, --max-shots, --visibility, --item-buffer, --item-neighbourhood, --far-field, --regions,
/// --strong-regions, --strong-fraction, --region-size, --fixed-eyes.
void addSolverOptions(CLI::App& cmd, SolverParams& solver, OptionScope scope = {});
/// --no-ambient (bake: leave out radiosity/solve/ambient.h's term) and --ambient-share (bake: the stop per
/// cell).
void addAmbientOption(CLI::App& cmd, bool& noAmbient, double& ambientShare);
/// bake's `--time-limit SECONDS` (0: none).
void addTimeLimitOption(CLI::App& cmd, double& seconds);
/// --portals, --max-rounds, --jobs (for `--method cells`).
void addCellOptions(CLI::App& cmd, CellSolveParams& cells, OptionScope scope = {});
/// --voxel, --seal, --saddle-ratio, --min-depth, --opening-ratio, --min-cell-volume; params.memoryLimit
/// set to the default (commands with --max-memory copy theirs into it).
void addDecomposeOptions(CLI::App& cmd, decomp::DecomposeParams& params, OptionScope scope = {});
/// --spp (paths per texel of the reference).
void addSppOption(CLI::App& cmd, int& spp, OptionScope scope = {});
/// --solve-density (bake: the indirect light on a coarser atlas, radiosity/solve/two_level_solve.h):
/// texels per metre, 0 for one level, or "auto" (kAutoSolveDensity, the default).
void addSolveDensityOption(CLI::App& cmd, float& density);
/// --density-tolerance (bake, with --density auto: radiosity/lightmap/light_density.h).
void addDensityToleranceOption(CLI::App& cmd, float& tolerance);
/// --max-texels (bake, with --density auto: radiosity/solve/auto_density.h, fitTexelBudget).
void addMaxTexelsOption(CLI::App& cmd, size_t& maxTexels);
/// --lamp-coarsening (bake, with --solve-density: radiosity/solve/refined_lamp_shot.h).
void addLampCoarseningOption(CLI::App& cmd, float& coarsening);
/// --cell-noise and --max-spp (more paths for the reference's noisy cells,
/// radiosity/reference/noisy_cells.h).
void addCellNoiseOptions(CLI::App& cmd, CellNoiseTarget& target, OptionScope scope = {});
/// --max-bounces (the reference's path depth); returns the option, to tell whether it was given.
CLI::Option* addMaxBouncesOption(CLI::App& cmd, int& maxBounces, OptionScope scope = {});
/// --scale F, --strict, --repair (the default, kept for old scripts), --allow-outside-files, --emit
/// MATERIAL=W/m2 and --albedo MATERIAL=R,G,B (repeatable): every command that loads a scene takes these.
void addLoadOptions(CLI::App& cmd, LoadOptions& load);
/// --allow-dark (bake, reference): go on with a scene nothing lights.
void addDarkOption(CLI::App& cmd, bool& allowDark);
/// --sky none|uniform|cie-overcast, --sky-irradiance W/m2 | --sky-zenith W/(m2 sr), --sun X,Y,Z,E,
/// --ground A|none (core/sky.h), and with `gatherRays` (bake) --sky-rays N. Values are checked as they are
/// parsed; makeSky's own rules when core/sky.h's applySky puts them on the scene (bake and reference
/// alike, so that both model the same light).
void addSkyOptions(CLI::App& cmd, SkyRequest& sky, bool gatherRays);

/// --view-size WxH (or W×H) of the view-*.png / .exr pictures: width and height in [16, 8192]; without it
/// 640 wide at the camera's aspect. A bad size fails at parsing, before any work.
void addViewOptions(CLI::App& cmd, ViewParams& views);
/// --report DIR (compare-light: DIR/report.html).
void addReportOption(CLI::App& cmd, std::string& dir);
/// --boundary coarse|dark (on-demand bakes).
void addBoundaryOption(CLI::App& cmd, BoundaryMode& mode);

/// Parses `--view-size`'s "WxH" (x, X or ×) into `views`; returns what is wrong with `text`, or "" when it
/// is two whole numbers in [16, 8192].
std::string parseViewSize(const std::string& text, ViewParams& views);

/// Parses `--around`'s "X,Y,Z" (metres); throws InputError(option, ...) unless it is three finite numbers.
glm::vec3 parsePoint(const std::string& text, const std::string& option);

}  // namespace cpgi::cli
