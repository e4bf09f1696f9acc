// Where the cells of a `--method cells` bake come from, shared by `cpgi bake --cells` and
// `cpgi compare-cells --bake`, so that both bake with exactly the same graph for the same source.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/image_io.h"
#include "core/scene.h"
#include "core/scene_io.h"
#include "decomposition/decompose.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// The cells of `cellsFile` (another file of the same scene, e.g. a decompose output's cells.glb or the
/// hand-made scene) over `scene`'s triangles, matched by centroid to the millimetre and by the side they
/// face (the two faces of a zero-thickness wall share a centroid), so a different triangle order does not
/// matter. Triangles of `scene` found in no cell of the file stay in none (a warning in ctx naming
/// `name`). Throws InputError when the file has no cells.
CellGraph matchCellsToScene(const Scene& scene, const LoadedScene& cellsFile, const std::string& name,
                            Context& ctx);

/// bake's `--cells SOURCE` for the scene loaded from `scenePath`:
///  - "auto": the automatic decomposition with `params`; it may split triangles on portal planes, so it
///    replaces loaded.scene by the split scene;
///  - a folder: its cells.glb (a `cpgi decompose` output);
///  - the scene file itself: its own cell:/portal: nodes, or rooms given only as cellvolume: meshes
///    (decomp::decomposeFromVolumes with `params`' voxel size; like auto, it replaces loaded.scene by the
///    split scene);
///  - another glTF of the same scene: matchCellsToScene.
/// Throws InputError("--cells", ...) for "none" or a missing file, and InputError("time limit", ...) when
/// `deadline` comes during a decomposition (checked at each of its stages): a cells bake has no result
/// without its cells.
CellGraph resolveCells(
    const std::string& source, const std::string& scenePath, LoadedScene& loaded,
    const decomp::DecomposeParams& params, const LoadOptions& load, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

/// The rooms of a scene without cells of its own, for its lightmap's "cell" channel (compare-light's
/// per-cell figures) and the ambient term: the automatic decomposition with default options (so that bake
/// and reference label alike), each texel given the room in front of it (decomp::cellsFaced); no triangle
/// is split. `graph` holds the rooms' names and portals, no triangles. Both are empty when the
/// decomposition finds fewer than two rooms or cannot take the scene, or when `deadline` comes during it
/// (checked at each of its stages; said in a warning): then the scene is one room.
struct RoomLabels {
  CellGraph graph;
  ExrChannel channel;
};
/// With `volumes` (rooms given only as cellvolume: meshes, CellGraph::definedByVolumes), the rooms are
/// those volumes' cells (decomp::decomposeFromVolumes) instead.
/// `memoryLimit`: bytes the decomposition may take (DecomposeParams::memoryLimit, 0: none); a
/// decomposition that would take more is not made (said in a warning): the scene is one room.
/// `wallPerCpuSecond`: the wall seconds a CPU second takes as the machine runs (the bake's CpuShare::ratio);
/// a decomposition whose estimate (roomsCpuSeconds at it) would end past `deadline` is not started (said in
/// a warning): a stage of it cannot stop part-way, and at 2 % of a core one took 20-45 s. Nor is the
/// estimate made when its own coarse pass (roomsExtentCpuSeconds at it) would end past `deadline`.
RoomLabels labelTexelsByRoom(
    const Scene& scene, const std::string& scenePath, const LightmapAtlas& atlas, Context& ctx,
    const CellGraph& volumes = {},
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max(),
    uint64_t memoryLimit = 0, double wallPerCpuSecond = 1.0);

/// The CPU seconds of labelTexelsByRoom's decomposition of `scene` on an idle core, from its voxels at the
/// automatic voxel size (bench/RESULTS.md, "Never past --time-limit when the bake gets 2 % of a core").
double roomsCpuSeconds(const Scene& scene);
/// The most CPU seconds roomsCpuSeconds takes on an idle core: its coarse pass over the scene's triangles
/// (decomp::chooseGrid's extent).
double roomsExtentCpuSeconds(const Scene& scene);

}  // namespace cpgi
