// Converts the world geometry of a Quake III BSP (version 46: OpenArena's maps, as in Debian's
// openarena-data) to OBJ in metres, y up, for running the decomposition on real levels the project did
// not make. Polygon and mesh faces are triangle lists; Bézier patches are tessellated; billboards and
// brush models other than the world (doors, platforms) are left out, and so are the see-through
// surfaces a player walks through (texture flagged SURF_NONSOLID, contents not CONTENTS_SOLID: fog
// volumes' faces, light beams, clear water's surface), which are no walls: on oa_dm7 a pool's surface
// and a fog layer sealed the whole lower level and the open arena off as rooms without a door
// (issue 46); and so are the faces of water and fog that the shader does not flag non-solid (light
// crosses them in the game: hydronex's water sealed its lower level), lava and slime kept opaque;
// --keep-nonsolid keeps them all. Sky faces (SURF_SKY) are kept as the level's ceiling, which
// seals it: no daylight comes in. --open-sky leaves them out, so the level opens onto the sky where a
// player sees it (the outside then floods the open arenas). The data stays outside the repo.
//   q3bsp_to_obj MAP.bsp OUT.obj [--scale METRES_PER_UNIT] [--keep-nonsolid] [--open-sky]
//   (default scale 0.03: a 56-unit player is 1.7 m)
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "q3bsp.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(
        stderr,
        "usage: q3bsp_to_obj MAP.bsp OUT.obj [--scale METRES_PER_UNIT] [--keep-nonsolid] [--open-sky]\n");
    return 1;
  }
  q3bsp::Options options;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--scale" && a + 1 < argc)
      options.scale = std::atof(argv[++a]);
    else if (arg == "--keep-nonsolid")
      options.keepNonsolid = true;
    else if (arg == "--open-sky")
      options.openSky = true;
    else {
      std::fprintf(stderr, "q3bsp_to_obj: unknown option %s\n", arg.c_str());
      return 1;
    }
  }
  std::ifstream in(argv[1], std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const q3bsp::Mesh mesh = q3bsp::convert(file, options);
  if (!mesh.error.empty()) {
    std::fprintf(stderr, "q3bsp_to_obj: %s: %s\n", argv[1], mesh.error.c_str());
    return 1;
  }
  std::ofstream out(argv[2]);
  out << "# " << argv[1] << " (IBSP v" << mesh.version << "), world model, " << options.scale
      << " m per unit, y up\no world\n";
  char line[128];
  for (const q3bsp::V3& p : mesh.points) {
    std::snprintf(line, sizeof(line), "v %.5f %.5f %.5f\n", p[0], p[1], p[2]);
    out << line;
  }
  for (const auto& t : mesh.triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  std::fprintf(
      stderr,
      "%s: %zu triangles (%zu nodraw, %zu non-solid see-through, %zu water and fog, %zu inside opaque "
      "liquid and %zu sky faces skipped)\n",
      argv[2], mesh.triangles.size(), mesh.skippedNodraw, mesh.skippedNonsolid, mesh.skippedLiquid,
      mesh.skippedInLiquid, mesh.skippedSky);
  return 0;
}
