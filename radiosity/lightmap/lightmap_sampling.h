// A lightmap read as an engine reads it: the triangle's lightmap coordinates interpolated over it and a
// bilinear lookup between texel centres. With that, a lightmap on one atlas can be judged on another's
// texels (issue 13: a bake whose texels follow the light against a reference at a fixed fine density),
// which a texel-by-texel comparison cannot do, and a coarse lightmap is charged for the detail it blurs.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// The value of a `width` × `height` lightmap at atlas coordinates `uv` in [0,1]² (texel centres at
/// (i+½)/width, v down the rows), bilinear between the four nearest texels, clamped at the border.
glm::vec3 sampleBilinear(int width, int height, std::span<const glm::vec3> lightmap, glm::vec2 uv);

/// Per triangle of `scene`, the index of the triangle of `other` with the same three corners in the
/// same order (bit for bit: a baked.glb read back holds the positions it was written from), or −1.
/// What a lightmap's coordinates, stored per triangle of its own file, are for each triangle of a scene
/// that lists them in another order.
std::vector<int32_t> matchTriangles(const Scene& scene, const Scene& other);

/// Per texel of `atlas` (an atlas of `scene`), `lightmap` (width × height, padding already dilated)
/// looked up at the texel's centre: its point on the triangle under it, given the coordinates of that
/// triangle's corners in `lightmap` by `uvs[source[triangle]]`. 0 on padding; `missing` (when not null)
/// counts the valid texels whose triangle has no entry in `source` (< 0), left 0.
std::vector<glm::vec3> sampleAtTexels(const LightmapAtlas& atlas, const Scene& scene,
                                      std::span<const int32_t> source,
                                      std::span<const std::array<glm::vec2, 3>> uvs, int width, int height,
                                      std::span<const glm::vec3> lightmap, size_t* missing = nullptr);

/// Per triangle of `scene` that `source` (matchTriangles(scene, other)) leaves unmatched, the triangles
/// of `other` that no scene triangle matched and that lie on it: in its plane, facing its way, every
/// corner on it (the pieces a bake on the automatic cells cut it into on its portal planes); empty for
/// the others, and for a triangle `other` dropped.
std::vector<std::vector<int32_t>> matchSplitPieces(const Scene& scene, const Scene& other,
                                                   std::span<const int32_t> source);

/// sampleAtTexels for the texels whose triangle `source` leaves unmatched: the texel's centre held onto
/// the nearer of its quad's two triangles (texelTriangle names a quad's first for all its texels, and a
/// border texel's centre lies off both), then read through that triangle's match, or on its piece
/// (`pieces`, from matchSplitPieces; indices into `other` and `uvs`) nearest to the point, which holds
/// it unless a sliver of the cut was dropped. Writes those texels of `out`; returns how many valid texels
/// lie on a triangle with neither match nor piece, marked 1 in `unread` (atlas-sized), left as they were.
size_t sampleOnSplitPieces(const LightmapAtlas& atlas, const Scene& scene, std::span<const int32_t> source,
                           const std::vector<std::vector<int32_t>>& pieces, const Scene& other,
                           std::span<const std::array<glm::vec2, 3>> uvs, int width, int height,
                           std::span<const glm::vec3> lightmap, std::vector<glm::vec3>& out,
                           std::vector<char>& unread);

}  // namespace cpgi
