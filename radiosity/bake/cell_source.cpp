#include "radiosity/bake/cell_source.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <tuple>

#include "core/error.h"
#include "decomposition/faced_cells.h"
#include "decomposition/outside_portals.h"
#include "decomposition/volume_cells.h"
#include "radiosity/lightmap/cell_channel.h"

namespace cpgi {
namespace {

using Clock = std::chrono::steady_clock;

// Thrown out of a decomposition that a deadline ends (deadlineContext).
struct DeadlineReached {};

// A Context for a decomposition run inside a bake: its progress goes on to `outer`'s when `forward`, and
// past `deadline` its next progress report (the decomposition makes one at the end of each stage, and
// through the watershed's levels) throws DeadlineReached, which ends it.
Context deadlineContext(const Context& outer, bool forward, Clock::time_point deadline) {
  Context inner;
  inner.setProgress([&outer, forward, deadline](const Progress& p) {
    if (Clock::now() >= deadline) throw DeadlineReached{};
    if (forward) outer.progress(p);
  });
  return inner;
}

}  // namespace

CellGraph matchCellsToScene(const Scene& scene, const LoadedScene& cellsFile, const std::string& name,
                            Context& ctx) {
  if (cellsFile.cells.empty()) throw InputError(name, "has no cell:/portal: nodes");
  // The centroid to the millimetre and the side the triangle faces: the two faces of a zero-thickness
  // partition share their centroids, and by centroid alone both went to one room, which then had the
  // partition twice and the other none (openings: a third of room B's light escaped through the hole).
  auto key = [](const Triangle& t) {
    const glm::ivec3 k = glm::ivec3(glm::round(t.centroid() * 1000.0f));
    const glm::ivec3 side = glm::ivec3(glm::round(t.geometricNormal() * 8.0f));
    return std::tuple{k.x, k.y, k.z, side.x, side.y, side.z};
  };
  std::map<std::tuple<int, int, int, int, int, int>, int> cellAt;
  const std::vector<int> otherCell = cellsFile.cells.cellOfTriangle(cellsFile.scene.triangles.size());
  for (size_t t = 0; t < cellsFile.scene.triangles.size(); ++t)
    cellAt[key(cellsFile.scene.triangles[t])] = otherCell[t];
  CellGraph graph = cellsFile.cells;
  for (Cell& c : graph.cells) c.triangles.clear();
  size_t unmatched = 0;
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto it = cellAt.find(key(scene.triangles[t]));
    if (it == cellAt.end())
      ++unmatched;
    else if (it->second >= 0)
      graph.cells[it->second].triangles.push_back(uint32_t(t));
  }
  if (unmatched > 0)
    ctx.warn(name + ": " + std::to_string(unmatched) + " triangles of the scene are not in the cells file");
  return graph;
}

CellGraph resolveCells(const std::string& source, const std::string& scenePath, LoadedScene& loaded,
                       const decomp::DecomposeParams& params, const LoadOptions& load, Context& ctx,
                       Clock::time_point deadline) {
  // No cells named: the scene's own (cell:/portal: nodes or room volumes) when it has them, else the
  // automatic ones, as a user asking for the cells method on a scene that holds its rooms expects.
  if (source.empty())
    return resolveCells(loaded.cells.empty() ? "auto" : scenePath, scenePath, loaded, params, load, ctx,
                        deadline);
  if (source == "none")
    throw InputError("--cells", "--method cells needs cells: a glTF with cell:/portal: nodes, or auto");
  decomp::DecomposeParams p = params;
  p.sourceName = scenePath;
  // The decomposition splits triangles: the scene becomes the split one, with the same lights, sky and looks.
  auto takeDecomposition = [&](decomp::Decomposition d) {
    std::vector<PunctualLight> lights = std::move(loaded.scene.lights);
    const Sky sky = loaded.scene.sky;
    SceneLooks looks = std::move(loaded.scene.looks);  // the pieces keep their source's Triangle::uv
    loaded.scene = std::move(d.scene);
    loaded.scene.lights = std::move(lights);
    loaded.scene.sky = sky;
    loaded.scene.looks = std::move(looks);
    return std::move(d.graph);
  };
  // Past the deadline a cells bake has no cells to bake with: one line naming the limit.
  auto decomposeBy = [&](auto&& run) {
    Context inner = deadlineContext(ctx, true, deadline);
    try {
      decomp::Decomposition d = run(inner);
      for (const std::string& w : inner.warnings()) ctx.warn(w);
      for (const Context::Timing& t : inner.timings()) ctx.addTiming(t.stage, t.seconds);
      return d;
    } catch (const DeadlineReached&) {
      throw InputError("time limit", "came during the decomposition of " + scenePath +
                                         " into cells, before any light was solved; raise it, or decompose "
                                         "once (cpgi decompose) and give its folder as `cell graph`");
    }
  };
  if (source == "auto") {
    auto t = ctx.time("decompose");
    decomp::Decomposition d =
        decomposeBy([&](Context& inner) { return decomp::decompose(loaded.scene, p, inner); });
    if (d.graph.cells.size() < 2) ctx.warn(scenePath + ": the automatic decomposition found one cell");
    decomp::nameCellsByVolumes(d, loaded.cells);  // named by the scene's room volumes where one covers them
    return takeDecomposition(std::move(d));
  }
  std::filesystem::path path = source;
  if (std::filesystem::is_directory(path)) path /= "cells.glb";
  if (!std::filesystem::exists(path)) throw InputError("--cells", path.string() + ": no such file");
  auto fromVolumes = [&](const CellGraph& volumes) {
    auto t = ctx.time("decompose");
    return takeDecomposition(decomposeBy(
        [&](Context& inner) { return decomp::decomposeFromVolumes(loaded.scene, volumes, p, {}, inner); }));
  };
  // Read back from a file, portals onto the outside may face into their room (outside_portals.h).
  if (std::filesystem::equivalent(path, scenePath)) {
    if (loaded.cells.empty()) throw InputError(path.string(), "has no cell:/portal:/cellvolume: nodes");
    if (loaded.cells.definedByVolumes()) return fromVolumes(CellGraph(loaded.cells));
    CellGraph graph = loaded.cells;
    decomp::orientOutsidePortals(loaded.scene, graph);
    return graph;
  }
  const LoadedScene other = loadScene(path.string(), load);
  if (other.cells.definedByVolumes()) return fromVolumes(other.cells);
  CellGraph graph = matchCellsToScene(loaded.scene, other, path.string(), ctx);
  decomp::orientOutsidePortals(loaded.scene, graph);
  return graph;
}

// The decomposition's CPU seconds a voxel on an idle core (voxels, distances, watershed, leaks, portals):
// game maps decomposed at the automatic 4 M voxels took 5-33 CPU s (bench/RESULTS.md, "Eight OpenArena
// 0.8.5/0.8.8 maps"), 1.3-8e-6 a voxel since the contact cuts and the leaks stage; at 4e-7 kaos2's rooms,
// estimated to fit, ran 73 s at 0.1 of a core and took its files' time.
constexpr double kRoomsCpuPerVoxel = 3e-6;

double roomsCpuSeconds(const Scene& scene) {
  // The grid spans where the rooms are (decomp::chooseGrid), not the bounds: a level's far scenery would
  // otherwise make a fine voxel's grid look hundreds of times larger than it is.
  Context quiet;
  const decomp::GridChoice grid = decomp::chooseGrid(scene, decomp::DecomposeParams{}, quiet);
  const double voxel = grid.voxel;
  const glm::dvec3 size = glm::dvec3(grid.extent.box.size()) + 2.0 * decomp::DecomposeParams{}.outsideMargin;
  return kRoomsCpuPerVoxel * (size.x / voxel + 1.0) * (size.y / voxel + 1.0) * (size.z / voxel + 1.0);
}

// The extent's coarse pass a triangle on an idle core, with room to spare: kaos2's 30 511 triangles took
// 20 s of wall at load 12 on 2 cores (about 0.09 of a core), 1.8 CPU s.
constexpr double kRoomsExtentCpuPerTriangle = 1e-4;

double roomsExtentCpuSeconds(const Scene& scene) {
  return kRoomsExtentCpuPerTriangle * double(scene.triangles.size());
}

RoomLabels labelTexelsByRoom(const Scene& scene, const std::string& scenePath, const LightmapAtlas& atlas,
                             Context& ctx, const CellGraph& volumes, Clock::time_point deadline,
                             uint64_t memoryLimit, double wallPerCpuSecond) {
  auto t = ctx.time("rooms");
  RoomLabels out;
  const char* late =
      "rooms: the time limit came during the decomposition into rooms; the stop per room and the ambient "
      "term take the scene as one room";
  // Past the deadline already, not even its first stage (the voxels: seconds on a loaded machine).
  if (Clock::now() >= deadline) {
    ctx.warn(late);
    return out;
  }
  if (deadline != Clock::time_point::max() && !volumes.definedByVolumes()) {
    const double ratio = std::max(1.0, wallPerCpuSecond);
    // The estimate's own coarse pass cannot stop either: on a map it ran 20 s past the limit, to find it
    // had no time.
    const double extent = roomsExtentCpuSeconds(scene) * ratio;
    if (extent > std::chrono::duration<double>(deadline - Clock::now()).count()) {
      char line[300];
      std::snprintf(line, sizeof line,
                    "rooms: the decomposition into rooms would end past the time limit (its first pass alone "
                    "about %.3g s as the machine runs): not started; the stop per room and the ambient term "
                    "take the scene as one room",
                    extent);
      ctx.warn(line);
      return out;
    }
    const double estimate = roomsCpuSeconds(scene) * ratio;
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (estimate > left) {
      char line[300];
      std::snprintf(line, sizeof line,
                    "rooms: the decomposition into rooms, estimated at %.3g s as the machine runs, would end "
                    "past the time limit (%.3g s left): not started; the stop per room and the ambient term "
                    "take the scene as one room",
                    estimate, left);
      ctx.warn(line);
      return out;
    }
  }
  decomp::Decomposition d;
  try {
    // The decomposition's warnings are about cells the user did not ask for.
    Context quiet = deadlineContext(ctx, false, deadline);
    decomp::DecomposeParams params;
    params.sourceName = scenePath;
    params.memoryLimit = memoryLimit;
    d = volumes.definedByVolumes() ? decomp::decomposeFromVolumes(scene, volumes, params, {}, quiet)
                                   : decomp::decompose(scene, params, quiet);
  } catch (const InputError& e) {
    // requireMemory's refusal (core/memory_limit.h) is the user's limit, said without its remedy (the
    // rooms' voxel is not the bake's to set); any other is the scene's shape (no room found), which the
    // scene taken as one room answers.
    const std::string& problem = e.problem();
    if (problem.find("`maximum memory`") != std::string::npos)
      ctx.warn("rooms: " + problem.substr(0, problem.find(';')) +
               "; the stop per room and the ambient term take the scene as one room");
    return out;
  } catch (const DeadlineReached&) {
    ctx.warn(late);
    return out;
  }
  if (d.graph.cells.size() < 2) return out;
  std::vector<glm::vec3> points, normals;
  std::vector<size_t> texel;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0)
      points.push_back(atlas.position[i]), normals.push_back(atlas.normal[i]), texel.push_back(i);
  const std::vector<int> cell = decomp::cellsFaced(d, points, normals);
  out.channel = ExrChannel{kCellChannel, std::vector<float>(atlas.texelCount(), -1.0f)};
  for (size_t k = 0; k < texel.size(); ++k) out.channel.values[texel[k]] = float(cell[k]);
  out.graph = std::move(d.graph);
  for (Cell& c : out.graph.cells) c.triangles.clear();  // they index the decomposition's split scene
  return out;
}

}  // namespace cpgi
