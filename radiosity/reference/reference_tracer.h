// The independent reference (design.md §5): a CPU path tracer that estimates, at given sample points,
// the same quantity the radiosity solvers store — outgoing radiosity B = E + ρ·H (W/m²), H the
// irradiance. It shares nothing with the GPU solver: Embree rays for visibility (radiosity/lightmap/ray_scene.h),
// cosine-weighted hemisphere sampling, next-event estimation to emissive triangles by area sampling,
// combined with the BSDF-sampled emitter hits by multiple importance sampling (Veach's power heuristic),
// next-event estimation to the punctual lights (core/lights.h; a shadow ray each, since no bounce can hit
// a point), Russian roulette after a few bounces, and the sky and ground at infinity
// (Scene::sky, core/sky.h) where a path leaves the scene. Surfaces are one-sided like the solver's patches: a ray that
// reaches a triangle's back face sees black.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// Where to estimate B: a point on a surface, on that surface's front side.
struct SamplePoint {
  glm::vec3 position{0.0f};  ///< metres
  glm::vec3 normal{0.0f};    ///< unit, the side light is gathered from
  glm::vec3 albedo{0.0f};    ///< ρ in [0, 1]
  glm::vec3 emission{0.0f};  ///< E, W/m²
  /// The edges of the surface part the point stands for: paths start uniformly over the parallelogram
  /// position ± ½·footprintU ± ½·footprintV, so the estimate is B's mean over it. Zero: the point itself.
  glm::vec3 footprintU{0.0f}, footprintV{0.0f};
};

struct ReferenceParams {
  /// Paths per sample point, ≥ 2. They are drawn as 16 (or spp, if fewer) independent batches, each a
  /// randomly shifted low-discrepancy set for the first vertex (randomised quasi-Monte Carlo), so spp is
  /// rounded up to a multiple of the batch count; the standard error comes from the batch means.
  int spp = 256;
  int rouletteAfter = 5;    ///< bounces that always continue before Russian roulette may stop a path
  int maxBounces = 1000;    ///< safety cap; only albedo ≈ 1 gets near it
  uint64_t seed = 0x5eedu;  ///< with the point's index, fixes each point's random sequence
  /// Ray origins are pushed this far off surfaces (metres); ≤ 0 → 1e-5 × scene diagonal.
  float rayOffset = 0.0f;
  /// Over an atlas: each texel's mean over its part of the patch (paths start all over it), which is the
  /// texel's value in the solver's books (its power ÷ its area) and what the bake stores where the light
  /// changes inside a texel (a lamp's shadow or beam edge, shaders/receive.comp). False: B at the texel's
  /// centre, which across a penumbra's knee differs from the mean by more than any solver error there.
  bool texelMean = true;
};

struct ReferenceResult {
  std::vector<glm::vec3> radiosity;      ///< B per point, W/m² (0 where no point, e.g. atlas padding)
  std::vector<glm::vec3> standardError;  ///< per channel, standard error of B's mean
  uint64_t rays = 0;                     ///< rays cast (intersections + shadow rays)
  int spp = 0;                           ///< paths per point actually traced (rounded up, see spp)
};

/// Estimates B at every point. Deterministic: the same scene, points and params give bit-identical
/// results whatever the thread count, since point i draws only from its own generator, seeded by
/// params.seed and its stream number: streams[i], or i when `streams` is empty (else it has one per point).
/// Throws InputError("samples per texel", ...) for spp < 2.
ReferenceResult traceReference(const Scene& scene, std::span<const SamplePoint> points,
                               const ReferenceParams& params, Context& ctx,
                               std::span<const uint64_t> streams = {});

/// The same over the valid texels of an atlas (texel sample point, normal, albedo, emission, and with
/// params.texelMean its footprint); results
/// are indexed like the atlas texels, padding texels left at 0. `ranks` (increasing, as
/// TexelSample::ranks) traces only those valid texels and leaves the others at 0; empty traces all. A
/// texel draws from the stream of its rank either way, so it gets the same value whichever others are
/// traced.
ReferenceResult traceReference(const Scene& scene, const LightmapAtlas& atlas, const ReferenceParams& params,
                               Context& ctx, std::span<const size_t> ranks = {});

/// The reference's own noise in the metric of design.md §5: sqrt(Σ a_i |σ_i|² / Σ a_i |B_i|²), σ_i the
/// per-texel standard error (RGB norm). A comparison against this reference cannot resolve relative RMSE
/// below about this value. `area` is per point (the atlas's area channel); 0 when Σ a |B|² is 0.
double relativeStandardError(const ReferenceResult& result, std::span<const float> area);

}  // namespace cpgi
