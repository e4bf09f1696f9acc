// An ambient term for a progressive solve stopped early (after Cohen, Chen, Wallace & Greenberg 1988):
// the power still unshot will, after all its bounces, add some irradiance everywhere; each texel shows
// B + ρ × that irradiance. Cohen spreads it evenly over the scene, which measured +28 % in a room two
// openings from the lamp (its light is mostly unshot in the lit rooms, and little of it gets through).
// Here it follows the cells: each cell's unshot power bounces in its room, a share A_portal / (A_cell +
// A_portals) of each bounce leaving through each portal, the small cell-to-cell system solved by its
// series. One cell (a scene without cells) gives Cohen's term. Without any ambient the default stop
// (1 % unshot) left a room lit through doors 9–16 % dark (issue 11).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/ambient_transfer.h"

namespace cpgi {

/// A room as the ambient term sees it: its surfaces' area (m²), Σ ρ × area over them (m², RGB) and the
/// power still unshot in it (W, RGB).
struct AmbientRoom {
  double area = 0.0;
  glm::dvec3 albedoArea{0.0};
  glm::dvec3 unshot{0.0};
};
/// An opening of `area` m² between rooms `a` and `b` (indices into the rooms).
struct AmbientOpening {
  size_t a = 0, b = 0;
  double area = 0.0;
};

/// Per room, the power its surfaces receive (W, RGB) from every room's unshot power, all bounces: what
/// leaves a room's surfaces lands in it, or through each opening in the next, a share
/// A_opening / (A_room + A_openings), and is absorbed or reflected by the room's mean albedo.
std::vector<glm::dvec3> ambientLanded(const std::vector<AmbientRoom>& rooms,
                                      const std::vector<AmbientOpening>& openings);
/// The same with the shares given: transfer[c][d] of what leaves room c's surfaces lands in room d, the
/// rest of each row leaves the scene (AmbientTransfer::share, measured by rays).
std::vector<glm::dvec3> ambientLandedByShares(const std::vector<AmbientRoom>& rooms,
                                              const std::vector<std::vector<double>>& transfer);

/// Adds ρ_i × (its cell's ambient irradiance) to every valid texel of `radiosity` (per atlas texel,
/// W/m²). `residual`: the unshot radiosity per texel (W/m²), or empty to spread `unshotPower` (W per
/// channel) by area; `texelCell`: per texel its cell in `graph` (radiosity/lightmap/cell_channel.h), or
/// empty, or a graph without cells: one cell. `measured` (its cells those of `graph` and one for no cell):
/// the light's ways between the cells and out of the scene, instead of the portals' areas. Returns the mean
/// ambient irradiance over the scene (W/m², RGB).
glm::dvec3 addAmbient(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                      const glm::dvec3& unshotPower, std::span<const float> texelCell, const CellGraph& graph,
                      std::vector<glm::vec3>& radiosity, const AmbientTransfer* measured = nullptr);

/// bake --ambient-share's default (bench/RESULTS.md, "The default stop per room").
inline constexpr double kDefaultAmbientShare = 0.1;

/// A cell lit at less than this share of the scene's light per m² (its cells' together) holds no stop per
/// cell (ambientShares, RoundStop: share 0): its light is a leak's, black at any exposure of the scene.
/// Held to --ambient-share, thin-wall's closed room B, lit only by what crosses a zero-thickness wall,
/// ran the global bake to 2.7e-6 unshot (142 shots, not 38; issue 11, session 21).
inline constexpr double kNegligibleCellLight = 1e-4;

/// Per cell, ambient[c] / light[c] (W, the cell's light with the ambient term in it), or 0 where the cell's
/// light per m² of area[c] is below kNegligibleCellLight × Σ light / Σ area, or there is none.
std::vector<double> ambientShareOfLitCells(const std::vector<double>& ambient,
                                           const std::vector<double>& light, const std::vector<double>& area);

/// Per cell (and the last entry: texels in no cell), what the stop per room weighs: the power still unshot
/// on its surfaces (W, RGB) and the light leaving its reflectors (W, R + G + B; lamps left out).
struct CellLight {
  std::vector<glm::dvec3> unshot;
  std::vector<double> light;
  /// Per atlas texel, the power it holds unshot (W, R + G + B): where each cell's unshot power leaves
  /// from. Empty: spread over the cell's surfaces by area (the time estimate's cells).
  std::vector<double> texelUnshot;
};

/// The stop per room (bake --ambient-share): a progressive solve that reaches its unshot stop stops only
/// once in no cell the ambient term would be more than `share` of the cell's light (ambientShares). Asked
/// of a solve's texels (the loop's acceptStop) or of each cell's light (CellLight) as the time estimate's
/// model foresees it (radiosity/solve/solve_estimate.h): one rule for both. Holds a reference to `atlas`.
class RoomStop {
 public:
  /// `texelCell`, `graph`, `measured` as ambientShares's; `share`: the most the ambient term may be.
  RoomStop(const LightmapAtlas& atlas, std::span<const float> texelCell, const CellGraph& graph,
           const AmbientTransfer* measured, double share);
  /// Per atlas texel, its entry in CellLight.
  std::vector<int> texelCells() const;
  /// The cells' light from per-texel radiosity and unshot residual (W/m², RGB).
  CellLight cellLight(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual) const;
  /// Per entry, ρ E / (B + ρ E) over its reflectors (0 for a cell lit at a leak's level).
  std::vector<double> shares(const CellLight& cells) const;
  /// No entry's share above `share`.
  bool accepts(const CellLight& cells) const;
  bool accepts(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual) const {
    return accepts(cellLight(radiosity, residual));
  }

 private:
  const LightmapAtlas& atlas_;
  double share_;
  std::vector<size_t> texelEntry_;
  std::vector<AmbientRoom> rooms_;  // every surface: where the unshot power bounces
  std::vector<AmbientOpening> openings_;
  AmbientTransfer transfer_;                     // measured, or empty: the openings' areas
  std::vector<glm::dvec3> reflectorAlbedoArea_;  // the lamps left out: what shows the ambient term
  std::vector<double> reflectorArea_;
};

/// Per cell of `graph` (and a last entry for texels in no cell; one entry in all without cells), the share
/// of its reflectors' light (area-weighted, R + G + B, lamps left out) that the ambient term of `residual`
/// would be: ρ E / (B + ρ E). A progressive solve's stop per cell (bake): 1 % unshot in the whole scene
/// left a fifth of the light of a room two openings from the lamp to the ambient term, which is flat over
/// the room (openings, room C: 5.7 % per texel at the default stop, 4.2 % with the stop per cell).
/// A cell lit at a leak's level counts 0 (kNegligibleCellLight).
std::vector<double> ambientShares(const LightmapAtlas& atlas, const std::vector<glm::vec3>& residual,
                                  std::span<const float> texelCell, const CellGraph& graph,
                                  const std::vector<glm::vec3>& radiosity,
                                  const AmbientTransfer* measured = nullptr);

/// One line naming the rooms whose ambient share (`shares`, per entry of `names` and one more for texels in
/// no cell) is above `target`, largest first with their shares: what a solve stopped at its bound on the
/// stop per room (SolveResult::stopBounded, radiosity/solve/progressive_loop.h) left above it. "" if none.
std::string roomsAboveShare(const std::vector<double>& shares, const std::vector<std::string>& names,
                            double target);

}  // namespace cpgi
