#include "apps/options.h"

#include "core/number_list.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "apps/commands.h"
#include "core/memory_limit.h"

namespace cpgi::cli {
namespace {

// Every parameter the libraries name in their errors, with the flag that sets it.
struct ParameterFlag {
  std::string_view parameter, flag;
};
constexpr ParameterFlag kFlags[] = {
    // Loading (core/scene_io.h)
    {"repair", "--repair"},
    {"strict", "--strict"},
    {"outside files", "--allow-outside-files"},
    {"emit", "--emit"},
    {"albedo", "--albedo"},
    {"dark", "--allow-dark"},
    // Atlas (radiosity/lightmap/atlas.h)
    {"texels per quad", "--texels-per-quad"},
    {"texel density", "--density"},
    {"maximum memory", "--max-memory"},
    // GPU solver (radiosity/gpu/gl_shot_engine.h)
    {"unshot fraction", "--unshot"},
    {"maximum shots", "--max-shots"},
    {"visibility", "--visibility"},
    {"item buffer", "--item-buffer"},
    {"item-buffer neighbourhood", "--item-neighbourhood"},
    {"far-field ratio", "--far-field"},
    {"fixed eyes", "--fixed-eyes"},
    {"visibility regions", "--regions"},
    {"strong-shot regions", "--strong-regions"},
    {"strong-shot fraction", "--strong-fraction"},
    {"region size", "--region-size"},
    {"lamp rays", "--lamp-rays"},
    // Ambient term (radiosity/solve/ambient.h), bake only
    {"no ambient term", "--no-ambient"},
    {"ambient share", "--ambient-share"},
    // Bake only: stop the solve at a wall-clock limit, writing a partial result
    {"time limit", "--time-limit"},
    {"solve density", "--solve-density"},
    {"lamp coarsening", "--lamp-coarsening"},
    {"density tolerance", "--density-tolerance"},
    {"maximum texels", "--max-texels"},
    // Loading, every command
    {"scale", "--scale"},
    // The sky, sun and ground of an open scene (core/sky.h), bake and reference
    {"sky", "--sky"},
    {"sky irradiance", "--sky-irradiance"},
    {"sky zenith", "--sky-zenith"},
    {"sun", "--sun"},
    {"ground albedo", "--ground"},
    {"sky rays", "--sky-rays"},
    // Views (radiosity/lightmap/views.h)
    {"view size", "--view-size"},
    // compare-light's page (core/html_report/html_report.h)
    {"report folder", "--report"},
    // Cells (radiosity/cells/)
    {"cell graph", "--cells"},
    {"portal light", "--portals"},
    {"portal lobe width", "--lobe-width"},
    {"portal bin rays", "--portal-rays"},
    {"portal density scale", "--portal-scale"},
    {"maximum rounds", "--max-rounds"},
    {"jobs", "--jobs"},
    {"boundary", "--boundary"},
    // Reference (radiosity/reference/reference_tracer.h)
    {"samples per texel", "--spp"},
    {"maximum bounces", "--max-bounces"},
    {"cell noise", "--cell-noise"},
    {"maximum samples per texel", "--max-spp"},
    // Decomposition (decomposition/decompose.h)
    {"voxel size", "--voxel"},
    {"seal radius", "--seal"},
    {"saddle ratio", "--saddle-ratio"},
    {"minimum depth", "--min-depth"},
    {"opening ratio", "--opening-ratio"},
    {"minimum cell volume", "--min-cell-volume"},
    {"outside saddle ratio", "--outside-saddle-ratio"},
    {"storey spread", "--storey-spread"},
    {"keep contacts", "--keep-contacts"},
    {"gallery floor rise", "--gallery-floor-rise"},
};

std::string flag(std::string_view parameter) {
  for (const ParameterFlag& f : kFlags)
    if (f.parameter == parameter) return std::string(f.flag);
  throw std::logic_error("apps/options.cpp: no flag for parameter '" + std::string(parameter) + "'");
}

// "With --bake: " before the help of options that need another.
std::string help(const OptionScope& scope, const std::string& text) {
  return scope.needs ? "With " + scope.needs->get_name() + ": " + text : text;
}

CLI::Option* scoped(CLI::Option* option, const OptionScope& scope) {
  if (scope.needs) option->needs(scope.needs);
  return option;
}

// Every number a flag takes is finite: CLI11 reads "nan", "inf" and "1e999" into a float, and its Range
// lets NaN through (every comparison with NaN is false).
const CLI::Validator kFinite(
    [](std::string& value) -> std::string {
      double v = 0.0;
      if (CLI::detail::lexical_cast(value, v) && !std::isfinite(v))
        return "must be a finite number, got " + printable(value);
      return {};
    },
    "");

// Numbers in [min, max], NaN refused, saying the range and what was given.
CLI::Validator within(double min, double max) {
  std::ostringstream range;
  range << "[" << min << ", " << max << "]";
  return CLI::Validator(
      [min, max, range = range.str()](std::string& value) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(value, v)) return "must be a number, got " + printable(value);
        if (!(v >= min && v <= max)) return "must be in " + range + ", got " + printable(value);
        return {};
      },
      "");
}
const CLI::Validator kNonNegative = within(0.0, std::numeric_limits<double>::max());

// An option whose value `check` bounds, with its default in the help: the shape of every numeric
// parameter, so that each is refused when not finite.
template <class T>
CLI::Option* addChecked(CLI::App& cmd, const OptionScope& scope, std::string_view parameter, T& field,
                        const std::string& text, const CLI::Validator& check) {
  return scoped(cmd.add_option(flag(parameter), field, help(scope, text))
                    ->check(kFinite)
                    ->check(check)
                    ->capture_default_str(),
                scope);
}

// A flag taking one of `choices` by name, setting `field` to the value named (help: "TEXT:{a,b}=a").
template <class Enum>
CLI::Option* addChoice(CLI::App& cmd, const std::string& name, Enum& field,
                       const std::vector<std::pair<std::string, Enum>>& choices, const std::string& text) {
  std::vector<std::string> names;
  std::string current;
  for (const auto& [n, value] : choices) {
    names.push_back(n);
    if (value == field) current = n;
  }
  return cmd
      .add_option_function<std::string>(
          name,
          [&field, choices](const std::string& given) {
            for (const auto& [n, value] : choices)
              if (n == given) field = value;
          },
          text)
      ->check(CLI::IsMember(names))
      ->default_str(current);
}

}  // namespace

std::string flagOf(const std::string& parameter) {
  for (const ParameterFlag& f : kFlags)
    if (f.parameter == parameter) return std::string(f.flag);
  return parameter;
}

std::string userMessage(const InputError& e) {
  std::string problem = e.problem();
  for (size_t open = problem.find('`'); open != std::string::npos; open = problem.find('`', open + 1)) {
    const size_t close = problem.find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string name = problem.substr(open + 1, close - open - 1), flag = flagOf(name);
    if (flag == name) continue;
    problem.replace(open, close - open + 1, flag);
  }
  return flagOf(e.where()) + ": " + problem;
}

void printWarning(const std::string& text) {
  std::cerr << "warning: " << text << "\n";
}

void printLoaderWarnings(const std::string& scene, const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) printWarning(scene + ": " + w);
}

void addAtlasOptions(CLI::App& cmd, AtlasParams& atlas, OptionScope scope, bool* densityAuto,
                     uint64_t* memoryLimit) {
  const OptionGroup group(cmd, "Atlas");
  auto* tpq = scoped(cmd.add_option(flag("texels per quad"), atlas.texelsPerQuad,
                                    help(scope, "N×N texels per quad whatever its size (the thesis's mode)"))
                         ->check(within(1, 4096)),
                     scope);
  CLI::Option* density = nullptr;
  if (!densityAuto) {
    density = addChecked(cmd, scope, "texel density", atlas.density, "Texels per metre along each patch edge",
                         kPositive);
  } else {
    density = scoped(
        cmd.add_option_function<std::string>(
               flag("texel density"),
               [&atlas, densityAuto](const std::string& given) {
                 *densityAuto = given == "auto";
                 if (*densityAuto) return;
                 char* end = nullptr;
                 const double d = std::strtod(given.c_str(), &end);
                 if (end == given.c_str() || *end != '\0' || !std::isfinite(d) || !(d > 0.0) || d > 1e6)
                   throw CLI::ValidationError(
                       flag("texel density"),
                       "must be auto or texels per metre above 0, not " + printable(given));
                 atlas.density = float(d);
               },
               help(scope,
                    "Texels per metre along each patch edge, or auto (the default): more where a "
                    "first shot of the lamps finds shadow and beam edges and near "
                    "contacts, fewer where the light is flat"))
            ->type_name("T|auto")
            ->default_str(*densityAuto ? "auto" : std::to_string(int(atlas.density))),
        scope);
    tpq->each([densityAuto](const std::string&) { *densityAuto = false; });  // a fixed resolution
  }
  tpq->excludes(density);
  addMemoryOption(cmd, memoryLimit ? *memoryLimit : atlas.memoryLimit, scope);
}

void addMemoryOption(CLI::App& cmd, uint64_t& limit, OptionScope scope) {
  const OptionGroup group(cmd, "Limits");
  limit = defaultMemoryLimit();
  scoped(cmd.add_option_function<std::string>(
                flag("maximum memory"), [&limit](const std::string& text) { limit = parseByteSize(text); },
                help(scope,
                     "Refuse up front a run whose estimated memory passes this (e.g. 8G, 512M; default 75 % "
                     "of this machine's: " +
                         formatBytes(double(limit)) + ")"))
             ->check(CLI::Validator(
                 [](std::string& text) -> std::string {
                   return parseByteSize(text) > 0
                              ? ""
                              : "must be a size such as 8G or 512M, got " + printable(text);
                 },
                 "SIZE")),
         scope);
}

void addSolverOptions(CLI::App& cmd, SolverParams& solver, OptionScope scope) {
  const OptionGroup group(cmd, "Solver");
  addChecked(cmd, scope, "unshot fraction", solver.unshotFraction,
             "Stop when this fraction of the emitted power is still unshot", within(1e-9, 0.999999));
  addChecked(cmd, scope, "maximum shots", solver.maxShots, "Stop after this many shots",
             within(1, 100000000));
  scoped(addChoice(cmd, flag("visibility"), solver.visibility,
                   {{"hemisphere", Visibility::Hemisphere}, {"hemicube", Visibility::Hemicube}},
                   help(scope,
                        "hemisphere: the thesis's one-pass item buffer; hemicube: five faces, exact "
                        "straight edges")),
         scope);
  // The solver checks it against the GL limits and says why.
  scoped(cmd.add_option(flag("item buffer"), solver.itemBuffer,
                        help(scope, "Item-buffer edge in pixels (hemicube: faces of half this edge)"))
             ->capture_default_str(),
         scope);
  addChecked(cmd, scope, "item-buffer neighbourhood", solver.neighbourhood,
             "Item-buffer pixels around a receiver's own searched for its patch (1: 3x3; "
             "0: its pixel)",
             within(0, 4));
  addChecked(cmd, scope, "far-field ratio", solver.farField,
             "A shooter piece counts as one for receivers farther than this many times its "
             "radius",
             within(1.0f, 1000.0f));
  addChecked(cmd, scope, "visibility regions", solver.maxRegions,
             "Visibility regions per edge of a large shooter, each with its own item "
             "buffer: soft light through doors from large shooters, at up to N² item "
             "buffers per shot (the GL engine's weak shots: twice as many, up to 4, of "
             "half --region-size)",
             within(1, 4));
  addChecked(cmd, scope, "strong-shot regions", solver.strongShotRegions,
             "Visibility regions per edge for the strong shots, those carrying at least "
             "--strong-fraction of the emitted power (0: as --regions)",
             within(0, 4));
  addChecked(cmd, scope, "strong-shot fraction", solver.strongShotFraction,
             "Share of the emitted power that makes a shot strong", within(0.0, 1.0));
  addChecked(cmd, scope, "region size", solver.regionSize,
             "Metres per visibility region along a shooter's edge", within(0.01f, 1000.0f));
  addChecked(cmd, scope, "lamp rays", solver.lampRays,
             "Shadow rays per texel and lamp for the lamps' first shot on the CPU (16x in penumbrae), a "
             "multiple of 4; 0: the lamps shoot through item buffers like every other patch",
             CLI::Validator(
                 [](std::string& text) {
                   char* end = nullptr;
                   const long n = std::strtol(text.c_str(), &end, 10);
                   return *end == '\0' && n >= 0 && n <= 4096 && n % 4 == 0
                              ? std::string()
                              : "must be 0 or a multiple of 4 up to 4096, got " + text;
                 },
                 "0, 4, 8, ... 4096"));
  scoped(cmd.add_flag_callback(
             flag("fixed eyes"), [&solver] { solver.jitteredEyes = false; },
             help(scope,
                  "One fixed eye per visibility region, chosen clear of nearby occluders, "
                  "instead of eyes drawn by unshot power at every shot")),
         scope);
}

void addAmbientOption(CLI::App& cmd, bool& noAmbient, double& ambientShare) {
  const OptionGroup group(cmd, "Solver");
  cmd.add_flag(flag("no ambient term"), noAmbient,
               "Leave out the ambient term for the power still unshot at the stop (Cohen et al. 1988)");
  addChecked(
      cmd, OptionScope{}, "ambient share", ambientShare,
      "At the unshot stop, shoot on (cells: run more rounds) until in every cell (room) the ambient term "
      "would be at most this share of its light, so that a room lit through doors is not left mostly to "
      "the flat estimate (0: the unshot stop alone)",
      within(0.0, 1.0));
}

void addTimeLimitOption(CLI::App& cmd, double& seconds) {
  const OptionGroup group(cmd, "Limits");
  addChecked(cmd, OptionScope{}, "time limit", seconds,
             "End the bake within about this many seconds (wall clock, from its start; 0: no limit): "
             "every stage stops at its share with what it has, the files' time kept back, and the result "
             "is written marked partial in report.json",
             within(0.0, 1e9));
}

void addCellOptions(CLI::App& cmd, CellSolveParams& cells, OptionScope scope) {
  const OptionGroup group(cmd, "Cells");
  scoped(addChoice(cmd, flag("portal light"), cells.portals,
                   {{"diffuse", PortalLight::Diffuse},
                    {"directional", PortalLight::Directional},
                    {"binned", PortalLight::Binned}},
                   help(scope,
                        "Portal light with --method cells: diffuse (re-emits the irradiance as a "
                        "Lambertian area light), directional (keeps the directions the light arrived "
                        "with, as one lobe) or binned (keeps them per colour channel in 18 x 18 bins of 10 "
                        "degrees found by rays)")),
         scope);
  addChecked(cmd, scope, "portal lobe width", cells.lobeMinWidth,
             "With --portals directional: the narrowest lobe a portal texel re-emits, as the standard "
             "deviation of sin θ (about radians when small); arrivals spread wider keep their own spread",
             within(1e-3, 0.45));
  addChecked(cmd, scope, "portal bin rays", cells.portalBinRays,
             "With --portals binned: rays per portal texel that find the directions its light arrived from",
             within(64, 1048576));
  addChecked(cmd, scope, "portal density scale", cells.portalDensityScale,
             "With --method cells: the portals' texels per metre as a multiple of the solve's (a finer "
             "portal carries the edge of the light through a door)",
             within(1.0, 8.0));
  addChecked(cmd, scope, "maximum rounds", cells.maxRounds,
             "With --method cells: solve rounds (syncs) at most", within(1, 100000));
  addChecked(cmd, scope, "jobs", cells.jobs,
             "With --method cells: cells solved at once in a round, each on its own "
             "thread and OpenGL context (same result as 1)",
             within(1, 64));
}

void addDecomposeOptions(CLI::App& cmd, decomp::DecomposeParams& params, OptionScope scope) {
  const OptionGroup group(cmd, "Cells");
  // --max-memory is the atlas's option where a command has both; the command copies it here.
  params.memoryLimit = defaultMemoryLimit();
  addChecked(cmd, scope, "voxel size", params.voxelSize,
             "Voxel edge, metres, in (0, 10]; 0 = from the scene: max(0.05, cbrt(bounds volume / 4e6))",
             within(0.0, 10.0));
  addChecked(cmd, scope, "seal radius", params.sealRadius,
             "Closing radius, metres, in [0, 1]: seals cracks up to ~2 seal + 1 voxel wide",
             within(0.0, 1.0));
  addChecked(cmd, scope, "saddle ratio", params.merge.saddleRatio,
             "Merge two basins when saddle / smaller peak exceeds this (higher keeps more portals)",
             within(0.0, 1.0));
  addChecked(cmd, scope, "minimum depth", params.merge.minDepth,
             "Merge when smaller peak - saddle is below this, metres (furniture, pillars)", kNonNegative);
  addChecked(cmd, scope, "opening ratio", params.merge.openingRatio,
             "Merge when interface area / (smaller volume)^(2/3) exceeds this; 0 disables", kNonNegative);
  addChecked(cmd, scope, "minimum cell volume", params.merge.minCellVolume,
             "Cells smaller than this, m3, join a neighbour", kNonNegative);
  addChecked(cmd, scope, "outside saddle ratio", params.merge.outsideSaddleRatio,
             "Merge a room into the outside when the saddle of its opening / its peak exceeds this (exterior "
             "doors are wide)",
             within(0.0, 1.0));
  addChecked(
      cmd, scope, "storey spread", params.merge.storeySpread,
      "Groups whose mean heights are further apart than this x the sum of their heights' standard "
      "deviations are storeys: a hole in the floor between them stays a portal however wide; 0 disables",
      kNonNegative);
  addChecked(cmd, scope, "gallery floor rise", params.merge.galleryFloorRise,
             "Groups side by side whose floors stand more than this apart, metres, are a gallery and the "
             "room it overlooks: a long parapet's opening does not merge them; 0 disables",
             kNonNegative);
}

void addSppOption(CLI::App& cmd, int& spp, OptionScope scope) {
  const OptionGroup group(cmd, "Solver");
  addChecked(cmd, scope, "samples per texel", spp, "Reference paths per texel (noise falls as 1/sqrt(spp))",
             within(2, 1 << 20));
}

void addSolveDensityOption(CLI::App& cmd, float& density) {
  const OptionGroup group(cmd, "Solver");
  cmd.add_option_function<std::string>(
         "--solve-density",
         [&density](const std::string& given) {
           if (given == "auto") {
             density = kAutoSolveDensity;
             return;
           }
           char* end = nullptr;
           const double d = std::strtod(given.c_str(), &end);
           if (end == given.c_str() || *end != '\0' || !std::isfinite(d) || d < 0.0 || d > 10000.0)
             throw CLI::ValidationError("--solve-density",
                                        "must be auto or texels per metre in [0, 10000], not " + given);
           density = float(d);
         },
         "Solve the light the lamps' light leaves on the surfaces on an atlas of this many texels per metre, "
         "the lamps' own shots on the output's; 0: all on the output's atlas; auto (the default): 5 with "
         "--density auto, else half the output's density (at most 5) when the output has more than 100 000 "
         "texels, else 0; --method cells as global, but cell jobs (--plan), --only-cells and --around solve "
         "in one level")
      ->type_name("auto|T")
      ->default_str("auto");
}

void addLampCoarseningOption(CLI::App& cmd, float& coarsening) {
  const OptionGroup group(cmd, "Solver");
  addChecked(
      cmd, {}, "lamp coarsening", coarsening,
      "With --solve-density and --lamp-rays 0 (else the lamps shoot by shadow rays at every output texel): "
      "the lamps shoot first on an atlas this many times coarser than the output's (at least 10 texels per "
      "metre), then again at the output's texels only where that shot's light has an edge, a penumbra or a "
      "bend; 1: at every output texel",
      within(1.0, 1000.0));
}

void addDensityToleranceOption(CLI::App& cmd, float& tolerance) {
  const OptionGroup group(cmd, "Atlas");
  addChecked(
      cmd, {}, "density tolerance", tolerance,
      "With --density auto: the RMS miss of the lightmap's interpolation allowed over a quad, a share of "
      "its light (smaller: more texels where the lamps' light bends or has edges)",
      within(1e-4, 1.0));
}

void addMaxTexelsOption(CLI::App& cmd, size_t& maxTexels) {
  const OptionGroup group(cmd, "Atlas");
  addChecked(cmd, {}, "maximum texels", maxTexels,
             "With --density auto: the most texels the atlas (and the density pilot) lays out; past it every "
             "surface's texels per metre are scaled down alike to fit, said in one line (0: no limit)",
             within(0.0, 1e12));
}

void addCellNoiseOptions(CLI::App& cmd, CellNoiseTarget& target, OptionScope scope) {
  const OptionGroup group(cmd, "Solver");
  addChecked(cmd, scope, "cell noise", target.meanNoise,
             "Trace the texels of every cell whose mean is noisier than this (relative standard error) again "
             "with more paths, until none is or --max-spp is reached; 0: off",
             within(0.0, 1.0));
  addChecked(cmd, scope, "maximum samples per texel", target.maxSpp,
             "Paths per texel at most for --cell-noise; 0: 16 x --spp", within(0, 1 << 24));
}

CLI::Option* addMaxBouncesOption(CLI::App& cmd, int& maxBounces, OptionScope scope) {
  const OptionGroup group(cmd, "Solver");
  return addChecked(
      cmd, scope, "maximum bounces", maxBounces,
      "Bounces a reference path may take at most (Russian roulette ends most far sooner); giving "
      "it lets a scene of albedo near 1 be traced, the light past N bounces left out",
      within(1, 100000));
}

void addBoundaryOption(CLI::App& cmd, BoundaryMode& mode) {
  const OptionGroup group(cmd, "Cells");
  addChoice(
      cmd, flag("boundary"), mode, {{"coarse", BoundaryMode::Coarse}, {"dark", BoundaryMode::Dark}},
      "On demand: coarse (cells next to the baked ones are solved on a coarse atlas, so their lamps and "
      "bounces light the baked cells through the portals; not written) or dark");
}

void addViewOptions(CLI::App& cmd, ViewParams& views) {
  const OptionGroup group(cmd, "Output");
  cmd.add_option_function<std::string>(
         flag("view size"), [&views](const std::string& text) { parseViewSize(text, views); },
         "Size of the view-*.png/.exr pictures, WxH pixels (default 640 wide at the camera's aspect; the "
         "vertical field of view stays the camera's)")
      ->check(CLI::Validator(
          [](std::string& text) {
            ViewParams unused;
            return parseViewSize(text, unused);
          },
          "WxH"));
}

void addReportOption(CLI::App& cmd, std::string& dir) {
  const OptionGroup group(cmd, "Output");
  cmd.add_option(flag("report folder"), dir,
                 "Also write DIR/report.html: A's baked.glb in 3D with a per-texel error heat map against B "
                 "and the per-cell figures");
}

std::string parseViewSize(const std::string& text, ViewParams& views) {
  std::string ascii = text;
  for (size_t at = ascii.find("×"); at != std::string::npos; at = ascii.find("×")) ascii.replace(at, 2, "x");
  int w = 0, h = 0;
  char x = 0, rest = 0;
  if (std::sscanf(ascii.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X') || w < 16 ||
      w > 8192 || h < 16 || h > 8192)
    return "must be WIDTHxHEIGHT in pixels, each in [16, 8192], got " + text;
  views.width = w;
  views.height = h;
  return {};
}

glm::vec3 parsePoint(const std::string& text, const std::string& option) {
  const std::optional<std::vector<float>> values = parseNumberList(text);
  if (!values || values->size() != 3)
    throw InputError(option, "'" + text + "' is not X,Y,Z (three numbers in metres)");
  return {(*values)[0], (*values)[1], (*values)[2]};
}

// "NAME=V" or "NAME=R,G,B" (split at the last '=', so a name may hold one) → an override of NAME.
MaterialOverride parseOverride(const std::string& text, const std::string& parameter, bool emission) {
  const size_t eq = text.rfind('=');
  const std::string what = emission ? "W/m2" : "albedo";
  if (eq == std::string::npos || eq == 0)
    throw InputError(parameter, "'" + text + "' is not MATERIAL=" + what + " or MATERIAL=R,G,B");
  const std::optional<std::vector<float>> values = parseNumberList(text.substr(eq + 1));
  const bool inRange = values && std::all_of(values->begin(), values->end(),
                                             [&](float v) { return v >= 0.0f && (emission || v <= 1.0f); });
  if (!inRange)
    throw InputError(
        parameter,
        "'" + text +
            "': " + (emission ? "an emission is a number >= 0 (W/m2)" : "an albedo is a number in [0, 1]"));
  if (values->size() != 1 && values->size() != 3)
    throw InputError(parameter, "'" + text + "' is not MATERIAL=" + what + " or MATERIAL=R,G,B");
  const std::vector<float>& n = *values;
  const glm::vec3 v = n.size() == 1 ? glm::vec3(n[0]) : glm::vec3(n[0], n[1], n[2]);
  MaterialOverride o{text.substr(0, eq), std::nullopt, std::nullopt};
  (emission ? o.emission : o.albedo) = v;
  return o;
}

void addLoadOptions(CLI::App& cmd, LoadOptions& load) {
  const OptionGroup group(cmd, "Input");
  addChecked(cmd, {}, "scale", load.scale,
             "Multiply the scene's coordinates by this to get metres as it loads: a scene in Quake units "
             "(inches) takes 0.0254, centimetres 0.01, millimetres 0.001",
             within(1e-6, 1e6));
  auto* strict = cmd.add_flag(flag("strict"), load.strict,
                              "Refuse a scene with zero-area or duplicate triangles (default: drop them, "
                              "with one warning)");
  // Kept for scripts written when refusing was the default: dropping is the default now.
  const std::string repairHelp = "Drop zero-area and duplicate triangles (the default; excludes --strict)";
  cmd.add_flag(flag("repair"), repairHelp)->excludes(strict);
  cmd.add_flag_callback(
      flag("keep contacts"), [&load] { load.cutContacts = false; },
      "Keep faces whole where other geometry runs through them (default: cut there and drop the pieces "
      "inside solids, so that no lightmap chart runs across a wall, a slab or a pane)");
  cmd.add_flag(flag("outside files"), load.allowOutsideFiles,
               "Read files the scene refers to (buffers, images, mtllib) even outside its folder");
  // One value per occurrence (repeat the flag), so that it never swallows the scene argument.
  for (const bool emission : {true, false})
    cmd.add_option_function<std::vector<std::string>>(
           flag(emission ? "emit" : "albedo"),
           [&load, emission](const std::vector<std::string>& texts) {
             // Runs while CLI11 parses: its own error type, so main prints the one line.
             try {
               for (const std::string& text : texts)
                 load.overrides.push_back(parseOverride(text, emission ? "emit" : "albedo", emission));
             } catch (const InputError& e) {
               throw CLI::ValidationError(userMessage(e));
             }
           },
           emission ? "MATERIAL=W/m2 or MATERIAL=R,G,B: the material (by name) emits this, replacing the "
                      "file's emission (repeatable)"
                    : "MATERIAL=A or MATERIAL=R,G,B: the material's albedo in [0, 1], replacing the file's "
                      "(repeatable)")
        ->allow_extra_args(false);
}

void addDarkOption(CLI::App& cmd, bool& allowDark) {
  const OptionGroup group(cmd, "Input");
  cmd.add_flag(flag("dark"), allowDark,
               "Go on when nothing lights the scene (no emissive material, no punctual light, no --emit): "
               "the result is black");
}

void addSkyOptions(CLI::App& cmd, SkyRequest& sky, bool gatherRays) {
  const OptionGroup group(cmd, "Sky");
  auto* kind = addChoice(
      cmd, flag("sky"), sky.kind,
      {{"none", Sky::Kind::None}, {"uniform", Sky::Kind::Uniform}, {"cie-overcast", Sky::Kind::CieOvercast}},
      "The sky around the scene, seen through its openings: none (black), uniform, or "
      "cie-overcast (radiance Lz (1 + 2 cos theta)/3); Y is up");
  // Optional values: the library tells "not given" from 0 (a default irradiance, or a zenith radiance).
  auto optionalNumber = [&cmd, kind](std::string_view parameter, std::optional<float>& field,
                                     const std::string& text) {
    return cmd
        .add_option_function<float>(
            flag(parameter), [&field](float v) { field = v; }, text)
        ->check(kFinite)
        ->check(within(0.0, 1e12))
        ->needs(kind);
  };
  auto* irradiance =
      optionalNumber("sky irradiance", sky.horizontalIrradiance,
                     "The sky's irradiance on an open horizontal plane, W/m2 (default 15, about 10,000 lux "
                     "at 683 lm/W)");
  optionalNumber("sky zenith", sky.zenithRadiance, "The sky's radiance at the zenith, W/(m2 sr)")
      ->excludes(irradiance);
  cmd.add_option_function<std::string>(
      flag("sun"),
      [&sky](const std::string& text) {
        const std::optional<std::vector<float>> v = parseNumberList(text);
        if (!v || v->size() != 4)
          throw CLI::ValidationError(flag("sun") + ": '" + printable(text) +
                                     "' is not X,Y,Z,E (the direction towards the sun, Y up, and its "
                                     "irradiance in W/m2 on a plane facing it)");
        sky.towardsSun = glm::vec3((*v)[0], (*v)[1], (*v)[2]);
        sky.sunIrradiance = (*v)[3];
      },
      "X,Y,Z,E: a sun in the direction X,Y,Z (towards it, Y up) giving E W/m2 on a plane facing it, as a "
      "directional light named sun");
  cmd.add_option_function<std::string>(
         flag("ground albedo"),
         [&sky](const std::string& text) {
           if (text == "none") {
             sky.groundAlbedo.reset();
             return;
           }
           const std::optional<std::vector<float>> v = parseNumberList(text);
           if (!v || v->size() != 1 || !((*v)[0] >= 0.0f && (*v)[0] <= 1.0f))
             throw CLI::ValidationError(flag("ground albedo") +
                                        ": must be an albedo in [0, 1] or none, got '" + printable(text) +
                                        "'");
           sky.groundAlbedo = (*v)[0];
         },
         "A or none: the albedo of the ground at infinity below the horizon, lit by the sky and the sun "
         "(the scene's own ground, if it has one, hides it)")
      ->default_str("0.2");
  if (gatherRays)
    addChecked(cmd, OptionScope{}, "sky rays", sky.gatherRays,
               "Directions per texel the first shot gathers the sky and ground from", within(1, 65536));
}

OptionGroup::OptionGroup(CLI::App& cmd, std::string_view name)
    : cmd_(cmd), previous_(cmd.option_defaults()->get_group()) {
  cmd.option_defaults()->group(std::string(name));
}

OptionGroup::~OptionGroup() {
  cmd_.option_defaults()->group(previous_);
}

}  // namespace cpgi::cli
