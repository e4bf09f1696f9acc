// The light arriving at a point, read back from a baked result by rays (issue 48: directional lightmaps and
// light probes). Whatever engine solved the bake (GL item buffers or Embree rays), its result is radiosity
// per atlas texel, and that is all this reads: a ray from the point that hits a surface brings that
// surface's reflected radiance (B − Le)/π, read bilinearly at the hit as an engine reads the lightmap; the
// emitted radiance Le/π is found both by those rays and by points drawn on the emissive texels by power
// (next-event estimation), the two combined by the power heuristic (Veach's multiple importance
// sampling): the points find a small lamp far away, the rays a lit wall next to the point (the balance
// heuristic left one ray's chance hit on a small lamp 3 % of a texel's light); the punctual
// lights are traced to exactly; a ray that leaves the scene brings the sky's radiance.
// Stratified directions over the point's hemisphere (a surface) or sphere (a probe).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

/// One sample of the light arriving at a point: from unit direction `towards` (from the point to where the
/// light comes from), radiance times the solid angle it stands for, per channel (W/m²). Σ light is the
/// radiant "scalar irradiance" ∫ L dω and Σ light (towards · n) the irradiance on a surface of normal n.
struct ArrivalSample {
  glm::vec3 towards{0.0f};
  glm::vec3 light{0.0f};
};

struct GatherParams {
  int rays = 256;           ///< directions per point, stratified (rounded to a square), ≥ 1
  int emitterSamples = 32;  ///< points on the emissive texels per point, drawn by power (0: by rays only)
};

class BakedRadiance {
 public:
  /// `radiosity`: per texel of `atlas` (an atlas of `scene`), W/m², undilated; `rays` over `scene`. All
  /// three must outlive this.
  BakedRadiance(const Scene& scene, const RayScene& rays, const LightmapAtlas& atlas,
                const std::vector<glm::vec3>& radiosity);

  /// Replaces `out` with the samples at `x`. `normal`: a surface's unit normal (directions over its
  /// hemisphere, the point lifted off it) or zero (a probe: the whole sphere). `seed` picks the jitter:
  /// the same seed gives the same samples. Thread-safe.
  void gather(const glm::vec3& x, const glm::vec3& normal, uint64_t seed, const GatherParams& params,
              std::vector<ArrivalSample>& out) const;

  /// Rays traced so far (directions, emitter and light shadow rays), over every thread.
  uint64_t raysTraced() const;

 private:
  // Both take the two techniques' sample counts for the power heuristic's weights.
  void gatherDirections(const glm::vec3& origin, const glm::vec3& normal, uint64_t seed, int side,
                        int emitterSamples, std::vector<ArrivalSample>& out) const;
  void gatherEmitters(const glm::vec3& origin, const glm::vec3& normal, uint64_t seed, int directions,
                      int samples, std::vector<ArrivalSample>& out) const;
  /// The solid-angle density of one emitter draw landing on emissive texel `texel` seen at distance² r2
  /// and cosine cosEmitter.
  float emitterDensity(uint32_t texel, float r2, float cosEmitter) const;
  void gatherLights(const glm::vec3& origin, const glm::vec3& normal, std::vector<ArrivalSample>& out) const;

  const Scene& scene_;
  const RayScene& rays_;
  const LightmapAtlas& atlas_;
  std::vector<glm::vec3> reflected_;  ///< per texel, (B − Le), dilated for bilinear reads
  std::vector<uint32_t> emitters_;    ///< emissive valid texels
  std::vector<double> emitterCdf_;    ///< their power's running share, last = 1
  std::vector<float> emitterChance_;  ///< per texel, the chance one emitter draw picks it (0: none)
  float offset_ = 0.0f;               ///< ray origins lifted off surfaces (m)
  mutable std::atomic<uint64_t> traced_{0};
};

}  // namespace cpgi
