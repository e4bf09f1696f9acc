// The artist's lightmap coordinates (issue 48, item 3): a scene that brings its own TEXCOORD_1 gets its
// engine lightmap laid out in them, checked first as a lightmapper checks them (in [0,1], no two triangles
// on the same texels, enough texels per chart), each problem naming its mesh. The light is solved on cpgi's
// own atlas and read into the artist's layout at every texel centre, on the triangle under it, as an engine
// reads cpgi's lightmap (bilinear between texel centres): one resampling, no second solve.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// What the checks of the scene's TEXCOORD_1 found, at the layout's resolution.
struct SceneUvCheck {
  int size = 0;  ///< texels along each edge of the layout (chosen by sceneUvSize)
  /// Problems that make the coordinates unusable, one line each naming the mesh (its node path): a
  /// triangle without TEXCOORD_1, coordinates outside [0,1], triangles sharing texels.
  std::vector<std::string> refusals;
  /// Problems the layout can be used with: meshes whose charts mostly get fewer than 4 texels.
  std::vector<std::string> warnings;
  size_t coveredTexels = 0;  ///< texels whose centre lies on some triangle
  bool usable() const { return refusals.empty(); }
};

/// The edge of a square layout giving the scene's TEXCOORD_1 about as many texels as `texels` (cpgi's own
/// atlas's valid texels) over the area its triangles cover, a multiple of 4 in [16, maxSize]. With
/// `triangles`, those only (one object's own square, radiosity/lightmap/object_lightmaps.h); else all.
int sceneUvSize(const Scene& scene, size_t texels, int maxSize = 8192,
                std::span<const uint32_t> triangles = {});

/// Checks every triangle's TEXCOORD_1 (Scene::looks) on a `size` × `size` layout; with `triangles`, those
/// only.
SceneUvCheck checkSceneUVs(const Scene& scene, int size, std::span<const uint32_t> triangles = {});

/// The light of cpgi's atlas `own` (`values` per texel, padding dilated) read into the scene's TEXCOORD_1 at
/// `size` × `size`: at every texel centre on a triangle, `own` at that point of the triangle (bilinear),
/// then a gutter of `gutter` texels around each chart filled from its edge. `uvs` gets each triangle's
/// corners in the layout (v down the rows, as cpgi's atlas). With `triangles`, those only are read in (and
/// only their `uvs` set).
std::vector<glm::vec3> resampleToSceneUVs(const Scene& scene, const LightmapAtlas& own,
                                          const std::vector<glm::vec3>& values, int size,
                                          std::vector<std::array<glm::vec2, 3>>& uvs, int gutter = 4,
                                          std::span<const uint32_t> triangles = {});

}  // namespace cpgi
