// compare-light's per-cell figures (design.md §5): each texel's cell from the lightmaps' "cell" channel
// (the reference's, else the lightmap's under test) and the cells' names from the folders' report.json.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "radiosity/metrics/cell_metrics.h"

namespace cpgi::cli {

/// The names of the cells the "cell" channel of `dir`/lightmap.exr indexes: report.json's "cell_names";
/// empty when the folder has none (an older output).
std::vector<std::string> readCellNames(const std::string& dir);

/// "cells": [{name, texels, ratio_of_means, ratio_error, rel_rmse, reference_noise}], NaN as null.
nlohmann::json cellsJson(const std::vector<CellError>& cells);

/// A reference's "cells_noise": [{name, texels, mean_noise, texel_noise}], NaN as null.
nlohmann::json cellNoiseJson(const std::vector<CellNoise>& cells);

/// One line per cell, the worst marked, for compare-light's text output.
void printCells(const std::vector<CellError>& cells);

}  // namespace cpgi::cli
