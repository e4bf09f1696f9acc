// Real spherical harmonics up to band 2, in the basis and order that Godot's LightmapGI and Unity's
// SphericalHarmonicsL2 use (Sloan, "Stupid Spherical Harmonics Tricks", 2008): index 0 is Y(0,0), then
// Y(1,−1) ∝ y, Y(1,0) ∝ z, Y(1,1) ∝ x, then Y(2,−2) ∝ xy, Y(2,−1) ∝ yz, Y(2,0) ∝ 3z² − 1, Y(2,1) ∝ xz,
// Y(2,2) ∝ x² − y². Coefficients are projections of radiance, L_lm = ∫ L(ω) Y_lm(ω) dω (W/(m²·sr)·sr per
// channel); the irradiance on a surface of normal n is Ramamoorthi & Hanrahan's convolution
// ("An efficient representation for irradiance environment maps", 2001):
//     E(n) = Σ_l Â_l Σ_m L_lm Y_lm(n),  Â_0 = π, Â_1 = 2π/3, Â_2 = π/4.
#pragma once

#include <array>
#include <span>

#include <glm/glm.hpp>

namespace cpgi {

inline constexpr float kShY00 = 0.282095f;  ///< Y(0,0) = 1 / (2√π)
inline constexpr float kShY1 = 0.488603f;   ///< Y(1,m) = √(3 / 4π) times y, z or x

/// The nine basis functions at unit `w`, in the order above.
std::array<float, 9> shBasis(const glm::vec3& w);

/// The irradiance (per channel) on a surface of unit normal `n` from radiance coefficients (4: L1,
/// 9: L2, in the order above), by Ramamoorthi & Hanrahan's convolution.
glm::vec3 shIrradiance(std::span<const glm::vec3> coefficients, const glm::vec3& n);

/// Band 4's nine real basis functions at unit `w`, m = −4 … 4 (the orthonormal real forms of the usual
/// tables, as band 2's above). Band 3 adds nothing to irradiance (its Â_3 is 0) and band 4 is the first
/// that does: Â_4 = −π/24, the part of a concentrated light's irradiance that L2 leaves out (a point
/// light's L2 irradiance is 6 % of its peak too bright facing it and 9 % of it beside it).
std::array<float, 9> shBasisBand4(const glm::vec3& w);

/// The irradiance band 4's coefficients (L4,−4 … L4,4; radiance projections) add to shIrradiance's, on a
/// surface of unit normal `n`: Â_4 Σ_m L4m Y4m(n).
glm::vec3 shIrradianceBand4(std::span<const glm::vec3> band4, const glm::vec3& n);

/// The vector irradiance V = ∫ L(ω) ω dω of one channel from its L1 coefficients: V = (L11, L1−1, L10) /
/// Y1. For light arriving from one side of a surface of normal n_s, V · n_s is the surface's irradiance
/// exactly, and max(0, V · n) the first-order irradiance for a shading normal n near n_s.
glm::vec3 shIrradianceVector(std::span<const glm::vec3> coefficients, int channel);

}  // namespace cpgi
