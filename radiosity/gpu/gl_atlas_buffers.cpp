// The GL engine's per-texel and per-patch buffers (gl_shot_backend.h): the atlas uploaded (radiosity,
// residual, incident, the patches' tiles), the directional emission's lobes and bins, the uniforms that
// stay for the whole solve, and the read-backs.
#include <cstring>

#include "core/error.h"
#include "radiosity/gpu/gl_shot_backend.h"
#include "radiosity/solve/emission_bins.h"

namespace cpgi::gl_engine {

// Whether the kTile × kTile tile at (x, y) of chart p holds a texel that receives (tiles that do not
// are left out of every shot's work list: compact.comp).
bool GlShotBackend::receivesIn(const Patch& p, int x, int y) const {
  if (params_.receivers.empty()) return true;
  for (int j = y; j < std::min(y + kTile, p.h); ++j)
    for (int i = x; i < std::min(x + kTile, p.w); ++i)
      if (params_.receivers[size_t(p.y + j) * size_t(atlas_.width) + size_t(p.x + i)]) return true;
  return false;
}

// Punctual lights (radiosity/lightmap/direct_light.h): their shot is done, so the solve starts after it,
// as after any shot: ρE reflected in radiosity and residual, E received.
void GlShotBackend::addDirectLight(std::span<const glm::vec3> direct, std::vector<glm::vec4>& exitance,
                                   std::vector<glm::vec4>& incident) const {
  for (size_t i = 0; i < direct.size() && i < exitance.size(); ++i) {
    if (atlas_.patch[i] < 0) continue;
    exitance[i] += glm::vec4(atlas_.albedo[i] * direct[i], 0.0f);
    incident[i] = glm::vec4(direct[i], 0.0f);
  }
}

std::vector<glm::vec3> GlShotBackend::readImage(const gl::Buffer& b) const {
  std::vector<glm::vec4> v(atlas_.texelCount());
  glGetNamedBufferSubData(b.get(), 0, GLsizeiptr(v.size() * sizeof(glm::vec4)), v.data());
  gl::check("read back");
  std::vector<glm::vec3> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) out[i] = glm::vec3(v[i]);
  return out;
}

std::vector<uint8_t> GlShotBackend::readLampFlags() const {
  std::vector<uint32_t> words(atlas_.texelCount());
  glGetNamedBufferSubData(texelFlags_.get(), 0, GLsizeiptr(words.size() * 4), words.data());
  gl::check("read back");
  std::vector<uint8_t> flags(words.size());
  for (size_t i = 0; i < words.size(); ++i) flags[i] = uint8_t(words[i] & 0xFFu);
  return flags;
}

std::vector<glm::vec4> GlShotBackend::readArrivals() const {
  std::vector<glm::vec4> v(atlas_.texelCount());
  glGetNamedBufferSubData(arrivals_.get(), 0, GLsizeiptr(v.size() * sizeof(glm::vec4)), v.data());
  gl::check("read back");
  return v;
}

void GlShotBackend::uploadAtlas() {
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
  ssbo(regions_, kRegions, kMaxEyes * sizeof(GpuRegion), nullptr);
  ssbo(nodes_, kNodes, maxPyramidNodes() * sizeof(GpuNode), nullptr);
  for (const ShooterLayout& l : allLayouts())
    for (const glm::ivec4& c : l.rects)
      if (topLevel(glm::ivec2(c.z - c.x, c.w - c.y)) > kMaxLevels)
        throw InputError("atlas", "a chart wider than 2^14 texels");
  ssbo(pending_, kPending, np * 4, pending.data());
  ssbo(selection_, kSelection, sizeof(GpuSelection), nullptr);
  ssbo(eyes_, kEyes, kMaxEyes * sizeof(glm::vec4), nullptr);
  ssbo(coverage_, kCoverage, size_t(mostEyes()) * size_t(params_.itemBuffer) * sizeof(glm::vec4), nullptr);
  const GLuint zero = 0;
  glClearNamedBufferData(stats_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

// Per-texel emission lobes (Lambertian when none are given), binned texels' bins after them (a binned
// lobe's slot turned into where its bins start, shaders/directional.glsl) and zeroed arrival moments.
void GlShotBackend::uploadDirectional(const std::vector<glm::vec4>* lobes) {
  const size_t n = atlas_.texelCount();
  if (lobes && lobes->size() != n) throw InputError("solver", "emission lobes must be one per atlas texel");
  const std::span<const float> bins = params_.emissionBins;
  if (bins.size() % kBinSlotFloats != 0) throw InputError("solver", "emission bins must come in whole slots");
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

void GlShotBackend::setConstantUniforms() {
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

}  // namespace cpgi::gl_engine
