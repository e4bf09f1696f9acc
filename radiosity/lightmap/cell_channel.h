// The per-texel "cell" channel of a lightmap (design.md §5, "Per cell"): every texel carries the cell of
// the surface it samples, written by bake and reference into lightmap.exr, so that compare-light can report
// each cell's error (radiosity/metrics/cell_metrics.h) normalised by that cell's own reference.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/cell_graph.h"
#include "core/image_io.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// The lightmap.exr channel holding each texel's cell index (−1: padding or a surface in no cell).
inline constexpr const char* kCellChannel = "cell";

/// Per atlas texel, the cell of the scene triangle it samples (`cellOfTriangle`, e.g.
/// CellGraph::cellOfTriangle), −1 on padding. A merged chart (a grid of quads) may cross cells, so the
/// texel's own quad is looked up, not the chart's first one.
std::vector<float> texelCells(const LightmapAtlas& atlas, std::span<const int> cellOfTriangle);

/// The "cell" channel of a lightmap over `scene` with the cells of `graph` (all −1 when it has none), and
/// the names its indices refer to (report.json's "cell_names").
ExrChannel cellChannel(const LightmapAtlas& atlas, const Scene& scene, const CellGraph& graph);
std::vector<std::string> cellNames(const CellGraph& graph);

}  // namespace cpgi
