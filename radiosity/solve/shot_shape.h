// How the shots of a solve are made, where they are not the plain ones (every shooter a Lambertian
// emitter, received at every texel, strong by the solve's own emitted power): what a caller asks of the
// engine's backend (EngineFeatures says which engine can) and of the loop's shot scaling. Two callers
// shape shots: the cells, whose portals emit with lobes or bins and whose shots are measured against the
// whole scene's light (radiosity/cells/portal_transfer.h, cell_round.h), and the lamps' refined shot,
// received at some texels only (refined_lamp_shot.h). When to stop and what to read back is apart, in
// SolveControls (solve_controls.h).
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

namespace cpgi {

struct ShotShape {
  /// Directional emission (radiosity/solve/emission_lobes.h): shooters emit with the per-texel lobes of
  /// `emissionLobes` (one per atlas texel; zero or none = Lambertian), and every texel accumulates the
  /// direction moments of what it receives (SolveResult::arrivals). Off: the passes are built without it
  /// and cost and results are those of the plain solver. Lobes without it are an error.
  bool directionalEmission = false;
  std::span<const glm::vec4> emissionLobes = {};
  /// With directional emission, whether the receivers accumulate the direction moments of what they
  /// receive (SolveResult::arrivals; directional portals carry them). Binned portals trace their bins
  /// instead, so without the moments the shooters with no lobe shoot with the plain programs: in
  /// spot-door's cells bake every reflector shot cost 1.6× the plain one for moments nobody read.
  bool arrivalMoments = true;
  /// Binned emission (radiosity/solve/emission_bins.h) for the texels whose lobe is binnedLobe(slot): slot
  /// after slot, kBinSlotFloats factors f each: per bin red, green, blue and an unused fourth, each
  /// channel normalised to mean 1 (normalisedEmissionBins).
  std::span<const float> emissionBins = {};

  /// Whether the emitters' own shots are a lamp's (resampled at beam edges and near the emitter, with
  /// jittered eyes per strong region: receive.comp, uLampShot). A cell solve's emitters are its portals,
  /// re-emitting what its neighbours sent, which a global solve carries by plain reflector shots; shot as
  /// lamps, they cost seed1's cells bake 2.4× the CPU for no gain in any cell.
  bool emittersAreLamps = true;
  /// > 0: a shot is strong (SolverParams::strongShotRegions) when it carries at least this power (W, R + G
  /// + B) rather than strongShotFraction of the solve's own emitted power. A cell solve lit through a
  /// door measures its shots against the whole scene's light, as a global solve would: against its own
  /// small input nearly every shot was strong, 16 item buffers each, and spot-door's cells took 3× a
  /// global solve's time per shot (radiosity/cells/cell_round.h, roundBudget).
  double strongShotPower = 0.0;

  /// Receive only at the texels flagged here (one per atlas texel, non-zero: receives; empty: every texel):
  /// a lamp's shot evaluated at the output's texels only where a coarser shot found its light varying
  /// (radiosity/solve/refined_lamp_shot.h). Such a shot's sums over part of its receivers cannot check what
  /// it delivered, so it needs `patchShotScale`: per patch, the factor that patch's shots are scaled by
  /// instead of the loop's own check (SolveResult::shotScales of the coarser shot).
  std::span<const uint8_t> receivers = {};
  std::span<const float> patchShotScale = {};
  /// Per atlas patch (empty: none), non-zero for a cell's portal: the rays engine cuts its shots into
  /// finer visibility regions (LayoutParams::openings, radiosity/lightmap/shooter_layout.h). The GL engine
  /// lays them out as any patch: its cells' portals passed the light through them within 0.1 % of the
  /// reference's where the rays engine's gave 5–13 % more.
  std::span<const uint8_t> openingPatches = {};
  /// Points per edge over an opening's receiver texel on the rays engine, each seen by its own segment
  /// (a jamb hides a strip along the portal's edge from part of the texel): 4 on the solve's 0.2 m portal
  /// texels; portals charted at twice the density (CellSolveParams::portalDensityScale) take 2, the same
  /// points a square metre rather than four times the segments.
  int openingPoints = 4;
  /// Also read back what the lamps' shots found at each texel (SolveResult::lampFlags).
  bool readLampFlags = false;

  /// The number the shots count from in the eyes' draw and the item buffer's turn (jitteredEyes): 0 for a
  /// solve; bench/shot_probe.cpp averages one shot over many draws with it.
  uint32_t firstShotNumber = 0;
};

}  // namespace cpgi
