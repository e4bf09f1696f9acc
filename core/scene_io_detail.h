// Internal to the scene readers: what a format reader hands to the shared checks of loadScene, and the
// cell naming convention of design.md §3 shared by the glTF and OBJ readers and the glTF writer.
#pragma once

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/scene.h"
#include "core/scene_io.h"

namespace cpgi::detail {

/// What a node/object name says about its role in the cell-portal graph.
struct CellTag {
  enum class Kind { None, Cell, Portal, CellVolume, Seal } kind = Kind::None;
  std::string a;  ///< the cell (Cell, CellVolume), the first cell of a portal, or the seal's name
  std::string b;  ///< the second cell of a portal
};
/// Parses `cell:NAME`, `portal:A:B` (a Blender duplicate suffix such as ".001" on B is ignored),
/// `cellvolume:NAME` and `seal:NAME`. Throws InputError(file, ...) for a malformed tag such as `portal:A`.
CellTag parseCellTag(const std::string& file, const std::string& nodeName);

/// A scene as a format reader found it, before the checks and the cell graph are built.
struct RawScene {
  Scene scene;                         ///< triangles, materials, node paths, cameras
  std::vector<int> cellOfTriangle;     ///< per scene triangle: index into cellNames, or -1
  std::vector<std::string> cellNames;  ///< cells in order of first appearance
  struct TaggedMesh {
    std::string node;  ///< full node name, e.g. "portal:A:B"
    CellTag tag;
    std::vector<Triangle> triangles;  ///< world space
  };
  std::vector<TaggedMesh> portals, volumes;
  std::vector<TaggedMesh> seals;  ///< `seal:` meshes: Scene::seal
  std::vector<std::string> warnings;
  /// Per scene triangle, its corners' second texture coordinates (glTF TEXCOORD_1: a baked lightmap's
  /// atlas); kept only when every triangle has them (`everyLightmapUV`).
  std::vector<std::array<glm::vec2, 3>> lightmapUVs;
  bool everyLightmapUV = true;
  /// Per scene triangle, its corners' first texture coordinates (glTF TEXCOORD_0), and which sets it has
  /// (bit 0: TEXCOORD_0, bit 1: TEXCOORD_1): finishScene keeps them as SceneLooks::uvs.
  std::vector<std::array<glm::vec2, 3>> textureUVs;
  std::vector<uint8_t> uvSets;

  /// Index of the cell called `name`, added if new.
  int cellIndex(const std::string& name);
  /// Index of `path` in scene.nodePaths, added if new.
  uint32_t nodeIndex(const std::string& path);

 private:
  std::unordered_map<std::string, uint32_t> nodeIndex_;  // scenes may have many thousand nodes
};

RawScene readGltf(const std::string& path, const LoadOptions& options);
RawScene readObj(const std::string& path, const LoadOptions& options);

/// The checks shared by every format (non-finite positions, degenerate and duplicate triangles, empty
/// scene) and the cell graph (portal quads, orientation, validateCells).
/// Throws InputError("time limit", ...) when options.deadline has passed: `path` was being read, `step` says
/// how far (e.g. "after 3 of 40 meshes").
void requireReadingTime(const std::string& path, const LoadOptions& options, const std::string& step);

LoadedScene finishScene(const std::string& path, RawScene raw, const LoadOptions& options);

/// Orders a portal's 4 distinct corners around their boundary; throws InputError when the mesh is not
/// one quad of 2 triangles.
std::array<glm::vec3, 4> portalCorners(const std::string& file, const std::string& node,
                                       const std::vector<Triangle>& triangles);

}  // namespace cpgi::detail
