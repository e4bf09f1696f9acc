#include "radiosity/bake/light_probes.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "decomposition/classify.h"
#include "decomposition/distance.h"
#include "decomposition/voxelize.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/spherical_harmonics.h"

namespace cpgi {
namespace {

// The lattice: every `spacing`-th voxel centre of the enclosed or roofed empty space that lies `clearance`
// clear of the surfaces (a voxel's distance is to the nearest solid voxel's centre, the surface half a voxel
// nearer).
// Past `deadline` after one of the voxels' stages (each seconds on a large level), none: `stopped` set.
std::vector<glm::vec3> probePoints(const Scene& scene, const ProbeParams& p, Context& ctx,
                                   std::chrono::steady_clock::time_point deadline, bool& stopped) {
  const auto late = [&] { return stopped = std::chrono::steady_clock::now() >= deadline; };
  decomp::VoxelizeParams v;
  v.voxelSize = p.voxel;
  v.memoryLimit = p.memoryLimit;
  const decomp::SolidGrid solid = decomp::voxelize(scene, v, ctx);
  if (late()) return {};
  const decomp::SpaceGrid space = decomp::classifySpace(scene, solid, {}, ctx);
  if (late()) return {};
  const decomp::DistanceGrid distance = decomp::distanceToGeometry(solid, space, ctx);
  if (late()) return {};
  const decomp::GridFrame& f = solid.frame;
  // A room with an open door or window is reachable from outside, so its voxels are "outside" too: those
  // under a roof (solid above and below them in their column) count as well.
  std::vector<int> lowest(size_t(f.dims.x) * f.dims.z, f.dims.y), highest(lowest.size(), -1);
  for (int z = 0; z < f.dims.z; ++z)
    for (int y = 0; y < f.dims.y; ++y)
      for (int x = 0; x < f.dims.x; ++x)
        if (space.space[f.index(x, y, z)] == decomp::Space::Solid) {
          const size_t c = size_t(z) * f.dims.x + x;
          lowest[c] = std::min(lowest[c], y), highest[c] = std::max(highest[c], y);
        }
  const int step = std::max(1, int(std::lround(p.spacing / p.voxel)));
  std::vector<glm::vec3> points;
  for (int z = step / 2; z < f.dims.z; z += step)
    for (int y = step / 2; y < f.dims.y; y += step)
      for (int x = step / 2; x < f.dims.x; x += step) {
        const size_t i = f.index(x, y, z), c = size_t(z) * f.dims.x + x;
        const bool covered = space.space[i] == decomp::Space::Outside && lowest[c] < y && y < highest[c];
        if ((space.space[i] == decomp::Space::Inside || covered) &&
            distance.metres(i) - 0.5 * f.voxel >= p.clearance)
          points.push_back(f.centre(glm::ivec3(x, y, z)));
      }
  return points;
}

// The cell most of 26 rays from `x` (the cube's faces, edges and corners) land in; −1 when none lands in a
// cell.
int cellOfPoint(const RayScene& rays, const std::vector<int>& cellOfTriangle, size_t cellCount,
                const glm::vec3& x) {
  std::vector<int> votes(cellCount, 0);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const RayScene::Hit hit = rays.intersect(x, glm::normalize(glm::vec3(dx, dy, dz)));
        if (!hit) continue;
        const int c = cellOfTriangle[size_t(hit.triangle)];
        if (c >= 0) ++votes[size_t(c)];
      }
  const auto best = std::max_element(votes.begin(), votes.end());
  return best == votes.end() || *best == 0 ? -1 : int(best - votes.begin());
}

}  // namespace

LightProbes gatherLightProbes(const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
                              const std::vector<glm::vec3>& radiosity, const ProbeParams& params,
                              Context& ctx, std::chrono::steady_clock::time_point deadline) {
  if (!(params.spacing > 0.0f) || !(params.voxel > 0.0f) || params.clearance < 0.0f)
    throw InputError("probe spacing", "the probes' spacing and voxel must be > 0");
  auto timer = ctx.time("light probes");
  const auto start = std::chrono::steady_clock::now();
  LightProbes out;
  out.params = params;
  if (start >= deadline) {  // the voxels alone take seconds on a large level
    out.stopped = true;
    ctx.warn("probes: the time limit came before the probes were placed; probes.json holds none");
    return out;
  }
  std::vector<glm::vec3> points;
  try {
    points = probePoints(scene, params, ctx, deadline, out.stopped);
  } catch (const InputError& e) {
    // The voxels' own limits name the decomposition's options; here they are the probes'.
    throw InputError("--probes",
                     std::string("the empty space is too large to find at 0.1 m voxels (") + e.what() + ")");
  }
  if (out.stopped) {
    ctx.warn("probes: the time limit came while the probes were placed; probes.json holds none");
    return out;
  }
  if (points.empty())
    ctx.warn("probes: no enclosed or roofed empty space " + std::to_string(params.clearance) +
             " m clear of the surfaces; probes.json holds none");
  const RayScene rays(scene);
  const BakedRadiance baked(scene, rays, atlas, radiosity);
  const std::vector<int> cellOfTriangle = cells.cellOfTriangle(scene.triangles.size());
  out.probes.resize(points.size());
  // In batches of about a million rays so that the deadline is seen; the first batch always runs, and the
  // probes past the deadline are left out (a probe with no light would read black).
  const int raysPerProbe = params.gather.rays + params.gather.emitterSamples + 26;
  const size_t batch = std::max<size_t>(1, (size_t(1) << 20) / size_t(std::max(1, raysPerProbe)));
  size_t end = 0;
  for (size_t from = 0; from < points.size(); from = end) {
    if (from > 0 && std::chrono::steady_clock::now() >= deadline) break;
    end = std::min(points.size(), from + batch);
    tbb::parallel_for(from, end, [&](size_t i) {
      LightProbe& probe = out.probes[i];
      probe.position = points[i];
      probe.cell = cellOfPoint(rays, cellOfTriangle, cells.cells.size(), points[i]);
      std::vector<ArrivalSample> samples;
      baked.gather(points[i], glm::vec3(0.0f), uint64_t(i), params.gather, samples);
      for (const ArrivalSample& a : samples) {
        const std::array<float, 9> y = shBasis(a.towards);
        for (size_t k = 0; k < 9; ++k) probe.sh[k] += a.light * y[k];
      }
    });
  }
  if (end < points.size()) {
    out.stopped = true;
    out.cut = points.size() - end;
    out.probes.resize(end);
    ctx.warn("probes: the time limit came after " + std::to_string(end) + " of " +
             std::to_string(points.size()) + " probes were gathered; probes.json holds those " +
             std::to_string(end));
  }
  out.rays = baked.raysTraced() + 26 * out.probes.size();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

nlohmann::json lightProbesJson(const LightProbes& probes, const CellGraph& cells) {
  nlohmann::json list = nlohmann::json::array();
  for (const LightProbe& p : probes.probes) {
    nlohmann::json sh = nlohmann::json::array();
    for (const glm::vec3& c : p.sh) sh.push_back({c.r, c.g, c.b});
    list.push_back(
        {{"position", {p.position.x, p.position.y, p.position.z}},
         {"cell", p.cell >= 0 ? nlohmann::json(cells.cells[size_t(p.cell)].name) : nlohmann::json()},
         {"sh", std::move(sh)}});
  }
  return {{"convention",
           "L2 SH of the radiance arriving, W/m2 per coefficient, basis and order of Godot's LightmapGI and "
           "Unity's SphericalHarmonicsL2: L00, L1-1 (y), L10 (z), L11 (x), L2-2 (xy), L2-1 (yz), L20 "
           "(3z2-1), L21 (xz), L22 (x2-y2); scene axes; irradiance E(n) = sum_l A_l sum_m L_lm Y_lm(n), "
           "A = pi, 2pi/3, pi/4 (Ramamoorthi and Hanrahan 2001)"},
          {"spacing_m", probes.params.spacing},
          {"clearance_m", probes.params.clearance},
          {"rays_per_probe", probes.params.gather.rays},
          {"count", probes.probes.size()},
          {"probes", std::move(list)}};
}

}  // namespace cpgi
