#include "radiosity/lightmap/cell_channel.h"

#include <algorithm>

namespace cpgi {

std::vector<float> texelCells(const LightmapAtlas& atlas, std::span<const int> cellOfTriangle) {
  std::vector<float> cells(atlas.texelCount(), -1.0f);
  auto cellOf = [&](int32_t triangle) {
    return triangle >= 0 && size_t(triangle) < cellOfTriangle.size() ? float(cellOfTriangle[triangle])
                                                                     : -1.0f;
  };
  for (const Patch& p : atlas.patches) {
    const int gx = std::max(p.grid.x, 1), gy = std::max(p.grid.y, 1);
    for (int y = 0; y < p.h; ++y)
      for (int x = 0; x < p.w; ++x) {
        const size_t t = size_t(p.y + y) * size_t(atlas.width) + size_t(p.x + x);
        if (atlas.patch[t] < 0 || &atlas.patches[size_t(atlas.patch[t])] != &p) continue;
        // The texel's quad in a merged grid (row-major, each quad w/gx × h/gy texels); else the chart's.
        const size_t q =
            size_t(std::min(y * gy / p.h, gy - 1)) * size_t(gx) + size_t(std::min(x * gx / p.w, gx - 1));
        const size_t tri = p.quads.size() > 1 && 2 * q < p.triangles.size() ? 2 * q : 0;
        cells[t] = p.triangles.empty() ? -1.0f : cellOf(p.triangles[tri]);
      }
  }
  return cells;
}

ExrChannel cellChannel(const LightmapAtlas& atlas, const Scene& scene, const CellGraph& graph) {
  const std::vector<int> cellOfTriangle = graph.cellOfTriangle(scene.triangles.size());
  return ExrChannel{kCellChannel, texelCells(atlas, cellOfTriangle)};
}

std::vector<std::string> cellNames(const CellGraph& graph) {
  std::vector<std::string> names;
  for (const Cell& c : graph.cells) names.push_back(c.name);
  return names;
}

}  // namespace cpgi
