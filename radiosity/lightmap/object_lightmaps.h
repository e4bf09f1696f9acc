// Lightmaps per object (issue 48 item 3, `bake --per-object`): for engines that give every mesh its own
// lightmap, each object's light in an image of its own. The solve stays one scene solve on one atlas;
// only the output's layout differs:
//  - on cpgi's own atlas, each object's charts (with their gutter ring, already dilated) are copied texel
//    for texel into an image packed for that object alone, and its triangles' lightmap coordinates moved
//    with them: no resampling, so an engine reads exactly what it would read from the scene's atlas;
//  - on the artist's TEXCOORD_1 (`--uv scene`), each object's coordinates are its own [0,1] square, as an
//    artist unwraps a mesh for a lightmap of its own: checked and resampled object by object
//    (radiosity/lightmap/scene_uv.h), so two objects' squares may overlap each other.
// An object is a scene node (Triangle::node: a glTF node's mesh, an OBJ object or group); a chart that
// holds triangles of two objects (a merged grid of coplanar quads) is copied into both.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// One object's lightmap: its size and how it is filled from the scene's atlas.
struct ObjectLightmap {
  uint32_t node = 0;     ///< Scene::nodePaths index
  std::string name;      ///< the node's path
  std::string fileStem;  ///< "lightmap-" + the name made safe for a file name, unique in the bake
  int width = 0, height = 0;
  std::vector<uint32_t> triangles;  ///< the scene triangles it holds
  /// Own atlas: rectangles of the scene's atlas (x, y, w, h, gutter ring included) copied to (dx, dy).
  struct Copy {
    int x = 0, y = 0, w = 0, h = 0, dx = 0, dy = 0;
  };
  std::vector<Copy> copies;
  size_t validTexels = 0;  ///< the scene atlas's valid texels it holds
};

struct ObjectLightmaps {
  bool sceneUVs = false;  ///< laid out in the artist's TEXCOORD_1 (else cpgi's charts, copied)
  std::vector<ObjectLightmap> objects;
  /// Per scene triangle: the object lightmap it lies on (−1: none, a triangle outside the atlas) and its
  /// corners' coordinates in that lightmap (v down the rows, as the atlas's).
  std::vector<int> objectOfTriangle;
  std::vector<std::array<glm::vec2, 3>> triangleUV;
};

/// Lays each object's charts of `atlas` (cpgi's own) out in an image of its own, in the order of the
/// nodes. Deterministic.
ObjectLightmaps layOutObjectLightmaps(const Scene& scene, const LightmapAtlas& atlas);

/// Each object's lightmap in its TEXCOORD_1 square, sized as sceneUvSize sizes the scene's for the
/// object's share of `atlas`'s texels. Appends one line per problem (scene_uv.h's checks, object by
/// object) to `refusals` and `warnings`; the layout is usable when no refusal was added.
ObjectLightmaps layOutObjectSceneUVs(const Scene& scene, const LightmapAtlas& atlas,
                                     std::vector<std::string>& refusals, std::vector<std::string>& warnings);

/// Object `k`'s image (width × height, row-major) of `values`, per texel of `atlas` with its gutters
/// already dilated: charts copied, or read into the scene's TEXCOORD_1 with a gutter of 4 texels.
std::vector<glm::vec3> objectImage(const Scene& scene, const LightmapAtlas& atlas,
                                   const ObjectLightmaps& layout, size_t k,
                                   const std::vector<glm::vec3>& values);

/// `name` made safe for a file name: letters, digits, '-', '_' and '.' kept, every other run of bytes
/// one '_', at most 60 characters; "object" when nothing is left.
std::string safeFileName(const std::string& name);

}  // namespace cpgi
