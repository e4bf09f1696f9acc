// How long a scene's light keeps bouncing (issue 15, defect 6): in a closed scene of mean albedo ρ the
// share of the emitted light still bouncing after k bounces is ρ^k, so it takes ln(share) / ln(ρ) bounces
// to fall to `share`: hundreds near ρ = 1, for ever at 1. The progressive solve would shoot for hours and
// the path tracer's Russian roulette would end its paths long before (a noisy, low reference), so bake
// and reference refuse such a scene up front by this one rule unless the user bounds them.
#pragma once

#include <string>

#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// Bounces past which a run must be bounded by the user (bake: --max-shots or --time-limit; reference:
/// --max-bounces).
inline constexpr double kMaxUnboundedBounces = 200.0;

struct BounceEstimate {
  double albedo = 0.0;   ///< area-weighted mean over the valid texels of each texel's largest channel
  double bounces = 0.0;  ///< ln(share) / ln(albedo); inf at albedo ≥ 1, 0 at albedo 0
  bool tooMany() const { return bounces > kMaxUnboundedBounces; }
  /// "mean albedo 0.99: light would bounce about 458 times" (or "for ever").
  std::string describe() const;
};

/// The estimate for `atlas` until `share` (in (0, 1)) of the light is left.
BounceEstimate estimateBounces(const LightmapAtlas& atlas, double share);

}  // namespace cpgi
