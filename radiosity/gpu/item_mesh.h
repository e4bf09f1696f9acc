#pragma once
// The triangles an item buffer draws (shaders/item.vert), as an indexed mesh. A vertex is shared by the
// triangles of one patch that meet at it, and only by those: its patch ID and the patch's normal (the side
// a receiver is on) travel with it, so what each triangle draws is what it drew on its own. Drawn
// indexed, llvmpipe shades each shared vertex once per batch instead of once per corner: the item buffers
// are 5 hemicube faces × every triangle × up to 16 eyes a shot, and their vertex work was most of them on
// a furnished house (bench/RESULTS.md, "Item buffers drawn indexed").
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

struct ItemMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< per vertex: its patch's normal (a face's own outside the atlas)
  std::vector<int32_t> patches;    ///< per vertex: its patch, -2 for a triangle outside the atlas
  std::vector<uint32_t> indices;   ///< three per drawn triangle, in the scene's triangle order
};

/// Every triangle of positive area, indexed; vertices shared where position, patch and normal are the same
/// bits.
ItemMesh buildItemMesh(const Scene& scene, const LightmapAtlas& atlas);

}  // namespace cpgi
