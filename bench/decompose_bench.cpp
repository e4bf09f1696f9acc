// Seconds and peak memory of the decomposition against voxel count, on the procedural house
// (bench/house.h). One configuration per process, so that the peak resident size is this run's:
//   decompose_bench --voxel 0.05 [--rooms 3] [--furniture 30] [--wall-cell 0.3] [--png PICTURE.png]
// prints one JSON object; bench/decompose_bench.sh sweeps voxel sizes under /usr/bin/time -v.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/house.h"
#include "core/image_io.h"
#include "decomposition/decompose.h"
#include "decomposition/picture.h"

int main(int argc, char** argv) {
  cpgi::bench::HouseParams house;
  double voxel = 0.05;
  std::string png;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    const double v = std::atof(argv[i + 1]);
    if (k == "--voxel") voxel = v;
    else if (k == "--png") png = argv[i + 1];
    else if (k == "--rooms") house.roomsPerSide = int(v);
    else if (k == "--furniture") house.furniturePerRoom = int(v);
    else if (k == "--wall-cell") house.wallCell = float(v);
    else {
      std::fprintf(stderr, "decompose_bench: unknown option %s\n", k.c_str());
      return 1;
    }
  }
  int expectedCells = 0, doors = 0;
  const cpgi::Scene scene = cpgi::bench::makeHouse(house, &expectedCells, &doors);
  cpgi::Context ctx;
  cpgi::decomp::DecomposeParams params;
  params.voxelSize = voxel;
  params.sourceName = "house";
  const auto start = std::chrono::steady_clock::now();
  const cpgi::decomp::Decomposition d = cpgi::decomp::decompose(scene, params, ctx);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  nlohmann::json j;
  j["triangles"] = scene.triangles.size();
  j["voxel_m"] = voxel;
  j["voxels"] = d.frame.count();
  j["dims"] = {d.frame.dims.x, d.frame.dims.y, d.frame.dims.z};
  size_t inside = 0;
  for (auto s : d.space) inside += s == cpgi::decomp::Space::Inside;
  j["inside_voxels"] = inside;
  j["cells"] = d.graph.cells.size();
  j["portals"] = d.graph.portals.size();
  j["expected_cells"] = expectedCells;
  j["doors"] = doors;
  j["basins"] = d.basins;
  j["leaking_faces"] = d.leakingFaces;
  j["fallback_triangles"] = d.fallbackTriangles;
  j["split_triangles"] = d.splitTriangles;
  j["seconds"] = seconds;
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& t : ctx.timings()) stages[t.stage] = stages.value(t.stage, 0.0) + t.seconds;
  j["stages_s"] = stages;
  j["peak_rss_mb"] = double(usage.ru_maxrss) / 1024.0;
  j["warnings"] = ctx.warnings();
  std::printf("%s\n", j.dump().c_str());
  if (!png.empty()) cpgi::writePng(png, cpgi::decomp::drawDecomposition(d));
  return 0;
}
