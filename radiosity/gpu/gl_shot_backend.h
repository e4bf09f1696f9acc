// The GL engine's shot backend (gl_shot_engine.h), inside the gpu library: the class and what its files
// share. Its member functions live by what they do:
//   gl_shot_backend.cpp  the shot (pyramids, eyes, item buffers, gathering, statistics, selection), the
//                        loop's interface (radiosity/solve/shot_backend.h);
//   gl_shot_regions.cpp  the shooters' visibility regions: the weak and strong layouts, the region table;
//   gl_item_buffers.cpp  the scene's geometry, the item-buffer targets, culling and drawing them;
//   gl_atlas_buffers.cpp the per-texel and per-patch buffers: upload, constant uniforms, read-back.
// Requires a current OpenGL 4.5 context on the calling thread.
#pragma once

#include <array>
#include <chrono>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/gpu/gl.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "radiosity/solve/shot_backend.h"
#include "radiosity/solve/solver_params.h"

namespace cpgi::gl_engine {

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
constexpr int kMaxRegions = 4;  // per chart edge, as the settings may ask (SolverParams::maxRegions)
// Per chart edge in a reflector's strong shot (strongReflectorLayout), and so the most eyes (item-buffer
// layers) a shot has: common.glsl's MAX_REGIONS.
constexpr int kMaxStrongRegions = 8;
constexpr int kMaxEyes = kMaxStrongRegions * kMaxStrongRegions;
constexpr GLuint kListHeader = 16;  // count + 3 dispatch arguments, in bytes
constexpr int kCoverageStride = 4;  // shot_coverage.comp's STRIDE

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

// glm matrices are column-major; these are uploaded so that `M * v` in GLSL gives dot(row_i, v).
inline glm::mat3 rowsOf(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  return glm::transpose(glm::mat3(a, b, c));
}

inline GLint loc(const gl::Program& p, const char* name) {
  return glGetUniformLocation(p.get(), name);
}
inline void set(const gl::Program& p, const char* n, int v) {
  glProgramUniform1i(p.get(), loc(p, n), v);
}
inline void setU(const gl::Program& p, const char* n, GLuint v) {
  glProgramUniform1ui(p.get(), loc(p, n), v);
}
inline void set(const gl::Program& p, const char* n, float v) {
  glProgramUniform1f(p.get(), loc(p, n), v);
}
inline void set(const gl::Program& p, const char* n, glm::vec3 v) {
  glProgramUniform3f(p.get(), loc(p, n), v.x, v.y, v.z);
}
inline void set(const gl::Program& p, const char* n, const glm::mat3& m) {
  glProgramUniformMatrix3fv(p.get(), loc(p, n), 1, GL_FALSE, &m[0][0]);
}

inline GLuint groups(size_t n, size_t size) {
  return static_cast<GLuint>((n + size - 1) / size);
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

}  // namespace cpgi::gl_engine

namespace cpgi {

// Compiled one program after another, the clock checked between them (llvmpipe compiles each in tens to
// hundreds of milliseconds of CPU, seconds of wall on a loaded machine): `complete` stays false when
// `deadline` came first (solver_programs.cpp).
struct SolverPrograms::Set {
  Set(const gl_engine::ProgramDefines& d, std::chrono::steady_clock::time_point deadline);
  gl::Program cull[3];  ///< item_cull.comp's passes
  gl::Program item, compact, finish, pyramid, receive, stats, tileStats, select, pickEyes, rescale, coverage;
  bool complete = false;  ///< every program compiled
};

}  // namespace cpgi

namespace cpgi::gl_engine {

/// The programs' #defines for `params` (solver_programs.cpp).
ProgramDefines programDefines(const SolveConfig& params);

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
             const std::vector<glm::vec4>* emissionLobes);

  // ShotBackend (gl_shot_backend.cpp).
  EnergyTotals start() override;
  ShooterChoice next() override {
    return {sel_.winner, channelSum(sel_.winnerUnshot), sel_.winnerPending != 0,
            sel_.winner >= 0 && sel_.winnerUnshot.w > 0.0f};
  }
  ShotGathered shoot(const ShooterChoice& choice, bool strong, bool lamp) override;
  double deliver(float scale) override;
  TexelSums sums() const override {
    return {channelSum(sel_.unshot), channelSum(sel_.incident), channelSum(sel_.absorbed)};
  }
  std::vector<glm::vec3> radiosity() override { return readRadiosity(); }
  std::vector<glm::vec3> residual() override { return readResidual(); }
  int shotEyes(int patch, bool strong) const override;
  std::vector<double> patchUnshot() override;
  void readBack(const ReadBack& what, SolveResult& result, Context& ctx) override;

  /// What the eyes of the last shot saw (shot_coverage.comp), each region's share weighted by its unshot
  /// power: covered by receivers facing them, and open (nothing there).
  struct Coverage {
    double covered = 1.0, open = 0.0;
  };
  const Coverage& lastCoverage() const { return lastCoverage_; }
  void reportPasses(Context& ctx) const { clock_.report(ctx); }
  void countShotsFrom(uint32_t n) { shotCount_ = n; }

 private:
  static double channelSum(const glm::vec4& v) { return double(v.r) + double(v.g) + double(v.b); }

  // The shot (gl_shot_backend.cpp).
  GpuSelection startGl();
  GpuSelection shootGl(int shooter, bool strong, bool lamp);
  void buildPyramids(int shooter, const ShooterLayout& l, const Patch& p, int baseRegions, int replicas,
                     const gl::Program& pyramidProgram, bool withLobes);
  void drawEyes(int shooter, const ShooterLayout& l, int regions, int baseRegions,
                std::vector<glm::vec3>& eyes);
  struct ShotGeometry {
    int shooter;
    const ShooterLayout& layout;
    const Patch& patch;
    const glm::mat3& toShooter;
    int baseRegions, regions, replicas;
  };
  void gather(const gl::Program& receiveProgram, const ShotGeometry& g, const std::vector<glm::vec3>& eyes,
              bool lamp, bool binnedShot, bool withLobes);
  GpuSelection rescaleLastShot(int shooter, float scale);
  size_t coverageColumns() const { return size_t(itemSize_ + kCoverageStride - 1) / kCoverageStride; }
  Coverage readCoverage(int regions);
  void runTileStats(size_t first, size_t end, int shooter, bool onlyVisible);
  void runStats(int shooter);
  GpuSelection select();

  // The shooters' visibility regions (gl_shot_regions.cpp).
  LayoutParams weakLayout() const;
  LayoutParams strongLayout() const;
  LayoutParams strongReflectorLayout() const;
  const ShooterLayout& layoutOf(int patch, bool strong, bool lamp) const;
  int mostEyes() const;
  int strongRegions() const {
    return params_.strongShotRegions > 0 ? params_.strongShotRegions : params_.maxRegions;
  }
  std::vector<ShooterLayout> allLayouts() const;
  int uploadRegions(const ShooterLayout& l, const Patch& p, int replicas);
  static glm::ivec2 levelDims(glm::ivec2 size, int k);
  static int topLevel(glm::ivec2 size);
  size_t maxPyramidNodes(const std::vector<uint8_t>* only = nullptr) const;

  // The item buffers (gl_item_buffers.cpp).
  void uploadGeometry();
  void makeItemBuffer();
  void cullItemFaces(std::span<const glm::vec3> eyes, const glm::mat3& toShooter);
  void renderItemBuffer(int layer, const glm::vec3& eye, const glm::mat3& toShooter);
  bool culled() const { return params_.visibility == Visibility::Hemicube && params_.cullItemBuffers; }

  // The atlas's buffers (gl_atlas_buffers.cpp).
  bool receivesIn(const Patch& p, int x, int y) const;
  void uploadAtlas();
  void uploadDirectional(const std::vector<glm::vec4>* lobes);
  void addDirectLight(std::span<const glm::vec3> direct, std::vector<glm::vec4>& exitance,
                      std::vector<glm::vec4>& incident) const;
  bool shotByRays(size_t patch) const { return !params_.shotLamps.empty() && params_.shotLamps[patch]; }
  void setConstantUniforms();
  std::vector<glm::vec3> readImage(const gl::Buffer& b) const;
  std::vector<glm::vec3> readRadiosity() const { return readImage(radiosity_); }
  std::vector<glm::vec3> readResidual() const { return readImage(residual_); }
  std::vector<glm::vec3> readIncident() const { return readImage(incident_); }
  std::vector<uint8_t> readLampFlags() const;
  std::vector<glm::vec4> readArrivals() const;

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
  // The weak shots' (weakLayout), the lamps' strong ones (strongLayout) and the other strong ones
  // (strongReflectorLayout, or strongLayout's where that has more regions).
  std::vector<ShooterLayout> layouts_, strongLayouts_, strongReflectorLayouts_;
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

}  // namespace cpgi::gl_engine
