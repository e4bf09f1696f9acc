#include "radiosity/gpu/gl_shot_engine.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>

#include "core/error.h"
#include "core/memory_limit.h"
#include "radiosity/gpu/gl.h"
#include "radiosity/gpu/item_mesh.h"
#include "radiosity/gpu/shader_library.h"
#include "radiosity/lightmap/direct_light.h"
#include "radiosity/lightmap/lamp_light.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "radiosity/lightmap/sky_light.h"
#include "radiosity/solve/emission_bins.h"
#include "radiosity/solve/progressive_loop.h"
#include "radiosity/solve/shot_backend.h"

namespace cpgi {
namespace {

// Mirrors of the std430 structs in shaders/common.glsl and select_shooter.comp.
struct GpuPatch {
  glm::ivec4 rect, tiles;
  glm::vec4 origin, texelU, texelV, normal;
};
struct GpuStats {
  glm::vec4 unshot, incident, absorbed;
};
struct GpuNode {
  glm::vec4 centreArea, radiosityRadius, moments;
};
constexpr int kMaxLevels = 14;  // MAX_LEVELS: pyramids of charts up to 2^14 texels on an edge
struct GpuRegion {
  glm::ivec4 rect, top;
  int32_t levelOffset[kMaxLevels + 2];
};
struct GpuSelection {
  int32_t winner, winnerPending, pad0, pad1;
  glm::vec4 winnerUnshot, unshot, incident, absorbed;
};
static_assert(sizeof(GpuPatch) == 96 && sizeof(GpuNode) == 48 && sizeof(GpuRegion) == 96 &&
              sizeof(GpuSelection) == 80);

constexpr int kTile = 8;                         // receiver work groups are kTile × kTile texels
constexpr uint32_t kNotReceiving = 0x80000000u;  // receive.comp's texel flag: ShotShape::receivers
constexpr int kMaxRegions = 4;                   // per chart edge; common.glsl's MAX_REGIONS is its square
constexpr GLuint kListHeader = 16;               // count + 3 dispatch arguments, in bytes
constexpr int kCoverageStride = 4;               // shot_coverage.comp's STRIDE

// Shader-storage binding points (shaders/*.comp).
// The per-texel atlas data lives in buffers too (shaders/atlas_buffers.glsl), indexed like the atlas.
enum Ssbo : GLuint {
  kPatches = 0,
  kStats = 1,
  kVisible = 2,
  kTiles = 3,
  kTileList = 4,
  kPatchList = 5,
  kRegions = 6,
  kPending = 7,
  kSelection = 8,
  kPosArea = 9,
  kNormalPatch = 10,
  kAlbedo = 11,
  kRadiosity = 12,
  kResidual = 13,
  kIncident = 14,
  kNodes = 15,
  kTileStats = 16,
  kEmissionLobes = 17,
  kArrivals = 18,
  kNodeLobes = 19,
  kEyes = 20,
  kShotGain = 21,
  kCoverage = 22,
  kTexelFlags = 23,
  kItemPositions = 24,  // shaders/item_cull.comp
  kItemIndices = 25,
  kFaceMasks = 26,
  kChunkSlots = 27,
  kFaceIndices = 28,
  kFaceDraws = 29
};

struct Face {
  glm::vec3 right, up, forward;
};
// The hemicube in shooter coordinates (z = shooter normal); must match visibility.glsl.
constexpr Face kFaces[5] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},
    {{0, -1, 0}, {0, 0, 1}, {-1, 0, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
};

// glm matrices are column-major; these are uploaded so that `M * v` in GLSL gives dot(row_i, v).
glm::mat3 rowsOf(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  return glm::transpose(glm::mat3(a, b, c));
}

GLint loc(const gl::Program& p, const char* name) {
  return glGetUniformLocation(p.get(), name);
}
void set(const gl::Program& p, const char* n, int v) {
  glProgramUniform1i(p.get(), loc(p, n), v);
}
void setU(const gl::Program& p, const char* n, GLuint v) {
  glProgramUniform1ui(p.get(), loc(p, n), v);
}
void set(const gl::Program& p, const char* n, float v) {
  glProgramUniform1f(p.get(), loc(p, n), v);
}
void set(const gl::Program& p, const char* n, glm::vec3 v) {
  glProgramUniform3f(p.get(), loc(p, n), v.x, v.y, v.z);
}
void set(const gl::Program& p, const char* n, const glm::mat3& m) {
  glProgramUniformMatrix3fv(p.get(), loc(p, n), 1, GL_FALSE, &m[0][0]);
}

GLuint groups(size_t n, size_t size) {
  return static_cast<GLuint>((n + size - 1) / size);
}

constexpr size_t kCullChunk = 32;  // triangles per invocation of item_cull.comp (its CHUNK)

void checkParams(const SolverParams& p, const LightmapAtlas& atlas, const EglContext& context) {
  const int maxTexture = context.maxTextureSize();
  if (p.itemBuffer < 16 || p.itemBuffer % 2 != 0 || p.itemBuffer > maxTexture ||
      (p.visibility == Visibility::Hemicube && p.itemBuffer / 2 * 3 > maxTexture))
    throw InputError("item buffer", "must be even, at least 16 and fit GL_MAX_TEXTURE_SIZE (" +
                                        std::to_string(maxTexture) + ")");
  if (p.neighbourhood < 0 || p.neighbourhood > 4)
    throw InputError("item-buffer neighbourhood", "must be in 0..4");
  if (!(p.unshotFraction > 0.0 && p.unshotFraction < 1.0))
    throw InputError("unshot fraction", "must be a fraction in (0, 1)");
  if (p.maxShots < 1) throw InputError("maximum shots", "must be at least 1");
  if (!(p.farField >= 1.0f)) throw InputError("far-field ratio", "must be at least 1");
  if (p.maxRegions < 1 || p.maxRegions > kMaxRegions)
    throw InputError("solver", "visibility regions per edge must be in 1..4");
  if (p.strongShotRegions < 0 || p.strongShotRegions > kMaxRegions)
    throw InputError("solver", "visibility regions per edge of a strong shot must be in 0..4");
  if (!(p.strongShotFraction >= 0.0 && p.strongShotFraction <= 1.0))
    throw InputError("solver", "the strong-shot fraction must be in [0, 1]");
  if (!(p.regionSize > 0.0f)) throw InputError("solver", "region size must be positive");
  if (atlas.width > maxTexture || atlas.height > maxTexture)
    throw InputError("atlas", "the lightmap atlas (" + std::to_string(atlas.width) + "x" +
                                  std::to_string(atlas.height) + ") exceeds GL_MAX_TEXTURE_SIZE " +
                                  std::to_string(maxTexture) + "; lower the resolution");
  // Every per-texel buffer (radiosity, residual, incident, ...) is one RGBA32F shader storage block of the
  // whole atlas. Past the driver's limit a shader reads and writes only part of it (llvmpipe: 128 MiB, 8.4
  // million texels), or the upload fails with GL_OUT_OF_MEMORY: refused before any buffer is made.
  const double blockBytes = double(atlas.texelCount()) * sizeof(glm::vec4);
  const int64_t maxBlock = context.maxStorageBlockSize();
  if (maxBlock > 0 && blockBytes > double(maxBlock))
    throw InputError(
        atlas.sizeParameter,
        "the lightmap atlas of " + std::to_string(atlas.width) + "x" + std::to_string(atlas.height) +
            " texels needs GPU buffers of " + formatBytes(blockBytes) +
            ", more than this driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE " + formatBytes(double(maxBlock)) +
            " (" + std::to_string(maxBlock / int64_t(sizeof(glm::vec4))) + " texels); lower the resolution");
}

// Per-pass wall times when SolverParams::profilePasses is set: glFinish, then charge the time since the
// previous mark to `stage`.
class PassClock {
 public:
  explicit PassClock(bool on) : on_(on) {}
  void mark(const char* stage) {
    if (!on_) return;
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    seconds_[stage] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  void restart() {
    if (on_) glFinish(), last_ = std::chrono::steady_clock::now();
  }
  void report(Context& ctx) const {
    for (const auto& [stage, s] : seconds_) ctx.addTiming(std::string("solve: ") + stage, s);
  }

 private:
  bool on_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  std::map<std::string, double> seconds_;
};

// The #defines each program is compiled with for `params`. Every SolverParams field that changes a
// program's text goes here, and so into the cache key.
struct ProgramDefines {
  std::vector<std::string> item, receive, pyramid;
  std::string key() const {
    std::string k;
    for (const auto* list : {&item, &receive, &pyramid}) {
      for (const std::string& d : *list) k += d + ",";
      k += ";";
    }
    return k;
  }
};

// The user's settings and the caller's controls together, as the passes read them.
struct SolveConfig : SolverParams {
  bool directionalEmission = false;          ///< ShotShape::directionalEmission
  bool arrivalMoments = true;                ///< ShotShape::arrivalMoments
  std::span<const float> emissionBins = {};  ///< ShotShape::emissionBins
  std::span<const uint8_t> receivers = {};   ///< ShotShape::receivers
  bool readLampFlags = false;                ///< ShotShape::readLampFlags
  /// The first shot made before the solve (shot_engine.h): its irradiance, its power, the lamps it spent.
  std::span<const glm::vec3> direct = {};
  double directEmitted = 0.0;
  std::span<const char> shotLamps = {};
};

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

}  // namespace

struct SolverPrograms::Set {
  // Compiled one program after another, the clock checked between them (llvmpipe compiles each in tens
  // to hundreds of milliseconds of CPU, seconds of wall on a loaded machine): `complete` stays false when
  // `deadline` came first.
  Set(const ProgramDefines& d, std::chrono::steady_clock::time_point deadline) {
    const bool hemisphere = std::find(d.item.begin(), d.item.end(), "HEMISPHERE") != d.item.end();
    const std::vector<std::string> itemShaders =
        hemisphere ? std::vector<std::string>{"item.vert", "item_hemisphere.tesc", "item_hemisphere.tese",
                                              "item.frag"}
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
  gl::Program cull[3];  ///< item_cull.comp's passes
  gl::Program item, compact, finish, pyramid, receive, stats, tileStats, select, pickEyes, rescale, coverage;
  bool complete = false;  ///< every program compiled
};

SolverPrograms::SolverPrograms() = default;
SolverPrograms::~SolverPrograms() = default;

const SolverPrograms::Set* SolverPrograms::get(const SolverParams& settings, bool directionalEmission,
                                               bool binnedEmission,
                                               std::chrono::steady_clock::time_point deadline) {
  SolveConfig config{settings};
  config.directionalEmission = directionalEmission;
  const float oneBin = 1.0f;
  if (binnedEmission) config.emissionBins = std::span<const float>(&oneBin, 1);
  const ProgramDefines defines = programDefines(config);
  std::unique_ptr<Set>& set = sets_[defines.key()];
  if (!set) {
    auto made = std::make_unique<Set>(defines, deadline);
    if (!made->complete) return nullptr;  // compiled again, whole, by the next solve that gets the time
    set = std::move(made);
  }
  return set.get();
}

namespace {

double channelSum(const glm::vec4& v) {
  return double(v.r) + double(v.g) + double(v.b);
}

// The progressive loop's shots by item buffers on the GL device (shot_backend.h): the atlas's state lives
// in GPU buffers, the next shooter is chosen there (select_shooter.comp), and the loop reads the sums back.
class GlShotBackend final : public ShotBackend {
 public:
  // Every uniform a program reads is set in setUp() or before each pass, so programs may come from earlier
  // solves.
  // `binned`: the programs for binned shooters (SolveConfig::emissionBins), null without bins. `plain`:
  // the programs without directional emission for shooters with no lobe, null where every shot must note
  // the arrival moments.
  GlShotBackend(const Scene& scene, const LightmapAtlas& atlas, const SolveConfig& params,
                const SolverPrograms::Set& programs, const SolverPrograms::Set* binned,
                const SolverPrograms::Set* plain)
      : scene_(scene),
        atlas_(atlas),
        params_(params),
        itemProgram_(programs.item),
        compactProgram_(programs.compact),
        finishProgram_(programs.finish),
        pyramidProgram_(programs.pyramid),
        receiveProgram_(programs.receive),
        statsProgram_(programs.stats),
        tileStatsProgram_(programs.tileStats),
        selectProgram_(programs.select),
        pickEyesProgram_(programs.pickEyes),
        rescaleProgram_(programs.rescale),
        coverageProgram_(programs.coverage),
        cullPrograms_{&programs.cull[0], &programs.cull[1], &programs.cull[2]},
        binnedPyramid_(binned ? &binned->pyramid : nullptr),
        binnedReceive_(binned ? &binned->receive : nullptr),
        plainPyramid_(plain ? &plain->pyramid : nullptr),
        plainReceive_(plain ? &plain->receive : nullptr),
        clock_(params.profilePasses) {}

  // The set-up, step by step, the clock checked between the steps and within the layouts (per batch of
  // patches): false when `deadline` came first, the buffers made so far freed with the backend.
  // `emissionLobes`: per texel, null for none.
  bool setUp(Context& ctx, std::chrono::steady_clock::time_point deadline,
             const std::vector<glm::vec4>* emissionLobes) {
    const auto late = [&] { return std::chrono::steady_clock::now() >= deadline; };
    ctx.progress("set-up", 0.2, "the gl engine: the shooters' eyes");
    layouts_ = layoutShooters(scene_, atlas_, weakLayout(), deadline);
    if (layouts_.size() < atlas_.patches.size()) return false;
    // Strong shots at strongShotRegions per edge whatever the shooter's size (within its texels): a
    // small lamp still gets several eyes, so with drawn eyes (jitteredEyes) its light through a narrow
    // door, or out of a housing, is a stratified estimate rather than one texel's view. Where the settings
    // ask for as many as --regions, the settings' own layout.
    const LayoutParams strong = strongRegions() != params_.maxRegions
                                    ? LayoutParams{1e-3f, strongRegions()}
                                    : LayoutParams{params_.regionSize, params_.maxRegions};
    strongLayouts_ = layoutShooters(scene_, atlas_, strong, deadline);
    if (strongLayouts_.size() < atlas_.patches.size()) return false;
    if (late()) return false;
    ctx.progress("set-up", 0.5, "the gl engine: the atlas's buffers");
    uploadAtlas();
    if (params_.directionalEmission) uploadDirectional(emissionLobes);
    if (late()) return false;
    ctx.progress("set-up", 0.7, "the gl engine: the scene's geometry");
    uploadGeometry();
    if (late()) return false;
    makeItemBuffer();
    setConstantUniforms();
    gl::check("solver setup");
    return true;
  }

  // ShotBackend. The books start from the atlas's unshot light, plus the first shot made before the solve
  // (params_.direct: its power emitted and shot; what it left reflected is in the unshot sum).
  EnergyTotals start() override {
    sel_ = startGl();
    EnergyTotals e;
    e.emitted = channelSum(sel_.unshot);
    if (!params_.direct.empty()) {
      double reflected = 0.0;
      for (size_t i = 0; i < params_.direct.size(); ++i)
        if (atlas_.patch[i] >= 0) {
          const glm::dvec3 r = glm::dvec3(atlas_.albedo[i]) * glm::dvec3(params_.direct[i]);
          reflected += (r.r + r.g + r.b) * atlas_.area[i];
        }
      e.shot = params_.directEmitted;
      e.emitted += e.shot - reflected;
    }
    const TexelSums now = sums();
    e.unshot = now.unshot, e.received = now.received, e.absorbed = now.absorbed;
    return e;
  }
  ShooterChoice next() override {
    return {sel_.winner, channelSum(sel_.winnerUnshot), sel_.winnerPending != 0,
            sel_.winner >= 0 && sel_.winnerUnshot.w > 0.0f};
  }
  ShotGathered shoot(const ShooterChoice& choice, bool strong, bool lamp) override {
    receivedBefore_ = channelSum(sel_.incident);
    lastShooter_ = choice.patch;
    sel_ = shootGl(choice.patch, strong, lamp);
    return {channelSum(sel_.incident) - receivedBefore_, lastCoverage_.covered, lastCoverage_.open};
  }
  // The shot has landed already; a scale other than 1 rescales what it gave (rescale_shot.comp).
  double deliver(float scale) override {
    if (scale != 1.0f) sel_ = rescaleLastShot(lastShooter_, scale);
    return channelSum(sel_.incident) - receivedBefore_;
  }
  TexelSums sums() const override {
    return {channelSum(sel_.unshot), channelSum(sel_.incident), channelSum(sel_.absorbed)};
  }
  std::vector<glm::vec3> radiosity() override { return readRadiosity(); }
  std::vector<glm::vec3> residual() override { return readResidual(); }
  // The patch statistics' unshot sums (patch_stats.comp), 48 bytes a patch: far less than the texels.
  // An item buffer a region (a lamp's strong shot draws its regions again: shootGl's replicas).
  int shotEyes(int patch, bool strong) const override {
    const ShooterLayout& l =
        strong && !strongLayouts_.empty() ? strongLayouts_[size_t(patch)] : layouts_[size_t(patch)];
    return l.regions.x * l.regions.y;
  }
  std::vector<double> patchUnshot() override {
    std::vector<GpuStats> stats(atlas_.patches.size());
    glGetNamedBufferSubData(stats_.get(), 0, GLsizeiptr(stats.size() * sizeof(GpuStats)), stats.data());
    std::vector<double> unshot(stats.size());
    for (size_t p = 0; p < stats.size(); ++p) unshot[p] = double(stats[p].unshot.w);
    return unshot;
  }
  void readBack(const ReadBack& what, SolveResult& result, Context& ctx) override {
    reportPasses(ctx);
    auto t = ctx.time("solve: read back");
    result.radiosity = readRadiosity();
    if (what.transfer) result.incident = readIncident(), result.residual = readResidual();
    if (what.arrivals) result.arrivals = readArrivals();
    if (what.lampFlags) result.lampFlags = readLampFlags();
    for (size_t i = 0; i < result.radiosity.size(); ++i)
      if (atlas_.patch[i] < 0) {
        result.radiosity[i] = glm::vec3(0.0f);
        if (what.transfer) result.incident[i] = result.residual[i] = glm::vec3(0.0f);
        if (!result.arrivals.empty()) result.arrivals[i] = glm::vec4(0.0f);
      }
  }

  // Statistics of every patch from the initial state, then the first selection.
  GpuSelection startGl() {
    std::vector<uint32_t> all(kListHeader / 4 + atlas_.patches.size());
    all[0] = uint32_t(atlas_.patches.size());
    for (size_t i = 0; i < atlas_.patches.size(); ++i) all[kListHeader / 4 + i] = uint32_t(i);
    glNamedBufferSubData(patchList_.get(), 0, GLsizeiptr(all.size() * 4), all.data());
    glUseProgram(finishProgram_.get());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    runTileStats(0, tileCount_, -1, false);
    runStats(-1);
    return select();
  }

  /// `strong`: the shot carries at least SolverParams::strongShotFraction of the emitted power. `lamp`: an
  /// emitter's own shot, whose receivers crossed by a shadow or beam edge, or near it, are resampled
  /// (receive.comp).
  GpuSelection shootGl(int shooter, bool strong, bool lamp) {
    const ShooterLayout& l = strong && !strongLayouts_.empty() ? strongLayouts_[shooter] : layouts_[shooter];
    const Patch& p = atlas_.patches[shooter];
    const int baseRegions = l.regions.x * l.regions.y;
    // A lamp with fewer texels than a strong shot may have regions (--strong-regions per edge, squared)
    // is seen from that many eyes, each region's on a grid over it down to points within a texel (a power
    // of two per region, pick_eyes.comp), each eye carrying an equal share. One eye at a small lamp's
    // centre cut its beam out of a housing with a hard edge, where the lamp's area gives a penumbra as wide
    // as the beam: the edge landed on the door frame and lit it a texel wider than it is (spot-door's room
    // A +16 %). Lamps only: small strong walls' shots drew 4× the item buffers (seed1: 12–15 CPU s, not 10).
    int replicas = 1;
    const int strongEyes = strongRegions() * strongRegions();
    while (lamp && strong && params_.jitteredEyes && 2 * replicas * baseRegions <= strongEyes) replicas *= 2;
    const int regions = baseRegions * replicas;
    std::vector<glm::vec3> eyes;
    for (int i = 0; i < replicas; ++i)
      for (const glm::vec3& e : l.eyes) eyes.push_back(e + l.normal * eyeOffset_);
    clock_.restart();
    ++shotCount_;
    // The item buffer turned about the normal by a golden-ratio angle per shot (with drawn eyes). Pixel
    // centres aligned with a scene's axis-aligned edges otherwise: from a floor's eye, a pixel whose centre
    // ray ran along a wall's top edge, where both rooms' ceilings meet it, went to the far room's ceiling
    // by the rasterizer's tie rule, and that ceiling counted as seen through the wall (issue 11: 6.7e-4 of
    // the light into a closed room behind a zero-thickness wall; openings B +1.9 % at 20 texels/m).
    glm::vec3 tangent = l.tangent, bitangent = l.bitangent;
    if (params_.jitteredEyes) {
      const double turn = 6.283185307179586 * std::fmod(0.6180339887498949 * double(shotCount_), 1.0);
      const float c = float(std::cos(turn)), s = float(std::sin(turn));
      tangent = c * l.tangent + s * l.bitangent;
      bitangent = -s * l.tangent + c * l.bitangent;
    }
    const glm::mat3 toShooter = rowsOf(tangent, bitangent, l.normal);

    // Sub-shooters from the residual before it is zeroed: the regions' pyramids, level by level.
    const bool binnedShot = binnedReceive_ && hasBins_[shooter];
    const bool plainShot = plainReceive_ && !hasLobes_[shooter];
    const gl::Program& receiveProgram = binnedShot  ? *binnedReceive_
                                        : plainShot ? *plainReceive_
                                                    : receiveProgram_;
    buildPyramids(shooter, l, p, baseRegions, replicas,
                  binnedShot  ? *binnedPyramid_
                  : plainShot ? *plainPyramid_
                              : pyramidProgram_,
                  !plainShot);
    if (params_.jitteredEyes) drawEyes(shooter, l, regions, baseRegions, eyes);
    clock_.mark("shooter pyramid");

    const GLuint zero = 0;
    glClearNamedBufferData(visible_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    if (culled()) cullItemFaces(std::span(eyes).first(size_t(regions)), toShooter);
    for (int r = 0; r < regions; ++r) renderItemBuffer(r, eyes[r], toShooter);
    clock_.mark(lamp ? "item buffers (lamp shots)" : "item buffers");
    set(coverageProgram_, "uToShooter", toShooter);
    glUseProgram(coverageProgram_.get());
    glDispatchCompute(groups(coverageColumns(), 16), GLuint(regions), 1);
    clock_.mark("coverage");

    // The item-buffer fragments flag the patches they show (item.frag); list those patches' tiles.
    // Shader writes (the fragments' flags, last shot's list counters) must land before these updates.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const GLuint one = 1;
    glNamedBufferSubData(visible_.get(), GLintptr(shooter) * 4, 4, &one);  // its residual is zeroed below
    const uint32_t header[4] = {0, 0, 1, 1};
    glNamedBufferSubData(tileList_.get(), 0, sizeof header, header);
    glNamedBufferSubData(patchList_.get(), 0, sizeof header, header);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(compactProgram_.get());
    glDispatchCompute(groups(std::max(tileCount_, atlas_.patches.size()), 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(finishProgram_.get());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    clock_.mark("visible lists");

    gather(receiveProgram, {shooter, l, p, toShooter, baseRegions, regions, replicas}, eyes, lamp, binnedShot,
           !plainShot);
    clock_.mark(lamp ? "receive (lamp shots)" : "receive");

    runTileStats(0, tileCount_, shooter, true);
    runStats(shooter);
    clock_.mark("patch statistics");
    GpuSelection s = select();
    clock_.mark("select");
    lastCoverage_ = readCoverage(regions);
    return s;
  }

  // The regions' residual pyramids of `shooter` (shooter_pyramid.comp), level by level.
  void buildPyramids(int shooter, const ShooterLayout& l, const Patch& p, int baseRegions, int replicas,
                     const gl::Program& pyramidProgram, bool withLobes) {
    const int levels = uploadRegions(l, p, replicas);
    set(pyramidProgram, "uShooter", shooter);
    set(pyramidProgram, "uRegionCount", baseRegions);  // replicas share their region's pyramid
    set(pyramidProgram, "uTexelRadius", l.texelRadius);
    if (params_.directionalEmission && withLobes) set(pyramidProgram, "uShooterNormal", l.normal);
    glUseProgram(pyramidProgram.get());
    for (int k = 1; k <= levels; ++k) {
      set(pyramidProgram, "uLevel", k);
      glDispatchCompute(groups(levelNodes_[k], 64), 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }

  // Each region's eye drawn by power from the pyramid just built (pick_eyes.comp), into `eyes`.
  void drawEyes(int shooter, const ShooterLayout& l, int regions, int baseRegions,
                std::vector<glm::vec3>& eyes) {
    set(pickEyesProgram_, "uShooter", shooter);
    set(pickEyesProgram_, "uRegionCount", regions);
    set(pickEyesProgram_, "uBaseRegions", baseRegions);
    setU(pickEyesProgram_, "uShot", GLuint(shotCount_));
    glUseProgram(pickEyesProgram_.get());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::array<glm::vec4, kMaxRegions * kMaxRegions> drawn{};
    glGetNamedBufferSubData(eyes_.get(), 0, GLsizeiptr(regions * sizeof(glm::vec4)), drawn.data());
    for (int r = 0; r < regions; ++r)
      if (drawn[r].w > 0.0f) eyes[r] = glm::vec3(drawn[r]) + l.normal * eyeOffset_;
  }

  // Every visible receiver tile gathers the shot (receive.comp).
  struct ShotGeometry {
    int shooter;
    const ShooterLayout& layout;
    const Patch& patch;
    const glm::mat3& toShooter;
    int baseRegions, regions, replicas;
  };
  void gather(const gl::Program& receiveProgram, const ShotGeometry& g, const std::vector<glm::vec3>& eyes,
              bool lamp, bool binnedShot, bool withLobes) {
    const int shooter = g.shooter, baseRegions = g.baseRegions, regions = g.regions, replicas = g.replicas;
    const ShooterLayout& l = g.layout;
    const Patch& p = g.patch;
    set(receiveProgram, "uShooter", shooter);
    set(receiveProgram, "uRegionCount", regions);
    set(receiveProgram, "uRegionShare", 1.0f / float(replicas));
    set(receiveProgram, "uLampShot", int(lamp));
    glProgramUniform3fv(receiveProgram.get(), loc(receiveProgram, "uEyes"), regions, &eyes[0].x);
    std::vector<glm::vec3> regionOrigins;
    for (int r = 0; r < regions; ++r) {
      const glm::ivec4 c = l.rects[size_t(r % baseRegions)];
      regionOrigins.push_back(p.origin + float(c.x) * p.texelU + float(c.y) * p.texelV);
    }
    glProgramUniform3fv(receiveProgram.get(), loc(receiveProgram, "uRegionOrigins"), regions,
                        &regionOrigins[0].x);
    set(receiveProgram, "uToShooter", g.toShooter);
    set(receiveProgram, "uShooterNormal", l.normal);
    if (params_.directionalEmission && withLobes)
      set(receiveProgram, "uShooterLobes", int(hasLobes_[shooter]));
    if (binnedShot) {  // the shooter's bin frame, as the CPU lays its bins out
      const BinFrame frame = binFrame(l.normal);
      set(receiveProgram, "uBinT1", frame.t1);
      set(receiveProgram, "uBinT2", frame.t2);
    }
    set(receiveProgram, "uTexelU", p.texelU);
    set(receiveProgram, "uTexelV", p.texelV);
    set(receiveProgram, "uTexelRadius", l.texelRadius);
    glUseProgram(receiveProgram.get());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileList_.get());
    glDispatchComputeIndirect(4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  /// What the eyes of the last shot saw (shot_coverage.comp), each region's share weighted by its unshot
  /// power: covered by receivers facing them, and open (nothing there).
  struct Coverage {
    double covered = 1.0, open = 0.0;
  };
  const Coverage& lastCoverage() const { return lastCoverage_; }

  /// Scales what the last shot (of `shooter`) gave every receiver by `scale` (rescale_shot.comp),
  /// then the statistics and the selection again.
  GpuSelection rescaleLastShot(int shooter, float scale) {
    set(rescaleProgram_, "uShooter", shooter);
    set(rescaleProgram_, "uScale", scale);
    glUseProgram(rescaleProgram_.get());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileList_.get());
    glDispatchComputeIndirect(4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    runTileStats(0, tileCount_, shooter, true);
    runStats(shooter);
    return select();
  }

  void reportPasses(Context& ctx) const { clock_.report(ctx); }
  void countShotsFrom(uint32_t n) { shotCount_ = n; }

  size_t coverageColumns() const { return size_t(itemSize_ + kCoverageStride - 1) / kCoverageStride; }

  Coverage readCoverage(int regions) {
    const size_t perRegion = coverageColumns();
    std::vector<glm::vec4> columns(size_t(regions) * perRegion);
    glGetNamedBufferSubData(coverage_.get(), 0, GLsizeiptr(columns.size() * sizeof(glm::vec4)),
                            columns.data());
    Coverage weighted{0.0, 0.0};
    double power = 0.0;
    for (int r = 0; r < regions; ++r) {
      GpuNode top{};
      glGetNamedBufferSubData(nodes_.get(), GLintptr(topNode_[r] * sizeof(GpuNode)), sizeof top, &top);
      const double p = double(top.centreArea.w) *
                       (double(top.radiosityRadius.r) + top.radiosityRadius.g + top.radiosityRadius.b);
      glm::dvec3 sum(0.0);
      for (size_t x = 0; x < perRegion; ++x) sum += glm::dvec3(columns[r * perRegion + x]);
      if (!(p > 0.0) || !(sum.z > 0.0)) continue;
      weighted.covered += p * sum.x / sum.z;
      weighted.open += p * sum.y / sum.z;
      power += p;
    }
    if (!(power > 0.0)) return Coverage{};
    return Coverage{weighted.covered / power, weighted.open / power};
  }

  std::vector<glm::vec3> readRadiosity() const { return readImage(radiosity_); }
  std::vector<uint8_t> readLampFlags() const {
    std::vector<uint32_t> words(atlas_.texelCount());
    glGetNamedBufferSubData(texelFlags_.get(), 0, GLsizeiptr(words.size() * 4), words.data());
    gl::check("read back");
    std::vector<uint8_t> flags(words.size());
    for (size_t i = 0; i < words.size(); ++i) flags[i] = uint8_t(words[i] & 0xFFu);
    return flags;
  }
  std::vector<glm::vec3> readResidual() const { return readImage(residual_); }
  std::vector<glm::vec3> readIncident() const { return readImage(incident_); }
  std::vector<glm::vec4> readArrivals() const {
    std::vector<glm::vec4> v(atlas_.texelCount());
    glGetNamedBufferSubData(arrivals_.get(), 0, GLsizeiptr(v.size() * sizeof(glm::vec4)), v.data());
    gl::check("read back");
    return v;
  }

 private:
  // Whether the kTile × kTile tile at (x, y) of chart p holds a texel that receives (tiles that do not
  // are left out of every shot's work list: compact.comp).
  bool receivesIn(const Patch& p, int x, int y) const {
    if (params_.receivers.empty()) return true;
    for (int j = y; j < std::min(y + kTile, p.h); ++j)
      for (int i = x; i < std::min(x + kTile, p.w); ++i)
        if (params_.receivers[size_t(p.y + j) * size_t(atlas_.width) + size_t(p.x + i)]) return true;
    return false;
  }

  // The region table (common.glsl, Region) of one shooter; fills levelNodes_ (nodes per level over all
  // regions) and returns the highest level.
  int uploadRegions(const ShooterLayout& l, const Patch& p, int replicas) {
    std::vector<GpuRegion> table(l.rects.size());
    int levels = 1;
    for (size_t r = 0; r < table.size(); ++r) {
      const glm::ivec4 c = l.rects[r];
      table[r].rect = glm::ivec4(p.x + c.x, p.y + c.y, p.x + c.z, p.y + c.w);
      table[r].top.x = topLevel(glm::ivec2(c.z - c.x, c.w - c.y));
      levels = std::max(levels, table[r].top.x);
    }
    int32_t offset = 0;
    std::fill(levelNodes_.begin(), levelNodes_.end(), 0);
    for (int k = 1; k <= levels; ++k)
      for (GpuRegion& g : table) {
        if (k > g.top.x) continue;
        const glm::ivec2 d = levelDims(glm::ivec2(g.rect.z - g.rect.x, g.rect.w - g.rect.y), k);
        g.levelOffset[k] = offset;
        offset += d.x * d.y;
        levelNodes_[k] += size_t(d.x) * d.y;
      }
    // Replica i of region r is entry i × regions + r, with r's rectangle and pyramid.
    const size_t base = table.size();
    for (int i = 1; i < replicas; ++i)
      for (size_t r = 0; r < base; ++r) table.push_back(table[r]);
    glNamedBufferSubData(regions_.get(), 0, GLsizeiptr(table.size() * sizeof(GpuRegion)), table.data());
    topNode_.clear();
    for (const GpuRegion& g : table) topNode_.push_back(g.levelOffset[g.top.x]);
    return levels;
  }

  static glm::ivec2 levelDims(glm::ivec2 size, int k) { return (size + ((1 << k) - 1)) >> k; }
  static int topLevel(glm::ivec2 size) {
    int k = 1;
    while (glm::any(glm::greaterThan(levelDims(size, k), glm::ivec2(1)))) ++k;
    return k;
  }

  // Nodes the largest shooter's pyramids need (levels 1 and up, all regions); of the patches flagged in
  // `only` when given.
  size_t maxPyramidNodes(const std::vector<uint8_t>* only = nullptr) const {
    size_t most = 0;
    const std::vector<ShooterLayout> all = allLayouts();
    for (size_t i = 0; i < all.size(); ++i) {
      if (only && !(*only)[i % layouts_.size()]) continue;
      const ShooterLayout& l = all[i];
      size_t n = 0;
      for (const glm::ivec4& c : l.rects) {
        const glm::ivec2 size(c.z - c.x, c.w - c.y);
        for (int k = 1, top = topLevel(size); k <= top; ++k)
          n += size_t(levelDims(size, k).x) * levelDims(size, k).y;
      }
      most = std::max(most, n);
    }
    return std::max<size_t>(most, 1);
  }

  // Tile sums of tiles [first, end) (of the visible patches only when `onlyVisible`); the shooter's
  // residual is zeroed on the way.
  void runTileStats(size_t first, size_t end, int shooter, bool onlyVisible) {
    if (end <= first) return;
    setU(tileStatsProgram_, "uFirstTile", GLuint(first));
    setU(tileStatsProgram_, "uEndTile", GLuint(end));
    set(tileStatsProgram_, "uShooter", shooter);
    set(tileStatsProgram_, "uOnlyVisible", onlyVisible ? 1 : 0);
    glUseProgram(tileStatsProgram_.get());
    glDispatchCompute(groups(end - first, 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  void runStats(int shooter) {
    set(statsProgram_, "uShooter", shooter);
    glUseProgram(statsProgram_.get());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, patchList_.get());
    glDispatchComputeIndirect(4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  GpuSelection select() {
    glUseProgram(selectProgram_.get());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GpuSelection s{};
    glGetNamedBufferSubData(selection_.get(), 0, sizeof s, &s);
    gl::check("shot");
    return s;
  }

  // Per hemicube face, the triangles that may show in it from any of `eyes` (shaders/item_cull.comp), as
  // the index lists and draw commands renderItemBuffer draws.
  void cullItemFaces(std::span<const glm::vec3> eyes, const glm::mat3& toShooter) {
    // The planes a·local > b beyond which item.vert's projection clips, in shooter coordinates; from every
    // eye at once, a·(toShooter p) > b + max over the eyes of a·(toShooter eye).
    std::array<glm::vec4, 26> planes;
    float scale = 0.0f;
    for (const glm::vec3& e : eyes) scale = std::max(scale, glm::length(toShooter * e));
    auto plane = [&](glm::vec3 a, float b) {
      float most = -std::numeric_limits<float>::infinity();
      for (const glm::vec3& e : eyes) most = std::max(most, glm::dot(a, toShooter * e));
      return glm::vec4(a, b + most);
    };
    planes[0] = plane(glm::vec3(0, 0, -1), 0.0f);  // behind the shooter: gl_ClipDistance[0] < 0
    for (size_t f = 0; f < 5; ++f) {
      const glm::vec3 r = kFaces[f].right, u = kFaces[f].up, w = kFaces[f].forward;
      // y as item.vert has it: v.y on the top face, 2 v.y − w on the half side faces.
      const glm::vec3 y = f == 0 ? u : 2.0f * u - w;
      planes[1 + 5 * f] = plane(r - w, 0.0f);   // x > w
      planes[2 + 5 * f] = plane(-r - w, 0.0f);  // x < −w
      planes[3 + 5 * f] = plane(y - w, 0.0f);   // y > w
      planes[4 + 5 * f] = plane(-y - w, 0.0f);  // y < −w
      planes[5 + 5 * f] = plane(-w, -near_);    // w < near
    }
    const GLuint chunks = groups(size_t(triangleCount_), kCullChunk);
    for (int pass = 0; pass < 3; ++pass) {
      const gl::Program& p = *cullPrograms_[size_t(pass)];
      if (pass == 0) {
        set(p, "uToShooter", toShooter);
        glProgramUniform4fv(p.get(), loc(p, "uPlanes"), GLsizei(planes.size()), &planes[0].x);
        set(p, "uScale", scale + near_);
      }
      glUseProgram(p.get());
      glDispatchCompute(pass == 1 ? 5 : groups(chunks, 64), 1, 1);
      glMemoryBarrier(pass < 2 ? GL_SHADER_STORAGE_BARRIER_BIT
                               : GL_ELEMENT_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
  }

  void renderItemBuffer(int layer, const glm::vec3& eye, const glm::mat3& toShooter) {
    glNamedFramebufferTextureLayer(fbo_.get(), GL_COLOR_ATTACHMENT0, items_.get(), 0, layer);
    glNamedFramebufferTextureLayer(fbo_.get(), GL_COLOR_ATTACHMENT1, distances_.get(), 0, layer);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    const GLint none = -1;
    const GLfloat far = 1.0f, nothing = 1e30f;  // a pixel showing nothing cannot shadow
    glClearNamedFramebufferiv(fbo_.get(), GL_COLOR, 0, &none);
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 1, &nothing);
    glClearNamedFramebufferfv(fbo_.get(), GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_CLIP_DISTANCE0);
    glUseProgram(itemProgram_.get());
    set(itemProgram_, "uEye", eye);
    set(itemProgram_, "uToShooter", toShooter);
    glBindVertexArray(vao_.get());
    if (params_.visibility == Visibility::Hemisphere) {
      glViewport(0, 0, itemSize_, itemSize_);
      glPatchParameteri(GL_PATCH_VERTICES, 3);
      glDrawElements(GL_PATCHES, indexCount_, GL_UNSIGNED_INT, nullptr);
    } else {
      if (culled()) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, faceDraws_.get());
      const int f = itemSize_, half = f / 2;
      for (int i = 0; i < 5; ++i) {
        set(itemProgram_, "uFace", rowsOf(kFaces[i].right, kFaces[i].up, kFaces[i].forward));
        set(itemProgram_, "uHalfFace", i == 0 ? 0 : 1);
        if (i == 0)
          glViewport(0, 0, f, f);
        else
          glViewport(0, f + (i - 1) * half, f, half);
        if (culled())
          glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                 reinterpret_cast<const void*>(uintptr_t(i) * 5 * sizeof(GLuint)));
        else
          glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
      }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  // Punctual lights (radiosity/lightmap/direct_light.h): their shot is done, so the solve starts after it,
  // as after any shot: ρE reflected in radiosity and residual, E received.
  void addDirectLight(std::span<const glm::vec3> direct, std::vector<glm::vec4>& exitance,
                      std::vector<glm::vec4>& incident) const {
    for (size_t i = 0; i < direct.size() && i < exitance.size(); ++i) {
      if (atlas_.patch[i] < 0) continue;
      exitance[i] += glm::vec4(atlas_.albedo[i] * direct[i], 0.0f);
      incident[i] = glm::vec4(direct[i], 0.0f);
    }
  }

  bool shotByRays(size_t patch) const { return !params_.shotLamps.empty() && params_.shotLamps[patch]; }

  std::vector<glm::vec3> readImage(const gl::Buffer& b) const {
    std::vector<glm::vec4> v(atlas_.texelCount());
    glGetNamedBufferSubData(b.get(), 0, GLsizeiptr(v.size() * sizeof(glm::vec4)), v.data());
    gl::check("read back");
    std::vector<glm::vec3> out(v.size());
    for (size_t i = 0; i < v.size(); ++i) out[i] = glm::vec3(v[i]);
    return out;
  }

  void uploadAtlas() {
    const int w = atlas_.width;
    const size_t n = atlas_.texelCount();
    std::vector<glm::vec4> posArea(n), normalPatch(n), albedo(n), emission(n, glm::vec4(0.0f));
    for (size_t i = 0; i < n; ++i) {
      posArea[i] = glm::vec4(atlas_.position[i], atlas_.area[i]);
      normalPatch[i] = glm::vec4(atlas_.normal[i], float(atlas_.patch[i]));
      albedo[i] = glm::vec4(atlas_.albedo[i], 0.0f);
      if (atlas_.patch[i] >= 0) emission[i] = glm::vec4(atlas_.emission[i], 0.0f);
    }
    // Patch IDs travel as floats in uNormalPatch.w.
    if (atlas_.patches.size() >= (1u << 24)) throw InputError("atlas", "more than 2^24 patches");
    auto texels = [&](gl::Buffer& b, const std::vector<glm::vec4>& data, Ssbo binding) {
      b = gl::makeBuffer(n * sizeof(glm::vec4), data.data());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b.get());
    };
    texels(posArea_, posArea, kPosArea);
    texels(normalPatch_, normalPatch, kNormalPatch);
    texels(albedo_, albedo, kAlbedo);
    std::vector<glm::vec4> incident(n, glm::vec4(0.0f));
    if (!params_.direct.empty()) addDirectLight(params_.direct, emission, incident);
    texels(radiosity_, emission, kRadiosity);
    if (!params_.shotLamps.empty())  // lamps shot by rays (lamp_light.h): their light shows, but is spent
      for (size_t i = 0; i < n; ++i)
        if (atlas_.patch[i] >= 0 && params_.shotLamps[size_t(atlas_.patch[i])])
          emission[i] -= glm::vec4(atlas_.emission[i], 0.0f);
    texels(residual_, emission, kResidual);
    texels(incident_, incident, kIncident);
    shotGain_ = gl::makeBuffer(n * sizeof(glm::vec4), nullptr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShotGain, shotGain_.get());
    // receive.comp's per-texel word: bit 31 set where the texel does not receive (ShotShape::receivers),
    // the low bits what the lamps' shots found there (LampFlag).
    const bool flags = !params_.receivers.empty() || params_.readLampFlags;
    std::vector<uint32_t> texelFlags(flags ? n : 1, 0u);
    if (!params_.receivers.empty())
      for (size_t i = 0; i < n; ++i) texelFlags[i] = params_.receivers[i] ? 0u : kNotReceiving;
    texelFlags_ = gl::makeBuffer(texelFlags.size() * 4, texelFlags.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTexelFlags, texelFlags_.get());

    const size_t np = atlas_.patches.size();
    std::vector<GpuPatch> patches(np);
    std::vector<uint32_t> pending(np, 0);
    std::vector<glm::ivec4> tiles;
    firstTile_.assign(np + 1, 0);
    for (size_t i = 0; i < np; ++i) {
      const Patch& p = atlas_.patches[i];
      firstTile_[i] = tiles.size();
      for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x) {
          const size_t t = size_t(p.y + y) * w + p.x + x;
          if (atlas_.patch[t] == int(i) && atlas_.emission[t] != glm::vec3(0.0f) && !shotByRays(i))
            pending[i] = 1;
        }
      for (int y = 0; y < p.h; y += kTile)
        for (int x = 0; x < p.w; x += kTile)
          tiles.push_back({p.x + x, p.y + y, int(i), receivesIn(p, x, y) ? 0 : 1});
      patches[i].rect = {p.x, p.y, p.w, p.h};
      patches[i].tiles = {int(firstTile_[i]), int(tiles.size() - firstTile_[i]), 0, 0};
      patches[i].origin = glm::vec4(p.origin, 0.0f);
      patches[i].texelU = glm::vec4(p.texelU, 0.0f);
      patches[i].texelV = glm::vec4(p.texelV, 0.0f);
      patches[i].normal = glm::vec4(p.normal, 0.0f);
    }
    firstTile_[np] = tiles.size();
    tileCount_ = tiles.size();
    auto ssbo = [](gl::Buffer& b, Ssbo binding, size_t bytes, const void* data) {
      b = gl::makeBuffer(bytes, data);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b.get());
    };
    ssbo(patches_, kPatches, np * sizeof(GpuPatch), patches.data());
    ssbo(stats_, kStats, np * sizeof(GpuStats), nullptr);
    ssbo(visible_, kVisible, np * 4, nullptr);
    ssbo(tiles_, kTiles, tiles.size() * sizeof(glm::ivec4), tiles.data());
    ssbo(tileStats_, kTileStats, tiles.size() * sizeof(GpuStats), nullptr);
    ssbo(tileList_, kTileList, kListHeader + tiles.size() * 4, nullptr);
    ssbo(patchList_, kPatchList, kListHeader + np * 4, nullptr);
    ssbo(regions_, kRegions, kMaxRegions * kMaxRegions * sizeof(GpuRegion), nullptr);
    ssbo(nodes_, kNodes, maxPyramidNodes() * sizeof(GpuNode), nullptr);
    for (const ShooterLayout& l : allLayouts())
      for (const glm::ivec4& c : l.rects)
        if (topLevel(glm::ivec2(c.z - c.x, c.w - c.y)) > kMaxLevels)
          throw InputError("atlas", "a chart wider than 2^14 texels");
    ssbo(pending_, kPending, np * 4, pending.data());
    ssbo(selection_, kSelection, sizeof(GpuSelection), nullptr);
    ssbo(eyes_, kEyes, kMaxRegions * kMaxRegions * sizeof(glm::vec4), nullptr);
    ssbo(coverage_, kCoverage, kMaxRegions * kMaxRegions * size_t(params_.itemBuffer) * sizeof(glm::vec4),
         nullptr);
    const GLuint zero = 0;
    glClearNamedBufferData(stats_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  }

  // Per-texel emission lobes (Lambertian when none are given), binned texels' bins after them (a binned
  // lobe's slot turned into where its bins start, shaders/directional.glsl) and zeroed arrival moments.
  void uploadDirectional(const std::vector<glm::vec4>* lobes) {
    const size_t n = atlas_.texelCount();
    if (lobes && lobes->size() != n) throw InputError("solver", "emission lobes must be one per atlas texel");
    const std::span<const float> bins = params_.emissionBins;
    if (bins.size() % kBinSlotFloats != 0)
      throw InputError("solver", "emission bins must come in whole slots");
    const size_t slots = bins.size() / kBinSlotFloats, perSlot = kBinSlotFloats / 4;
    if (n + slots * perSlot >= (size_t(1) << 24))
      throw InputError("solver", "too many texels and emission bins for the lobes' float indices");
    std::vector<glm::vec4> data(n + slots * perSlot, glm::vec4(0.0f));
    hasLobes_.assign(atlas_.patches.size(), 0);
    hasBins_.assign(atlas_.patches.size(), 0);
    if (lobes)
      for (size_t i = 0; i < n; ++i) {
        glm::vec4 lobe = (*lobes)[i];
        if (lobe.w < 0.0f) {
          const size_t slot = size_t(-lobe.w) - 1;
          if (slot >= slots) throw InputError("solver", "a binned emission lobe names a slot past the bins");
          lobe.w = -float(n + slot * perSlot + 1);
        }
        data[i] = lobe;
        if (atlas_.patch[i] >= 0 && lobe != glm::vec4(0.0f)) hasLobes_[atlas_.patch[i]] = 1;
        if (atlas_.patch[i] >= 0 && lobe.w < 0.0f) hasBins_[atlas_.patch[i]] = 1;
      }
    if (!bins.empty()) std::memcpy(&data[n], bins.data(), bins.size() * sizeof(float));
    emissionLobes_ = gl::makeBuffer(data.size() * sizeof(glm::vec4), data.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEmissionLobes, emissionLobes_.get());
    arrivals_ = gl::makeBuffer(n * sizeof(glm::vec4), nullptr);
    const float zero = 0.0f;
    glClearNamedBufferData(arrivals_.get(), GL_R32F, GL_RED, GL_FLOAT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kArrivals, arrivals_.get());
    // Binned: after one lobe per node, the bins of the nodes of a binned shooter (shaders/directional.glsl,
    // uNodeBins), sized for the largest binned shooter only (portals, not a merged floor).
    const size_t nodes = maxPyramidNodes(), binNodes = bins.empty() ? 0 : maxPyramidNodes(&hasBins_);
    nodeLobes_ = gl::makeBuffer((nodes + binNodes * perSlot) * sizeof(glm::vec4), nullptr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNodeLobes, nodeLobes_.get());
    if (!bins.empty()) {
      if (binNodes >= (size_t(1) << 24) || nodes + binNodes * perSlot >= (size_t(1) << 31))
        throw InputError("solver", "a binned shooter too large for binned emission's indices");
      set(*binnedPyramid_, "uNodeBins", int(nodes));
      set(*binnedReceive_, "uNodeBins", int(nodes));
    }
  }

  void uploadGeometry() {
    const ItemMesh mesh = buildItemMesh(scene_, atlas_);
    indexCount_ = GLsizei(mesh.indices.size());
    positionBuffer_ = gl::makeBuffer(mesh.positions.size() * sizeof(glm::vec3), mesh.positions.data(), 0);
    idBuffer_ = gl::makeBuffer(mesh.patches.size() * 4, mesh.patches.data(), 0);
    normalBuffer_ = gl::makeBuffer(mesh.normals.size() * sizeof(glm::vec3), mesh.normals.data(), 0);
    indexBuffer_ = gl::makeBuffer(mesh.indices.size() * 4, mesh.indices.data(), 0);
    triangleCount_ = indexCount_ / 3;
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    vao_ = gl::VertexArray(vao);
    if (!culled()) {
      glVertexArrayElementBuffer(vao, indexBuffer_.get());
    } else {  // the hemicube's faces draw the culled lists (cullItemFaces)
      const size_t chunks = groups(size_t(triangleCount_), kCullChunk);
      auto ssbo = [](gl::Buffer& b, Ssbo binding, size_t bytes) {
        b = gl::makeBuffer(std::max<size_t>(bytes, 4), nullptr);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b.get());
      };
      ssbo(faceMasks_, kFaceMasks, size_t(triangleCount_) * 4);
      ssbo(chunkSlots_, kChunkSlots, 5 * chunks * 4);
      ssbo(faceIndices_, kFaceIndices, 5 * size_t(indexCount_) * 4);
      ssbo(faceDraws_, kFaceDraws, 5 * 5 * 4);
      if (indexCount_ > 0) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kItemPositions, positionBuffer_.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kItemIndices, indexBuffer_.get());
      }
      glVertexArrayElementBuffer(vao, faceIndices_.get());
    }
    glVertexArrayVertexBuffer(vao, 0, positionBuffer_.get(), 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayVertexBuffer(vao, 1, idBuffer_.get(), 0, 4);
    glVertexArrayAttribIFormat(vao, 1, 1, GL_INT, 0);
    glVertexArrayAttribBinding(vao, 1, 1);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayVertexBuffer(vao, 2, normalBuffer_.get(), 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(vao, 2, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 2, 2);
    glEnableVertexArrayAttrib(vao, 2);

    const Bounds b = scene_.bounds();
    const float diagonal = std::max(glm::length(b.size()), 1e-3f);
    far_ = 2.0f * diagonal;
    // Drawn eyes (pick_eyes.comp) may sit a few millimetres from a wall (a lamp's edge texel in its
    // housing): a near plane of 1e-3 × diagonal (9 mm in spot-door) cut such walls open and let the lamp
    // light the room through them (global rel. RMSE 128 %).
    near_ = 1e-4f * diagonal;
    eyeOffset_ = 1e-4f * diagonal;
  }

  void makeItemBuffer() {
    int w, h;
    if (params_.visibility == Visibility::Hemisphere) {
      itemSize_ = params_.itemBuffer;
      w = h = itemSize_;
    } else {
      itemSize_ = params_.itemBuffer / 2 + (params_.itemBuffer / 2) % 2;  // face edge, even
      w = itemSize_;
      h = itemSize_ * 3;  // top face, then four half-height side faces
    }
    // One layer per shooter region.
    GLuint items = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &items);
    items_ = gl::Texture(items);
    const int perEdge = std::max(weakLayout().maxRegions, strongRegions());
    glTextureStorage3D(items, 1, GL_R32I, w, h, perEdge * perEdge);
    glTextureParameteri(items, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // else incomplete for texelFetch
    glTextureParameteri(items, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    // The distance from the eye of what each pixel shows (item.frag), for the receivers' plane test.
    GLuint distances = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &distances);
    distances_ = gl::Texture(distances);
    glTextureStorage3D(distances, 1, GL_R32F, w, h, perEdge * perEdge);
    glTextureParameteri(distances, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(distances, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    depth_ = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, w, h);
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    fbo_ = gl::Framebuffer(fbo);
    glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT0, items, 0, 0);
    glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT1, distances, 0, 0);
    const GLenum outputs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, outputs);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw SystemError("OpenGL: the item-buffer framebuffer (R32I + R32F + depth) is incomplete");
    glBindTextureUnit(0, items_.get());
    glBindTextureUnit(1, distances_.get());
  }

  void setConstantUniforms() {
    set(itemProgram_, "uFar", far_);
    set(itemProgram_, "uNear", near_);
    if (params_.visibility == Visibility::Hemisphere) set(itemProgram_, "uItemSize", itemSize_);
    for (const gl::Program* p :
         {&receiveProgram_, &tileStatsProgram_, &pyramidProgram_, &pickEyesProgram_, &rescaleProgram_})
      set(*p, "uAtlasWidth", atlas_.width);
    for (const gl::Program* p : {binnedPyramid_, plainPyramid_})
      if (p) set(*p, "uAtlasWidth", atlas_.width);
    for (const gl::Program* receive : {&receiveProgram_, binnedReceive_, plainReceive_}) {
      if (!receive) continue;
      set(*receive, "uAtlasWidth", atlas_.width);
      set(*receive, "uItemSize", itemSize_);
      set(*receive, "uNeighbourhood", params_.neighbourhood);
      set(*receive, "uPlaneSlack", eyeOffset_);
      set(*receive, "uFarField", params_.farField);
      set(*receive, "uMasked", int(!params_.receivers.empty()));
      set(*receive, "uWriteFlags", int(params_.readLampFlags));
    }
    set(coverageProgram_, "uItemSize", itemSize_);
    setU(compactProgram_, "uTiles", GLuint(tileCount_));
    setU(compactProgram_, "uPatches", GLuint(atlas_.patches.size()));
    set(selectProgram_, "uPatches", int(atlas_.patches.size()));
    for (const gl::Program* p : cullPrograms_) {
      setU(*p, "uTriangles", GLuint(triangleCount_));
      setU(*p, "uIndexCount", GLuint(indexCount_));
    }
  }

  const Scene& scene_;
  const LightmapAtlas& atlas_;
  SolveConfig params_;
  const gl::Program &itemProgram_, &compactProgram_, &finishProgram_, &pyramidProgram_, &receiveProgram_,
      &statsProgram_, &tileStatsProgram_, &selectProgram_, &pickEyesProgram_, &rescaleProgram_,
      &coverageProgram_;
  std::array<const gl::Program*, 3> cullPrograms_;     ///< item_cull.comp's passes
  const gl::Program *binnedPyramid_, *binnedReceive_;  ///< for binned shooters; null without bins
  const gl::Program *plainPyramid_, *plainReceive_;    ///< for shooters with no lobe; null: not used
  gl::Buffer posArea_, normalPatch_, albedo_, radiosity_, residual_, incident_, emissionLobes_, arrivals_,
      nodeLobes_;
  gl::Buffer coverage_;  ///< per region and sampled item-buffer column: (covered, open, total) weight
  std::vector<int32_t> topNode_;  ///< per region of the last shot, its top pyramid node
  Coverage lastCoverage_;
  gl::Buffer shotGain_;            ///< per texel, what the last shot gave it (rescale_shot.comp)
  gl::Buffer texelFlags_;          ///< per texel, receive.comp's flags (one word when unused)
  std::vector<uint8_t> hasLobes_;  ///< directional: per patch, whether any of its texels has a lobe
  std::vector<uint8_t> hasBins_;   ///< binned: per patch, whether any of its texels is binned
  gl::Texture items_, distances_, depth_;
  gl::Buffer patches_, stats_, visible_, tiles_, tileList_, patchList_, regions_, nodes_, pending_,
      selection_, eyes_;
  std::array<size_t, kMaxLevels + 2> levelNodes_{};
  gl::Buffer tileStats_;
  std::vector<size_t>
      firstTile_;  // per patch, then the total: its tiles are [firstTile_[p], firstTile_[p + 1])
  gl::Buffer positionBuffer_, idBuffer_, normalBuffer_, indexBuffer_;
  gl::Buffer faceMasks_, chunkSlots_, faceIndices_, faceDraws_;  ///< item_cull.comp's, hemicube only
  gl::VertexArray vao_;
  gl::Framebuffer fbo_;
  std::vector<ShooterLayout> layouts_, strongLayouts_;  // the weak shots' (weakLayout) and the strong ones'
  bool culled() const { return params_.visibility == Visibility::Hemicube && params_.cullItemBuffers; }
  int strongRegions() const {
    return params_.strongShotRegions > 0 ? params_.strongShotRegions : params_.maxRegions;
  }
  // The weak shots' regions: half the settings' size, twice their count per edge (within kMaxRegions). A
  // region's eye decides for the whole region whether a receiver sees it, and gives it the region's whole
  // unoccluded light. A receiver behind a door sees only a ceiling's or a wall's far part through it (the
  // wall above the door hides the near part), where the form factor is smallest, so the region's whole
  // light overstates what passes: a 4 m × 3 m ceiling shooting into the room behind a door delivered
  // 1.057 of the exact transfer at 2 × 2 regions, 1.004 at 4 × 4 (DoorTransfer), and plan 4's rooms
  // behind three and four doors came out +12 % and +22 %. The rays engine gates a receiver near a region
  // piece by piece instead (ray_shot.cpp, nearRays), which item buffers cannot.
  LayoutParams weakLayout() const {
    return LayoutParams{0.5f * params_.regionSize, std::min(2 * params_.maxRegions, kMaxRegions)};
  }
  std::vector<ShooterLayout> allLayouts() const {
    std::vector<ShooterLayout> all = layouts_;
    all.insert(all.end(), strongLayouts_.begin(), strongLayouts_.end());
    return all;
  }
  PassClock clock_;
  GpuSelection sel_{};         ///< the selection and sums after the last pass
  double receivedBefore_ = 0;  ///< the received sum before the last shot
  int lastShooter_ = -1;
  GLsizei indexCount_ = 0, triangleCount_ = 0;
  size_t tileCount_ = 0;
  uint32_t shotCount_ = 0;  ///< shots so far, the seed of the eyes' draw
  int itemSize_ = 0;
  float far_ = 1.0f, near_ = 1e-3f, eyeOffset_ = 1e-4f;
};

}  // namespace

namespace {

std::unique_ptr<ShotBackend> makeGlBackend(const Scene& scene, const LightmapAtlas& atlas,
                                           const SolverParams& settings, const ShotShape& shape,
                                           const FirstShot& first, const EglContext& context,
                                           SolverPrograms& programs, Context& ctx,
                                           std::chrono::steady_clock::time_point deadline) {
  SolveConfig params{settings};
  params.directionalEmission = shape.directionalEmission;
  params.arrivalMoments = shape.arrivalMoments;
  params.emissionBins = shape.emissionBins;
  params.receivers = shape.receivers;
  params.readLampFlags = shape.readLampFlags;
  params.direct = first.irradiance;
  params.directEmitted = first.emitted;
  params.shotLamps = first.spentEmitters;
  checkParams(params, atlas, context);
  if (atlas.patches.empty()) return nullptr;
  // Each step null or false past the deadline: no backend then (ShotEngine::backend).
  ctx.progress("set-up", 0.0, "the gl engine: its programs");
  const SolverPrograms::Set* base = programs.get(params, params.directionalEmission, false, deadline);
  const bool binnedToo = params.directionalEmission && !params.emissionBins.empty();
  const SolverPrograms::Set* binned = binnedToo ? programs.get(params, true, true, deadline) : nullptr;
  const bool plainToo = params.directionalEmission && !params.arrivalMoments;
  const SolverPrograms::Set* plain = plainToo ? programs.get(params, false, false, deadline) : nullptr;
  if (!base || (binnedToo && !binned) || (plainToo && !plain)) return nullptr;
  const std::vector<glm::vec4> lobes(shape.emissionLobes.begin(), shape.emissionLobes.end());
  auto backend = std::make_unique<GlShotBackend>(scene, atlas, params, *base, binned, plain);
  if (!backend->setUp(ctx, deadline, lobes.empty() ? nullptr : &lobes)) return nullptr;
  ctx.progress("set-up", 1.0, "the gl engine");
  // Lamps shot by rays count as shots here, so that the reflectors' shots draw the eyes and turns they
  // would after the lamps' item-buffer shots: measured, a different draw alone moved seed1's room B by 1 %.
  const auto rayShots = std::count(first.spentEmitters.begin(), first.spentEmitters.end(), 1);
  backend->countShotsFrom(shape.firstShotNumber + uint32_t(rayShots));
  return backend;
}

}  // namespace

GlShotEngine::GlShotEngine(const EglContext& gl) : gl_(gl) {}

GlShotEngine::GlShotEngine(std::unique_ptr<EglContext> own) : own_(std::move(own)), gl_(*own_) {}

GlShotEngine::~GlShotEngine() = default;

std::unique_ptr<ShotBackend> GlShotEngine::backend(const Scene& scene, const LightmapAtlas& atlas,
                                                   const SolverParams& settings, const ShotShape& shape,
                                                   const FirstShot& first, Context& ctx,
                                                   std::chrono::steady_clock::time_point deadline) {
  return makeGlBackend(scene, atlas, settings, shape, first, gl_, programs_, ctx, deadline);
}

std::unique_ptr<ShotEngine> GlShotEngine::forThisThread() const {
  return std::unique_ptr<ShotEngine>(new GlShotEngine(EglContext::sibling(gl_)));
}

SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                             const EglContext& gl, Context& ctx, const SolveControls& controls,
                             const ShotShape& shape) {
  GlShotEngine engine(gl);
  return solveProgressive(scene, atlas, settings, engine, ctx, controls, shape);
}

}  // namespace cpgi
