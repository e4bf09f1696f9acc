#include "apps/compare_light_cells.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace cpgi::cli {

std::vector<std::string> readCellNames(const std::string& dir) {
  const std::filesystem::path path = std::filesystem::path(dir) / "report.json";
  std::ifstream in(path);
  if (!in) return {};
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (report.is_discarded() || !report.contains("cell_names")) return {};
  if (!report["cell_names"].is_array()) throw InputError(path.string(), "\"cell_names\" is not an array");
  std::vector<std::string> names;
  for (const nlohmann::json& n : report["cell_names"]) {
    if (!n.is_string()) throw InputError(path.string(), "\"cell_names\" holds a non-string");
    names.push_back(n.get<std::string>());
  }
  return names;
}

namespace {

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json cellsJson(const std::vector<CellError>& cells) {
  nlohmann::json out = nlohmann::json::array();
  for (const CellError& c : cells)
    out.push_back({{"name", c.name},
                   {"texels", c.texels},
                   {"ratio_of_means", number(c.ratioOfMeans)},
                   {"ratio_error", number(c.ratioError)},
                   {"reference_mean", number(c.referenceMean)},
                   {"rel_rmse", number(c.relRmse)},
                   {"rel_rmse_without_noise", number(c.relRmseWithoutNoise)},
                   {"reference_noise", number(c.referenceNoise)},
                   {"red_green_ratio", number(c.redGreenRatio)},
                   {"blue_green_ratio", number(c.blueGreenRatio)}});
  return out;
}

nlohmann::json cellNoiseJson(const std::vector<CellNoise>& cells) {
  nlohmann::json out = nlohmann::json::array();
  for (const CellNoise& c : cells)
    out.push_back({{"name", c.name},
                   {"texels", c.texels},
                   {"mean_noise", number(c.meanNoise)},
                   {"texel_noise", number(c.texelNoise)}});
  return out;
}

void printCells(const std::vector<CellError>& cells) {
  const std::optional<size_t> worst = worstCell(cells);
  std::printf("per cell (without lamps)   ratio of means       rel_rmse   ref. noise  without it  texels\n");
  for (size_t c = 0; c < cells.size(); ++c) {
    const CellError& e = cells[c];
    if (e.texels == 0) {
      std::printf("  %-24s no texel compared\n", e.name.c_str());
      continue;
    }
    std::printf("  %-24s %7.4f +- %.4f  %8.3f%%  %8.3f%%  %8.3f%%  %6zu%s\n", e.name.c_str(), e.ratioOfMeans,
                e.ratioError, 100.0 * e.relRmse, 100.0 * e.referenceNoise, 100.0 * e.relRmseWithoutNoise,
                e.texels, worst && *worst == c ? "  <- worst" : "");
  }
}

}  // namespace cpgi::cli
