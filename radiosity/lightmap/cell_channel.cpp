#include "radiosity/lightmap/cell_channel.h"

#include <algorithm>

namespace cpgi {

std::vector<float> texelCells(const LightmapAtlas& atlas, std::span<const int> cellOfTriangle) {
  std::vector<float> cells(atlas.texelCount(), -1.0f);
  auto cellOf = [&](int32_t triangle) {
    return triangle >= 0 && size_t(triangle) < cellOfTriangle.size() ? float(cellOfTriangle[triangle])
                                                                     : -1.0f;
  };
  for (const Patch& p : atlas.patches)
    for (int y = 0; y < p.h; ++y)
      for (int x = 0; x < p.w; ++x) {
        const size_t t = size_t(p.y + y) * size_t(atlas.width) + size_t(p.x + x);
        if (atlas.patch[t] < 0 || &atlas.patches[size_t(atlas.patch[t])] != &p) continue;
        // The texel's own quad: a merged chart (a grid of quads) may cross cells.
        cells[t] = cellOf(texelTriangle(p, x, y));
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
