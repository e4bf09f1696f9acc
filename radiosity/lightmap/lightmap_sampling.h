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

}  // namespace cpgi
