// When the cells' rounds stop: at the scene's unshot target, and then only once the ambient term (what the
// bake adds for the power left unshot, radiosity/solve/ambient.h) is at most --ambient-share of the light in
// every cell, as a global bake's solve stops (SolveControls::acceptStop). Refused, the rounds go on to
// kStopRecheck of the unshot power and ask again. At the scene's target alone, spot-door's lamp room (its
// lamp aimed through the door, its light mostly what comes back) stopped after one round with the ambient
// term 62 % of its light, 1.045 of the reference (0.998 converged).
//
// The figures are each cell's own, from its CellRound (cell_round.h): a solve in one process and the cell
// jobs' driver, which sees only the jobs' summaries, decide from the same numbers and stop after the same
// round.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_round.h"
#include "radiosity/solve/ambient.h"

namespace cpgi {

/// A cell's own surfaces (every valid texel of its atlas but its portals') as its stop sees them.
struct CellStopSurfaces {
  double area = 0.0;                    ///< m²
  glm::dvec3 albedoArea{0.0};           ///< Σ ρ × area (m², RGB)
  glm::dvec3 reflectorAlbedoArea{0.0};  ///< the same over the texels that do not emit: a lamp's own light
                                        ///< is not the room's, as in ambientShares
  bool written = true;  ///< false: an on-demand boundary cell, solved only to light its neighbours
};
CellStopSurfaces cellStopSurfaces(const CellState& s);

/// The graph's portals between two of its cells, as openings of the ambient term's rooms.
std::vector<AmbientOpening> cellOpenings(const CellGraph& graph);

class RoundStop;
/// The stop of the rounds of `cells` (graph order, the graph's cells).
RoundStop roundStop(const std::vector<CellState>& cells, const CellGraph& graph, double target,
                    double maxAmbientShare);
/// A round's CellRounds (graph order) as RoundStop::addRound takes them.
std::vector<const CellRound*> inGraphOrder(const std::vector<CellRound>& round);

class RoundStop {
 public:
  /// `target`: the scene's unshot power at which the rounds may stop (W); `maxAmbientShare` <= 0: they
  /// stop there (the target alone). `cells` and `openings` in graph order.
  RoundStop(double target, double maxAmbientShare, std::vector<CellStopSurfaces> cells,
            std::vector<AmbientOpening> openings);

  /// One round's figures, one CellRound per cell in graph order (a waiting cell's too): the light its
  /// reflectors gained, and the power it holds unshot after the round (its kept share and what its
  /// neighbours sent it).
  void addRound(const std::vector<const CellRound*>& round);

  /// Whether another round runs after one that left `unshot` W unshot (the emitted power before the first
  /// round). At the target it asks the ambient shares; refused, the target becomes kStopRecheck × unshot.
  bool another(double unshot);

  double target() const { return target_; }
  /// How often another() asked the ambient shares (SolveResult::stopChecks).
  int checks() const { return checks_; }
  /// Per cell, the ambient term's share of its reflectors' light (ρE / (B + ρE), R + G + B) now.
  std::vector<double> shares() const;

 private:
  double target_, maxShare_;
  std::vector<CellStopSurfaces> cells_;
  std::vector<AmbientOpening> openings_;
  std::vector<double> light_;       // per cell: Σ area × (R + G + B) of its reflectors' radiosity so far
  std::vector<glm::dvec3> unshot_;  // per cell: W (RGB) unshot after the last round
  int checks_ = 0;
};

}  // namespace cpgi
