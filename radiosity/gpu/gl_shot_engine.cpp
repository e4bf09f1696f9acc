#include "radiosity/gpu/gl_shot_engine.h"

#include <algorithm>

#include "core/error.h"
#include "core/memory_limit.h"
#include "radiosity/gpu/gl_shot_backend.h"

namespace cpgi {
namespace {

using gl_engine::GlShotBackend;
using gl_engine::kMaxRegions;
using gl_engine::SolveConfig;

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
