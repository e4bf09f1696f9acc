// Where the light leaving each cell's surfaces lands, measured with rays, for the ambient term
// (radiosity/solve/ambient.h). The term's own rule, a share A_portal / (A_cell + A_portals) of each bounce
// through each portal and the rest back into the cell, holds for closed rooms; it has no sky. The
// outside of a building is a cell whose surfaces (terrain, facades, roofs) send most of what they reflect
// out of the scene, and kept all of it: the furnished house's outside read +9 % with its ambient at 18 %
// of its light, and a window's light that leaves a room for the sky was put on the outside's ground.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

/// share[c][d]: of the light leaving cell c's surfaces (diffusely, spread over them by area), the share
/// that first lands on cell d's; 1 − Σ_d share[c][d] leaves the scene. Cells 0..K−1 and a last entry K for
/// texels in no cell (and hits on triangles outside the atlas).
struct AmbientTransfer {
  std::vector<std::vector<double>> share;
  int raysPerCell = 0;
};

/// `texelCell`: per atlas texel its cell (< 0 or ≥ `cells`: none). A cell without texels keeps all it has
/// (share[c][c] = 1). Deterministic for a seed (stratified points and directions).
AmbientTransfer measureAmbientTransfer(const LightmapAtlas& atlas, const RayScene& rays,
                                       std::span<const float> texelCell, size_t cells, int raysPerCell = 8192,
                                       uint64_t seed = 0x5eed);

}  // namespace cpgi
