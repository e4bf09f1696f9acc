// Light probes (issue 48 item 5): the light arriving at points through the rooms' empty space, for the
// objects a lightmap cannot hold (a character walking through the rooms). Each probe holds the L2
// spherical harmonics of the radiance arriving there, nine coefficients per colour channel in Godot's and
// Unity's basis and order (radiosity/lightmap/spherical_harmonics.h); an object shades a normal n with
// Ramamoorthi & Hanrahan's E(n) = Σ Â_l L_lm Y_lm(n), as Godot's LightmapGI probes do.
//
// Where: a lattice of `spacing` through the empty space the decomposition's voxels find enclosed
// (decomposition/classify.h: inside, not behind a wall) or roofed (outside, with a surface above and below
// it: a room whose door stands open is reachable from outside), at least `clearance` from any surface
// (decomposition/distance.h). Which room: the cell most of a probe's rays land in (the cell of the
// triangle hit), so hand-made and automatic cells alike. The light: gathered by rays from the baked
// result (radiosity/lightmap/baked_radiance.h), over the whole sphere.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/baked_radiance.h"

namespace cpgi {

struct ProbeParams {
  float spacing = 1.0f;     ///< metres between probes along x, y and z; > 0
  float clearance = 0.25f;  ///< metres a probe keeps from every surface
  float voxel = 0.1f;       ///< the voxels that find the empty space (m); at most clearance
  GatherParams gather = {1024, 256};
  uint64_t memoryLimit = 0;  ///< bytes the voxels may take (decompositionBytes; 0: none), --max-memory
};

struct LightProbe {
  glm::vec3 position{0.0f};
  int cell = -1;                  ///< index into the cell graph; −1: no cell (a graph without cells)
  std::array<glm::vec3, 9> sh{};  ///< L2 radiance SH, RGB per coefficient
};

struct LightProbes {
  std::vector<LightProbe> probes;
  ProbeParams params;
  uint64_t rays = 0;
  double seconds = 0.0;
  bool stopped = false;  ///< the deadline came before every probe was gathered
  size_t cut = 0;        ///< probes placed but left out at the deadline
};

/// Places probes in the enclosed empty space of `scene` and gathers each from the bake (`radiosity` per
/// texel of `atlas`, undilated). Deterministic. Throws InputError when the voxels would not fit in memory.
/// Past `deadline` none are placed, or the gather stops after the batch it is in (the first always runs)
/// and the probes it did not reach are left out (LightProbes::stopped, cut).
LightProbes gatherLightProbes(
    const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
    const std::vector<glm::vec3>& radiosity, const ProbeParams& params, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

/// probes.json: the convention, the spacing, and per probe its position, cell name and coefficients.
nlohmann::json lightProbesJson(const LightProbes& probes, const CellGraph& cells);

}  // namespace cpgi
