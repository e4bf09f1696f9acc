// Binned directional emission, for portals whose light is more concentrated than one lobe can say: a
// portal texel re-emits its exitance M with L(ω) = M f(ω) / π, f given per bin of kArrivalBins bins, the
// cells of a kBinGrid × kBinGrid square mapped onto the hemisphere by Shirley and Chiu's concentric map with
// the square's radius ρ = θ / (π/2): rings of equal angle, each cell about 90° / (kBinGrid / 2) across from
// the pole to the rim, read bilinearly between the cells' centres (binTaps). Each bin's projected solid
// angle is its share of the projected disk (binProjectedArea), and f is normalised so that ∫ f cos θ dω = π
// exactly for the bilinear reading (normalisedEmissionBins): the exitance, hence the bookkeeping, does not
// depend on the shape.
//
// Why rings of equal angle, not of equal projected area (ρ = sin θ, the plain concentric map): a door in
// a wall at right angles to a room's back wall lights that wall only from grazing directions, and the
// outermost ring of a 12 × 12 equal-area grid spans 56–90°: the whole first metre and a half of the wall
// took one bin's light, and a peak between 45 and 60° was spread over both rings, a band +30 % beside one
// −30 % (random plan 22, room R7). 18 × 18 cells of 10° give that wall within 12 % of the light through
// the opening (bench/portal_oracle.cpp; 12 × 12 equal-area: 0.64–2.1).
//
// Why that grid, not rings and sectors: light that goes straight through two doors in a row leaves the
// second near its normal, where 8 rings of 16 sectors were wedges 21° long meeting at the pole; the beam
// spread over them, and the wall facing the doors got 7 % too little (random plan 3, room R8).
//
// Each colour channel has its own f: the light a door passes in one direction is the colour of the wall it
// came from (a red wall straight through the door, a white ceiling above it), and one shape for the three
// channels handed every direction the texel's mean colour: a room lit through two doors in a row came out
// bluer than the path tracer's (random plan 3's room R6, blue/green 1.25).
//
// Why bins and not the moment-fitted lobe (emission_lobes.h): through openings' narrow door the lobe gave
// the wall beside it 0.79 of the light and the far part 1.12 (bench/portal_oracle.cpp), the gradient a
// cells bake showed there; 8 × 16 bins give 0.97–1.02 on both of that scene's portals (bench/RESULTS.md).
//
// The bins are found by rays (traceArrivalBins): from a point of the portal into the sending cell, each
// ray takes the exitance the texel it hits shot towards the portal, so the shape is exact in expectation
// whatever the solver's shooter pieces were.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

inline constexpr int kBinGrid = 18, kArrivalBins = kBinGrid * kBinGrid;
/// Irradiance per arrival bin, per channel (W/m²).
using ArrivalBins = std::array<glm::vec3, kArrivalBins>;
/// The factors of one binned emitter as the solver reads them: per bin f of red, green and blue and an
/// unused fourth (a vec4 a bin for the shaders), each channel normalised so that ∫ f cos θ dω = π. Must
/// match shaders/directional.glsl.
inline constexpr int kBinSlotFloats = 4 * kArrivalBins;
using EmissionBinSlot = std::array<float, kBinSlotFloats>;

/// The tangent frame the bins of a surface of unit normal n are laid out in; a function of n alone, so
/// the two sides of a portal (normals n and −n seen from the far side) agree. Must match
/// shaders/directional.glsl.
struct BinFrame {
  glm::vec3 n, t1, t2;
};
BinFrame binFrame(const glm::vec3& n);

/// Where unit direction ω leaving the surface (ω · n > 0) lies in the concentric map's square, in cells:
/// [0, kBinGrid)² (column, row).
glm::vec2 binSquarePoint(const BinFrame& frame, const glm::vec3& omega);

/// The bin of unit direction ω leaving the surface (ω · n > 0): row · kBinGrid + column of its cell in the
/// concentric map's square. The histogram a portal's arrival is gathered into.
int arrivalBin(const BinFrame& frame, const glm::vec3& omega);

/// The unit direction leaving the surface at point `square` of the concentric map's square, in cells:
/// [0, kBinGrid)² (column, row); binSquarePoint's inverse.
glm::vec3 binDirection(const BinFrame& frame, const glm::vec2& square);

/// The projected solid angle per unit area of the square at point `square` (in cells), relative to its
/// mean over the square: how much more of the projected disk a cell near the pole holds than one at the rim.
float binDensity(const glm::vec2& square);

/// Bin b's share of the projected disk, ∫_b cos θ dω / π (the shares sum to 1).
double binProjectedArea(int b);

/// The four bins and weights that f(ω) interpolates between: bilinear in the square between the cells'
/// centres, each edge cell's value held out to the edge. The emission reads f so, not as steps: a beam
/// narrower than a bin lit a wall with the bin's hard edges, a step of 0.6 to 1.3 across half a metre
/// (random plan 3, room R4). The normalisation (normalisedEmissionBins) integrates that reading, so the
/// exitance does not change. Must match shaders/directional.glsl.
struct BinTaps {
  std::array<int, 4> bin;
  std::array<float, 4> weight;
};
BinTaps binTaps(const BinFrame& frame, const glm::vec3& omega);

/// f(ω) per channel of bins holding the irradiance arriving through each (non-negative; normalised here
/// so that ∫ f cos θ dω = π): 0 behind the surface, 1 for a channel whose bins are all zero (a Lambertian).
glm::vec3 binnedEmissionFactor(const ArrivalBins& bins, const BinFrame& frame, const glm::vec3& omega);

/// A binned emitter read in many directions: its bins, frame and normalisation (the integral over every
/// bin) found once, so that each reading costs its four taps, not a pass over the kArrivalBins bins.
/// Refers to `bins`, which must outlive it.
struct BinnedEmitter {
  const ArrivalBins* bins = nullptr;
  BinFrame frame;
  glm::dvec3 total{0.0};  ///< per channel, what the bins' f read bilinearly integrates to before normalising
};
BinnedEmitter binnedEmitter(const ArrivalBins& bins, const glm::vec3& normal);
/// binnedEmissionFactor(*e.bins, e.frame, ω), the same floats.
glm::vec3 binnedEmissionFactor(const BinnedEmitter& e, const glm::vec3& omega);

/// The bins as the solver reads them (ShotShape::emissionBins): f per bin and channel, each bin's
/// irradiance over its projected solid angle, scaled so that ∫ f cos θ dω = π under the bilinear reading
/// (binTaps); all ones for a channel whose bins are all zero.
EmissionBinSlot normalisedEmissionBins(const ArrivalBins& bins);

/// The sum over the bins, per channel.
glm::dvec3 binTotals(const ArrivalBins& bins);

/// The emission lobe (ShotShape::emissionLobes) of a texel that emits with the binned slot `slot` ≥ 0
/// of ShotShape::emissionBins. Must match shaders/directional.glsl.
inline glm::vec4 binnedLobe(int slot) {
  return glm::vec4(0.0f, 0.0f, 0.0f, -float(slot + 1));
}

/// Per texel of `atlas` and a direction of travel ω (unit), the exitance (W/m², per channel) it sent
/// towards ω: its Lambertian shot, or that times its own emission shape.
using ExitanceToward = std::function<glm::vec3(size_t texel, const glm::vec3& omega)>;

/// Irradiance per arrival bin and channel (W/m²) at the parallelogram origin + [0,1]·edgeU + [0,1]·edgeV of
/// a surface of unit normal `facing` (towards where the light comes from), by `rayCount` rays from points
/// stratified over it, as many through each bin (at least one each when there are that many rays, else
/// spread over the square), each weighted by its projected solid angle: the rim's bins, small in projected
/// area, get as many rays as the pole's. The bins are those of the far side (normal −facing), on which the
/// light travels on. A ray that hits nothing or a texel outside the atlas brings nothing. Deterministic
/// for a given `seed`.
ArrivalBins traceArrivalBins(const RayScene& rays, const LightmapAtlas& atlas, const glm::vec3& origin,
                             const glm::vec3& edgeU, const glm::vec3& edgeV, const glm::vec3& facing,
                             int rayCount, uint32_t seed, const ExitanceToward& exitance);

/// The texel of `atlas` each of traceArrivalBins' rays meets, in the rays' order (kNoArrivalTexel where a
/// ray meets none): the rays depend on the parallelogram, `rayCount` and `seed` alone, so a portal texel's
/// rays meet the same texels in every round of a cells solve, whatever light they hold then.
inline constexpr int32_t kNoArrivalTexel = -1;
std::vector<int32_t> traceArrivalHits(const RayScene& rays, const LightmapAtlas& atlas,
                                      const glm::vec3& origin, const glm::vec3& edgeU, const glm::vec3& edgeV,
                                      const glm::vec3& facing, int rayCount, uint32_t seed);
/// traceArrivalBins from the texels its rays meet (traceArrivalHits with the same `facing` and `seed`, one
/// entry a ray): the same floats, without tracing a ray. With `directional` (per atlas texel, 1 where its
/// exitance depends on ω), the others are read with ω = 0, their ray's direction not worked out.
ArrivalBins arrivalBinsAlongHits(std::span<const int32_t> hits, const glm::vec3& facing, uint32_t seed,
                                 const ExitanceToward& exitance, std::span<const uint8_t> directional = {});

/// The atlas texel under a ray's hit on scene triangle `triangle` at barycentrics (u, v), or -1 when the
/// triangle has no chart or the texel is padding.
int64_t texelAtHit(const LightmapAtlas& atlas, int32_t triangle, float u, float v);

}  // namespace cpgi
