// A deterministic sample of an atlas's texels, so that the reference can be traced where tracing every
// texel would take hours (seed3 at 128² texels per quad has 19.6 M). The accuracy metric of design.md §5
// is a ratio of two area-weighted sums over texels, Σ a|B − R|² / Σ a|R|², and a weighted sample
// estimates each sum without bias.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cpgi {

struct TexelSample {
  /// The chosen texels, as ranks among the valid texels in atlas order (0 = the first texel with a
  /// patch), increasing.
  std::vector<size_t> ranks;
  /// Per chosen texel, the inverse of its probability of being chosen: how many valid texels it stands for.
  std::vector<float> weights;
};

/// Chooses min(count, validCount) of `validCount` texels: the valid texels in atlas order are cut into
/// `count` strata of ⌊M/N⌋ or ⌈M/N⌉ consecutive texels and one texel is drawn uniformly in each, from
/// `seed`. Why this is unbiased: every texel lies in exactly one stratum, of m texels, and is drawn with
/// probability 1/m, so weighting it by m makes Σ_sample w·f an unbiased (Horvitz–Thompson) estimate of
/// Σ_all f for any per-texel f, in particular both sums of the metric. Why strata in atlas order: the atlas
/// packs each patch's texels together, so the strata sweep the scene's surfaces and every region is
/// sampled in proportion to its texel count; with one draw per equal stratum the variance is never above
/// that of the same number of independent uniform draws. count ≥ validCount gives every texel, weight 1.
/// Throws std::invalid_argument for count 0 (callers validate options first).
TexelSample sampleTexels(size_t validCount, size_t count, uint64_t seed);

/// The standard error, from the texel sampling alone, of a relative RMSE estimated on a sample:
/// `test`, `reference`, `area` and `weight` (TexelSample::weights spread over the texels, 0 where not
/// chosen) indexed alike, `validTexels` the number of texels the sample was drawn from. The root of a
/// ratio estimator, linearised: with u_i = a_i (|B_i − R_i|² − R̂ |R_i|²) and R̂ the squared estimate,
/// Var(R̂) ≈ M² (1 − n/M) s_u² / (n D̂²), the variance of n independent uniform draws, which stratification
/// only lowers; then σ_rmse = σ_R / (2 √R̂). 0 when the estimate is 0 or every texel was chosen.
double sampledRelRmseError(std::span<const glm::vec3> test, std::span<const glm::vec3> reference,
                           std::span<const float> area, std::span<const float> weight, size_t validTexels);

}  // namespace cpgi
