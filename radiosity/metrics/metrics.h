// Accuracy of a lightmap against a reference on the same atlas (design.md §5). Texels are weighted by
// their area (the lightmap's "area" channel), so padding (area 0) never counts and a large texel counts
// for what it covers.
#pragma once

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

namespace cpgi {

struct LightmapError {
  /// sqrt(Σ a_i |B_i − R_i|² / Σ a_i |R_i|²), |·| the RGB Euclidean norm.
  double relRmse = 0.0;
  /// Signed bias of the total: Σ a_i (B_i − R_i)·(1,1,1) / Σ a_i R_i·(1,1,1); > 0 when B is too bright.
  double relMeanError = 0.0;
  /// max |B_i − R_i| (RGB norm, W/m²) over texels with a_i > 0.
  double maxAbs = 0.0;
  size_t texels = 0;  ///< texels compared (a_i > 0)
};

/// Compares `test` (B) against `reference` (R), both indexed like `area`. The spans must have the same
/// size (the caller checks atlas sizes and reports a mismatch as an input error). A reference that is
/// zero everywhere gives relative errors of 0 when B is zero too and +∞ otherwise.
LightmapError compareLightmaps(std::span<const glm::vec3> test, std::span<const glm::vec3> reference,
                               std::span<const float> area);

}  // namespace cpgi
