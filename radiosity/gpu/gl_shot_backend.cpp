// The GL engine's shot (gl_shot_backend.h): the shooter's residual pyramids and eyes, its item buffers,
// every visible receiver's gather, the statistics and the next shooter's selection; and the progressive
// loop's interface to it (radiosity/solve/shot_backend.h).
#include <algorithm>
#include <array>
#include <cmath>

#include "radiosity/gpu/gl_shot_backend.h"
#include "radiosity/solve/emission_bins.h"

namespace cpgi::gl_engine {

bool GlShotBackend::setUp(Context& ctx, std::chrono::steady_clock::time_point deadline,
                          const std::vector<glm::vec4>* emissionLobes) {
  const auto late = [&] { return std::chrono::steady_clock::now() >= deadline; };
  ctx.progress("set-up", 0.2, "the gl engine: the shooters' eyes");
  layouts_ = layoutShooters(scene_, atlas_, weakLayout(), deadline);
  if (layouts_.size() < atlas_.patches.size()) return false;
  strongLayouts_ = layoutShooters(scene_, atlas_, strongLayout(), deadline);
  if (strongLayouts_.size() < atlas_.patches.size()) return false;
  strongReflectorLayouts_ = layoutShooters(scene_, atlas_, strongReflectorLayout(), deadline);
  if (strongReflectorLayouts_.size() < atlas_.patches.size()) return false;
  for (size_t i = 0; i < strongLayouts_.size(); ++i) {
    const glm::ivec2 fine = strongReflectorLayouts_[i].regions, coarse = strongLayouts_[i].regions;
    if (fine.x * fine.y <= coarse.x * coarse.y) strongReflectorLayouts_[i] = strongLayouts_[i];
  }
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

// The books start from the atlas's unshot light, plus the first shot made before the solve
// (params_.direct: its power emitted and shot; what it left reflected is in the unshot sum).
EnergyTotals GlShotBackend::start() {
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

ShotGathered GlShotBackend::shoot(const ShooterChoice& choice, bool strong, bool lamp) {
  receivedBefore_ = channelSum(sel_.incident);
  lastShooter_ = choice.patch;
  sel_ = shootGl(choice.patch, strong, lamp);
  return {channelSum(sel_.incident) - receivedBefore_, lastCoverage_.covered, lastCoverage_.open};
}

// The shot has landed already; a scale other than 1 rescales what it gave (rescale_shot.comp).
double GlShotBackend::deliver(float scale) {
  if (scale != 1.0f) sel_ = rescaleLastShot(lastShooter_, scale);
  return channelSum(sel_.incident) - receivedBefore_;
}

// An item buffer a region (a lamp's strong shot has its own layout and may draw its regions again:
// shootGl's replicas).
int GlShotBackend::shotEyes(int patch, bool strong) const {
  const ShooterLayout& l = layoutOf(patch, strong, false);
  return l.regions.x * l.regions.y;
}

// The patch statistics' unshot sums (patch_stats.comp), 48 bytes a patch: far less than the texels.
std::vector<double> GlShotBackend::patchUnshot() {
  std::vector<GpuStats> stats(atlas_.patches.size());
  glGetNamedBufferSubData(stats_.get(), 0, GLsizeiptr(stats.size() * sizeof(GpuStats)), stats.data());
  std::vector<double> unshot(stats.size());
  for (size_t p = 0; p < stats.size(); ++p) unshot[p] = double(stats[p].unshot.w);
  return unshot;
}

void GlShotBackend::readBack(const ReadBack& what, SolveResult& result, Context& ctx) {
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
GpuSelection GlShotBackend::startGl() {
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
GpuSelection GlShotBackend::shootGl(int shooter, bool strong, bool lamp) {
  const ShooterLayout& l = layoutOf(shooter, strong, lamp);
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
  // A back face within a shooter texel of an eye is one the eye's texel ends against or hangs over
  // (shot_coverage.comp): left out of the coverage.
  set(coverageProgram_, "uNearBack", l.texelRadius);
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
void GlShotBackend::buildPyramids(int shooter, const ShooterLayout& l, const Patch& p, int baseRegions,
                                  int replicas, const gl::Program& pyramidProgram, bool withLobes) {
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
void GlShotBackend::drawEyes(int shooter, const ShooterLayout& l, int regions, int baseRegions,
                             std::vector<glm::vec3>& eyes) {
  set(pickEyesProgram_, "uShooter", shooter);
  set(pickEyesProgram_, "uRegionCount", regions);
  set(pickEyesProgram_, "uBaseRegions", baseRegions);
  setU(pickEyesProgram_, "uShot", GLuint(shotCount_));
  glUseProgram(pickEyesProgram_.get());
  glDispatchCompute(groups(size_t(regions), 16), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::array<glm::vec4, kMaxEyes> drawn{};
  glGetNamedBufferSubData(eyes_.get(), 0, GLsizeiptr(regions * sizeof(glm::vec4)), drawn.data());
  for (int r = 0; r < regions; ++r)
    if (drawn[r].w > 0.0f) eyes[r] = glm::vec3(drawn[r]) + l.normal * eyeOffset_;
}

void GlShotBackend::gather(const gl::Program& receiveProgram, const ShotGeometry& g,
                           const std::vector<glm::vec3>& eyes, bool lamp, bool binnedShot, bool withLobes) {
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
  if (params_.directionalEmission && withLobes) set(receiveProgram, "uShooterLobes", int(hasLobes_[shooter]));
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

/// Scales what the last shot (of `shooter`) gave every receiver by `scale` (rescale_shot.comp),
/// then the statistics and the selection again.
GpuSelection GlShotBackend::rescaleLastShot(int shooter, float scale) {
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

GlShotBackend::Coverage GlShotBackend::readCoverage(int regions) {
  const size_t perRegion = coverageColumns();
  std::vector<glm::vec4> columns(size_t(regions) * perRegion);
  glGetNamedBufferSubData(coverage_.get(), 0, GLsizeiptr(columns.size() * sizeof(glm::vec4)), columns.data());
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

// Tile sums of tiles [first, end) (of the visible patches only when `onlyVisible`); the shooter's
// residual is zeroed on the way.
void GlShotBackend::runTileStats(size_t first, size_t end, int shooter, bool onlyVisible) {
  if (end <= first) return;
  setU(tileStatsProgram_, "uFirstTile", GLuint(first));
  setU(tileStatsProgram_, "uEndTile", GLuint(end));
  set(tileStatsProgram_, "uShooter", shooter);
  set(tileStatsProgram_, "uOnlyVisible", onlyVisible ? 1 : 0);
  glUseProgram(tileStatsProgram_.get());
  glDispatchCompute(groups(end - first, 64), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void GlShotBackend::runStats(int shooter) {
  set(statsProgram_, "uShooter", shooter);
  glUseProgram(statsProgram_.get());
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, patchList_.get());
  glDispatchComputeIndirect(4);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

GpuSelection GlShotBackend::select() {
  glUseProgram(selectProgram_.get());
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  GpuSelection s{};
  glGetNamedBufferSubData(selection_.get(), 0, sizeof s, &s);
  gl::check("shot");
  return s;
}

}  // namespace cpgi::gl_engine
