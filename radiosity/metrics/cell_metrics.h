// Per-cell accuracy (design.md §5, "Per cell"): the whole-atlas figure is dominated by the lit rooms, so
// a room lit only through doors can be +50 % off while the scene's relative RMSE reads 0.5 %. Every texel
// carries the cell of the surface it samples (a "cell" channel in lightmap.exr,
// radiosity/lightmap/cell_channel.h), and compare-light reports each cell's figures normalised by that cell's
// own reference.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cpgi {

struct CellError {
  std::string name;
  size_t texels = 0;  ///< texels compared (weight > 0)
  /// Σ_c w a B / Σ_c w a R over R + G + B: > 1 when the cell is too bright.
  double ratioOfMeans = 0.0;
  /// The reference's weighted mean over the cell, (R + G + B) / 3, W/m²: how bright the room is, beside the
  /// other rooms (a room lit at a leak's level is black at any exposure that shows the lit ones).
  double referenceMean = 0.0;
  /// sqrt(Σ_c w a |B − R|² / Σ_c w a |R|²): normalised by this cell's own reference.
  double relRmse = 0.0;
  /// The reference's own noise, as relRmse would see it: sqrt(Σ_c w a σ² / Σ_c w a |R|²).
  double referenceNoise = 0.0;
  /// The test's own error with the reference's noise taken out: E|B − R|² = |B − truth|² + σ², so
  /// sqrt(max(relRmse² − referenceNoise², 0)). In a dim room the reference's per-texel noise can be most
  /// of relRmse (openings' C: 7.4 % of 9.8 % at 4096 paths a texel).
  double relRmseWithoutNoise = 0.0;
  /// Standard error of ratioOfMeans from the reference: its per-texel noise (√3 |σ|, channels taken as
  /// fully correlated, which bounds the sum's error) and, on a sparse reference, the texel sampling.
  double ratioError = 0.0;
  /// The cell's colour against the reference's: (ΣB_r / ΣB_g) / (ΣR_r / ΣR_g) over its weighted texels,
  /// and the same for blue over green; 1 when the light that bounced off coloured walls next door came
  /// through with its colour (NaN where a channel of either sum is 0).
  double redGreenRatio = 0.0, blueGreenRatio = 0.0;
};

/// Per-cell figures of `test` against `reference`; `weight` is area × sample weight (0: not compared,
/// e.g. padding, lamps, texels a sparse reference did not trace), `sigma` the reference's per-texel
/// standard error (RGB norm; empty: unknown, noise figures 0), `sampleWeight` the sparse reference's
/// per-texel weights (empty: a full reference), `validTexels` the texel count it was drawn from.
/// Cells with no compared texel get texels = 0 and NaN figures. Throws std::invalid_argument on size
/// mismatches.
std::vector<CellError> compareCells(std::span<const glm::vec3> test, std::span<const glm::vec3> reference,
                                    std::span<const float> weight, std::span<const float> sigma,
                                    std::span<const float> cell, std::span<const float> sampleWeight,
                                    size_t validTexels, const std::vector<std::string>& names);

/// A reference's own noise in one cell: what a comparison against it can resolve there.
struct CellNoise {
  std::string name;
  size_t texels = 0;  ///< texels with weight > 0 in this cell
  /// Relative standard error of the cell's mean (Σ w (R+G+B) / Σ w), from the per-texel noise (√3 |σ| a
  /// texel, as CellError::ratioError): a bias of three times this is measurable in the cell's ratio.
  double meanNoise = 0.0;
  /// sqrt(Σ w σ² / Σ w |R|²), the floor of the cell's relative RMSE (CellError::referenceNoise).
  double texelNoise = 0.0;
};

/// Per-cell noise of a reference (`sigma` its per-texel standard error, RGB norm; `weight` area × sample
/// weight, 0 where not traced). Cells with no weighted texel or a black reference get NaN figures.
/// Throws std::invalid_argument on size mismatches.
std::vector<CellNoise> referenceCellNoise(std::span<const glm::vec3> reference, std::span<const float> sigma,
                                          std::span<const float> weight, std::span<const float> cell,
                                          const std::vector<std::string>& names);

/// The headline: the cell whose ratio of means is farthest from 1 (in log terms, so ×0.5 and ×2 weigh
/// alike), among cells with texels and a non-zero reference; nullopt when there is none.
std::optional<size_t> worstCell(const std::vector<CellError>& cells);

}  // namespace cpgi
