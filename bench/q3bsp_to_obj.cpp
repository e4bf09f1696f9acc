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
// Each shader is its own material (OUT.mtl beside OUT.obj, named by the shader's path: bench/q3_materials.h),
// so that `cpgi bake --emit NAME=W` lights a closed level by its own light shaders. With --pk3 (an archive
// of the game's data, or a folder of them; repeatable, in the game's order) each material's Kd is its
// texture's mean colour, the light shaders (q3map_surfacelight) are named, and the --emit flags that
// light them are printed; without, every material is grey and no shader is known to be a light.
// The level's seal follows the drawn faces as the object `seal:brushes` (docs/scenes.md): the world's
// opaque brushes as closed solids, which the decomposition voxelizes and the bake neither draws nor lights.
// The drawn faces alone do not close a level (no face where no player looks: a wall's top under the sky
// box, a block's inside), and the outside flooded the playable space of sealed maps (issue 46). --no-seal
// leaves it out.
//   q3bsp_to_obj MAP.bsp OUT.obj [--scale METRES_PER_UNIT] [--keep-nonsolid] [--open-sky] [--pk3 PATH ...]
//     [--no-seal]
//   (default scale 0.03: a 56-unit player is 1.7 m; compile with -lgmp for CGAL)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include "q3_materials.h"
#include "q3bsp.h"
#include "q3bsp_seal.h"

namespace {

// The seal as its own OBJ object after `vertexCount` vertices already written.
std::string sealObject(const q3bsp::Solids& seal, size_t vertexCount) {
  std::string out = "o seal:brushes\n";
  char line[128];
  for (const q3bsp::V3& p : seal.points) {
    std::snprintf(line, sizeof(line), "v %.5f %.5f %.5f\n", p[0], p[1], p[2]);
    out += line;
  }
  for (const auto& t : seal.triangles)
    out += "f " + std::to_string(vertexCount + t[0] + 1) + " " + std::to_string(vertexCount + t[1] + 1) +
           " " + std::to_string(vertexCount + t[2] + 1) + "\n";
  return out;
}

// The vertices an OBJ text defines.
size_t vertexCount(const std::string& obj) {
  size_t n = obj.rfind("v ", 0) == 0 ? 1 : 0;
  for (size_t at = obj.find("\nv "); at != std::string::npos; at = obj.find("\nv ", at + 1)) ++n;
  return n;
}

// The archives a --pk3 names: the file, or every .pk3 in the folder in name order (pak0, pak1, ...).
std::vector<std::string> archivesAt(const std::string& path) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(path)) return {path};
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(path))
    if (e.path().extension() == ".pk3") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(
        stderr,
        "usage: q3bsp_to_obj MAP.bsp OUT.obj [--scale METRES_PER_UNIT] [--keep-nonsolid] [--open-sky] "
        "[--pk3 PATH ...] [--no-seal]\n");
    return 1;
  }
  q3bsp::Options options;
  std::vector<std::string> archives;
  bool seal = true;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--scale" && a + 1 < argc)
      options.scale = std::atof(argv[++a]);
    else if (arg == "--keep-nonsolid")
      options.keepNonsolid = true;
    else if (arg == "--open-sky")
      options.openSky = true;
    else if (arg == "--no-seal")
      seal = false;
    else if (arg == "--pk3" && a + 1 < argc)
      for (const std::string& p : archivesAt(argv[++a])) archives.push_back(p);
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
  std::unique_ptr<q3materials::GameData> data;
  if (!archives.empty()) {
    data = std::make_unique<q3materials::GameData>(archives);
    for (const std::string& p : data->unread)
      std::fprintf(stderr, "q3bsp_to_obj: %s: not a pk3, skipped\n", p.c_str());
  }
  const std::string obj = argv[2];
  const std::string mtl = obj.substr(0, obj.rfind('.')) + ".mtl";
  char header[512];
  std::snprintf(header, sizeof header, "%s (IBSP v%d), world model, %g m per unit, y up", argv[1],
                mesh.version, options.scale);
  const q3materials::Level level =
      q3materials::levelFiles(mesh, data.get(), header, std::filesystem::path(mtl).filename().string());
  std::ofstream(mtl) << level.mtl;
  const q3bsp::Solids solids =
      seal ? q3bsp::brushSolids(q3bsp::sealBrushes(file, options), options.scale) : q3bsp::Solids();
  std::ofstream(obj) << level.obj << (seal ? sealObject(solids, vertexCount(level.obj)) : std::string());
  const std::vector<q3materials::Material>& materials = level.materials;
  size_t found = 0;
  for (const q3materials::Material& m : materials) found += m.colourFound;
  std::fprintf(stderr, "%s: %zu materials (one per shader; %zu with their texture's colour, the rest grey)\n",
               mtl.c_str(), materials.size(), found);
  if (const std::string emit = q3materials::emitFlags(materials); !emit.empty())
    std::fprintf(stderr, "light shaders (q3map_surfacelight / 10 as W/m2): cpgi bake %s -o OUT %s\n",
                 obj.c_str(), emit.c_str());
  else if (data)
    std::fprintf(stderr, "no light shader found: light the level with --emit MATERIAL=W/m2 (names in %s)\n",
                 mtl.c_str());
  std::fprintf(
      stderr,
      "%s: %zu triangles (%zu nodraw, %zu non-solid see-through, %zu water and fog, %zu inside opaque "
      "liquid and %zu sky faces skipped)\n",
      argv[2], mesh.triangles.size(), mesh.skippedNodraw, mesh.skippedNonsolid, mesh.skippedLiquid,
      mesh.skippedInLiquid, mesh.skippedSky);
  if (seal)
    std::fprintf(stderr, "%s: seal: %zu brushes as %zu triangles (%zu without volume left out)\n", argv[2],
                 solids.brushes, solids.triangles.size(), solids.degenerate);
  return 0;
}
