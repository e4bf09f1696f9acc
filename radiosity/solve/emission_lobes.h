// Directional emission, for the cell solver's directional portals: light that crosses a door keeps the
// direction it travelled in. A portal texel records where its irradiance came from (arrival
// moments, accumulated by the GPU receiver pass, shaders/directional.glsl) and, on the other side of the
// opening, re-emits its exitance M with a lobe f instead of a Lambertian: radiance L(ω) = M f(ω) / π.
//
// The lobe is a mixture of a Lambertian and a Gaussian in gnomonic (tangent-plane) coordinates
// s = ω_t / cos θ, which map the open hemisphere onto the whole plane:
//     f(ω) = (1 − a) + a · exp(−|s − s0|² / 2σ²) / (2σ² cos⁴θ)
// Because cos θ dω = cos⁴θ ds, ∫ f cos θ dω = (1 − a)π + a π ∫ Gaussian ds = π exactly for any a, s0, σ:
// the exitance, hence the energy bookkeeping, does not depend on the lobe, and a = 0 is the diffuse portal.
// A mixture of such lobes (a sub-shooter block) is replaced by the one with the same weight, mean and
// variance, which is still normalised.
//
// Fit (fitEmissionLobe): the arrival moments are taken in the disk coordinates u = ω_t (|u| = sin θ), in
// which a Lambertian is uniform (mean 0, E|u|² = ½): mean m and second moment M2 of u, irradiance-weighted.
// The lobe weight a and centre u0 follow from matching m = a u0 and M2 = (1 − a)/2 + a (|u0|² + τ²) with
// the narrowest lobe allowed (τ = minWidth per axis); when even a = 1 leaves variance over, the lobe
// widens instead. Diffuse arrivals give a = 0; a collimated beam gives a = 1 around its direction.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// Per texel, what the GPU receiver pass accumulates (SolveResult::arrivals) for light travelling along
/// unit ω, seen from the far side of the receiving surface (normal nFar = −receiver normal): weight w (the
/// irradiance summed over R, G, B) times (u + |u|² nFar), u = ω − (ω·nFar) nFar, and w in .w. Sums of these
/// are the moments fitEmissionLobe reads.
glm::vec4 arrivalMoment(const glm::vec3& omega, const glm::vec3& nFar, float weight);

/// The lobe packed as the solver reads it: xyz = s0 + a·n (s0 ⟂ n), w = σ² (per axis, in s). The zero
/// vector is the Lambertian.
glm::vec4 fitEmissionLobe(const glm::vec4& moments, const glm::vec3& n, float minWidth);

/// f(ω) for unit ω leaving a surface of unit normal n (0 behind it), the lobe's σ² widened by blur2 (the
/// solver widens it by the receiver texel's footprint). Must match shaders/directional.glsl.
float emissionLobeFactor(const glm::vec4& lobe, const glm::vec3& n, const glm::vec3& omega,
                         float blur2 = 0.0f);

/// Lobes for every texel of an atlas from per-texel moments (zero moments → Lambertian), with the atlas's
/// normals. `moments` is empty or one per texel.
std::vector<glm::vec4> fitEmissionLobes(const std::vector<glm::vec4>& moments, const LightmapAtlas& atlas,
                                        float minWidth);

}  // namespace cpgi
