// Where the light leaving each cell's surfaces lands, measured with rays, for the ambient term
// (radiosity/solve/ambient.h). The term's own rule, a share A_portal / (A_cell + A_portals) of each bounce
// through each portal and the rest back into the cell, holds for closed rooms; it has no sky. The
// outside of a building is a cell whose surfaces (terrain, facades, roofs) send most of what they reflect
// out of the scene, and kept all of it: the furnished house's outside read +9 % with its ambient at 18 %
// of its light, and a window's light that leaves a room for the sky was put on the outside's ground.
//
// Nor is a room's light spread evenly over it, as the series over `share` alone assumes of every bounce:
// light that came in through a door lands on the surfaces that see that door, and what they reflect
// finds the room's other doors less often than light leaving the whole room would (and goes back out
// of the door it came in by more often); and a dim room's unshot power lies where its light came in. Both
// spread evenly, the ambient term put 12-18 % too much light in rooms three and four doors from the lamps
// at the default stop (random plans 4, 10, 17: bench/RESULTS.md, "The ambient term per room"). So the
// light is followed by random walks, per arrival: into cell d from cell c, its bounces in d at each
// surface's own albedo until it lands in another cell, which is the next arrival; and each cell's first
// rays are weighed by the unshot power where they leave.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

/// share[c][d]: of the light leaving cell c's surfaces (diffusely, spread over them by area), the share
/// that first lands on cell d's; 1 − Σ_d share[c][d] leaves the scene. Cells 0..K−1 and a last entry K for
/// texels in no cell (and hits on triangles outside the atlas).
struct AmbientTransfer {
  std::vector<std::vector<double>> share;
  int raysPerCell = 0;
  /// Light that landed on cell `to`'s surfaces from cell `from` (the two alike: light from a cell's own
  /// surfaces), as cell `from`'s rays of `share` land there, followed over its bounces in `to`: per 1 W
  /// (per channel) arriving, `landed` W land on `to`'s surfaces (the arrival and every bounce that stays
  /// in `to`) and `onward[e]` W land on cell e's (e != to), each an arrival from `to` into e.
  struct Arrival {
    size_t from = 0, to = 0;
    glm::dvec3 landed{0.0};
    std::vector<glm::dvec3> onward;
  };
  /// One per (from, to) with share[from][to] > 0; empty: the series over `share` alone.
  std::vector<Arrival> arrivals;
  /// A ray of `share`: the texel it left from (drawn by area) and the cell it landed on (-1: none).
  struct SourceRay {
    uint32_t texel = 0;
    int32_t to = -1;
  };
  /// Per cell, its rays (raysPerCell, or none for a cell without texels) and its texels' area (m²): the
  /// rays weighed by where the unshot power is (ambientLandedByArrivals).
  std::vector<std::vector<SourceRay>> rays;
  std::vector<double> sourceArea;
};

/// Per cell, the power (W, RGB) landing on its surfaces, all bounces, from `unshot` (W, RGB) leaving
/// each cell's surfaces: the series over `transfer.arrivals`. `texelUnshot`: per atlas texel the power
/// it holds unshot (W, any unit alike over the texels), where the unshot power leaves from; empty: spread
/// over each cell's surfaces by area. `texelArea`: per atlas texel its area (m²), with `texelUnshot`.
std::vector<glm::dvec3> ambientLandedByArrivals(const std::vector<glm::dvec3>& unshot,
                                                const AmbientTransfer& transfer,
                                                std::span<const double> texelUnshot = {},
                                                std::span<const float> texelArea = {});

/// `texelCell`: per atlas texel its cell (< 0 or ≥ `cells`: none). A cell without texels keeps all it has
/// (share[c][c] = 1). `walksPerArrival`: the most random walks followed per arrival (at least 16 per
/// landed ray of `share`); 0: no arrivals. Deterministic for a seed (stratified points and directions).
AmbientTransfer measureAmbientTransfer(const LightmapAtlas& atlas, const RayScene& rays,
                                       std::span<const float> texelCell, size_t cells, int raysPerCell = 8192,
                                       uint64_t seed = 0x5eed, int walksPerArrival = 2048);

}  // namespace cpgi
