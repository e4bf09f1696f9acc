// Converts the world geometry of a Quake III BSP (version 46: OpenArena's maps, as in Debian's
// openarena-data) to OBJ in metres, y up, for running the decomposition on real levels the project did
// not make. Polygon and mesh faces are triangle lists; Bézier patches are tessellated; billboards and
// brush models other than the world (doors, platforms) are left out, and so are the see-through
// surfaces a player walks through (texture flagged SURF_NONSOLID, contents not CONTENTS_SOLID: fog
// volumes' faces, light beams, clear water's surface), which are no walls: on oa_dm7 a pool's surface
// and a fog layer sealed the whole lower level and the open arena off as rooms without a door
// (issue 46); --keep-nonsolid keeps them. Sky faces (SURF_SKY) are kept as the level's ceiling, which
// seals it: no daylight comes in. --open-sky leaves them out, so the level opens onto the sky where a
// player sees it (the outside then floods the open arenas). The data stays outside the repo.
//   q3bsp_to_obj MAP.bsp OUT.obj [--scale METRES_PER_UNIT] [--keep-nonsolid] [--open-sky]
//   (default scale 0.03: a 56-unit player is 1.7 m)
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace {

struct Lump {
  int32_t offset, length;
};
struct Vertex {
  float pos[3], tex[2][2], normal[3];
  uint8_t colour[4];
};
struct Face {
  int32_t texture, effect, type, vertex, nVertices, meshvert, nMeshverts, lmIndex, lmStart[2], lmSize[2];
  float lmOrigin[3], lmVecs[2][3], normal[3];
  int32_t size[2];
};
struct Model {
  float mins[3], maxs[3];
  int32_t face, nFaces, brush, nBrushes;
};
struct Texture {
  char name[64];
  int32_t flags, contents;
};
struct Plane {
  float normal[3], dist;
};
struct Brush {
  int32_t side, nSides, texture;
};
struct BrushSide {
  int32_t plane, texture;
};
static_assert(sizeof(Vertex) == 44 && sizeof(Face) == 104 && sizeof(Model) == 40 && sizeof(Texture) == 72);
static_assert(sizeof(Plane) == 16 && sizeof(Brush) == 12 && sizeof(BrushSide) == 8);

// The planes of a convex brush (outward normals): p is inside when no plane has it further out than `slack`.
using Hull = std::vector<Plane>;
bool inside(const Hull& hull, const double p[3], double slack) {
  for (const Plane& q : hull)
    if (q.normal[0] * p[0] + q.normal[1] * p[1] + q.normal[2] * p[2] - q.dist > slack) return false;
  return true;
}

template <typename T>
std::vector<T> lump(const std::string& file, const Lump& l) {
  if (l.offset < 0 || l.length < 0 || size_t(l.offset) + size_t(l.length) > file.size()) return {};
  std::vector<T> out(size_t(l.length) / sizeof(T));
  std::memcpy(out.data(), file.data() + l.offset, out.size() * sizeof(T));
  return out;
}

using V3 = std::array<double, 3>;
V3 lerp(const V3& a, const V3& b, double t) { return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t}; }
V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: q3bsp_to_obj MAP.bsp OUT.obj [--scale METRES_PER_UNIT] [--keep-nonsolid] [--open-sky]\n");
    return 1;
  }
  double scale = 0.03;
  bool keepNonsolid = false, openSky = false;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--scale" && a + 1 < argc) scale = std::atof(argv[++a]);
    else if (arg == "--keep-nonsolid") keepNonsolid = true;
    else if (arg == "--open-sky") openSky = true;
    else {
      std::fprintf(stderr, "q3bsp_to_obj: unknown option %s\n", arg.c_str());
      return 1;
    }
  }
  std::ifstream in(argv[1], std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (file.size() < 8 + 17 * 8 || file.compare(0, 4, "IBSP") != 0) {
    std::fprintf(stderr, "q3bsp_to_obj: %s: not an IBSP file\n", argv[1]);
    return 1;
  }
  int32_t version;
  std::memcpy(&version, file.data() + 4, 4);
  Lump lumps[17];
  std::memcpy(lumps, file.data() + 8, sizeof(lumps));
  const auto textures = lump<Texture>(file, lumps[1]);
  const auto models = lump<Model>(file, lumps[7]);
  const auto vertices = lump<Vertex>(file, lumps[10]);
  const auto meshverts = lump<int32_t>(file, lumps[11]);
  const auto faces = lump<Face>(file, lumps[13]);
  const auto planes = lump<Plane>(file, lumps[2]);
  const auto brushes = lump<Brush>(file, lumps[8]);
  const auto brushSides = lump<BrushSide>(file, lumps[9]);
  if (models.empty()) {
    std::fprintf(stderr, "q3bsp_to_obj: %s: no world model\n", argv[1]);
    return 1;
  }
  // Quake: z up, x/y horizontal. Ours: y up; (x, y, z) -> (x, z, -y) is a rotation, so winding survives.
  auto toWorld = [&](const V3& q) { return V3{q[0] * scale, q[2] * scale, -q[1] * scale}; };
  std::vector<V3> points;
  std::vector<std::array<size_t, 3>> tris;
  size_t skippedNodraw = 0, skippedNonsolid = 0, skippedSky = 0;
  auto emit = [&](const V3& a, const V3& b, const V3& c, const V3& facing) {
    // Each triangle faces the same way as its face's normal (into the playable space).
    const bool flip = dot(cross(sub(b, a), sub(c, a)), facing) < 0.0;
    const size_t base = points.size();
    points.push_back(toWorld(a));
    points.push_back(toWorld(flip ? c : b));
    points.push_back(toWorld(flip ? b : c));
    tris.push_back({base, base + 1, base + 2});
  };
  const Model& world = models[0];
  // Opaque liquids (lava, slime: CONTENTS_LAVA | CONTENTS_SLIME): the faces seen only from inside one
  // (a pit's walls and floor under the surface, the surface's underside) are left out, as the compiler
  // leaves out the faces towards the void: no light reaches them, and kept they close the liquid's body
  // off as a room without a door under its surface (issue 46: oa_dm1's and oa_dm4's lava pits).
  std::vector<Hull> liquids;
  for (int32_t b = world.brush; b < world.brush + world.nBrushes && b < int32_t(brushes.size()); ++b) {
    const Brush& br = brushes[size_t(b)];
    if (br.texture < 0 || size_t(br.texture) >= textures.size() || !(textures[size_t(br.texture)].contents & (8 | 16)))
      continue;
    Hull hull;
    for (int32_t k = br.side; k < br.side + br.nSides && k < int32_t(brushSides.size()); ++k)
      if (brushSides[size_t(k)].plane >= 0 && size_t(brushSides[size_t(k)].plane) < planes.size())
        hull.push_back(planes[size_t(brushSides[size_t(k)].plane)]);
    if (!hull.empty()) liquids.push_back(hull);
  }
  size_t skippedInLiquid = 0;
  // A face lies in a liquid when all its points are inside (or on) the brush and a point just in front of
  // its middle is inside too: it looks into the liquid.
  auto looksIntoLiquid = [&](const Face& f) {
    if (f.nVertices <= 0 || f.vertex < 0 || size_t(f.vertex + f.nVertices) > vertices.size()) return false;
    double mid[3] = {0, 0, 0};
    for (int32_t v = f.vertex; v < f.vertex + f.nVertices; ++v)
      for (int k = 0; k < 3; ++k) mid[k] += vertices[size_t(v)].pos[k] / f.nVertices;
    V3 n{f.normal[0], f.normal[1], f.normal[2]};
    if (f.type != 1 || dot(n, n) < 0.5) return false;  // planar faces only
    const double ahead[3] = {mid[0] + 2.0 * n[0], mid[1] + 2.0 * n[1], mid[2] + 2.0 * n[2]};
    for (const Hull& hull : liquids) {
      bool all = inside(hull, ahead, 0.0);
      for (int32_t v = f.vertex; all && v < f.vertex + f.nVertices; ++v) {
        const double p[3] = {vertices[size_t(v)].pos[0], vertices[size_t(v)].pos[1], vertices[size_t(v)].pos[2]};
        all = inside(hull, p, 0.5);
      }
      if (all) return true;
    }
    return false;
  };
  for (int32_t fi = world.face; fi < world.face + world.nFaces && fi < int32_t(faces.size()); ++fi) {
    const Face& f = faces[size_t(fi)];
    if (f.texture >= 0 && size_t(f.texture) < textures.size() && (textures[size_t(f.texture)].flags & 0x80)) {
      ++skippedNodraw;  // SURF_NODRAW
      continue;
    }
    if (!keepNonsolid && f.texture >= 0 && size_t(f.texture) < textures.size() &&
        (textures[size_t(f.texture)].flags & 0x4000) && !(textures[size_t(f.texture)].contents & 1)) {
      ++skippedNonsolid;  // SURF_NONSOLID and not CONTENTS_SOLID: fog, beams, clear water
      continue;
    }
    if (looksIntoLiquid(f)) {
      ++skippedInLiquid;
      continue;
    }
    if (openSky && f.texture >= 0 && size_t(f.texture) < textures.size() &&
        (textures[size_t(f.texture)].flags & 0x4)) {
      ++skippedSky;  // SURF_SKY: where the level opens onto the sky, and daylight comes in
      continue;
    }
    auto pos = [&](int32_t v) {
      const Vertex& x = vertices[size_t(v)];
      return V3{x.pos[0], x.pos[1], x.pos[2]};
    };
    if (f.type == 1 || f.type == 3) {
      for (int32_t k = 0; k + 2 < f.nMeshverts; k += 3) {
        const int32_t a = f.vertex + meshverts[size_t(f.meshvert + k)], b = f.vertex + meshverts[size_t(f.meshvert + k + 1)],
                      c = f.vertex + meshverts[size_t(f.meshvert + k + 2)];
        if (a < 0 || b < 0 || c < 0 || size_t(std::max(a, std::max(b, c))) >= vertices.size()) continue;
        V3 facing{f.normal[0], f.normal[1], f.normal[2]};
        if (f.type == 3 || dot(facing, facing) < 0.5) {  // meshes: the vertices' normals
          const Vertex& x = vertices[size_t(a)];
          facing = {x.normal[0], x.normal[1], x.normal[2]};
        }
        emit(pos(a), pos(b), pos(c), facing);
      }
    } else if (f.type == 2) {
      // Biquadratic Bézier patches over a (size[0] × size[1]) control grid, 3 × 3 points each.
      const int w = f.size[0], h = f.size[1], level = 6;
      for (int py = 0; py + 2 < h; py += 2)
        for (int px = 0; px + 2 < w; px += 2) {
          V3 c[3][3];
          V3 n{0, 0, 0};
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
              const int32_t v = f.vertex + (py + j) * w + (px + i);
              c[j][i] = pos(v);
              const Vertex& x = vertices[size_t(v)];
              n = {n[0] + x.normal[0], n[1] + x.normal[1], n[2] + x.normal[2]};
            }
          auto at = [&](double u, double v) {
            V3 row[3];
            for (int j = 0; j < 3; ++j) row[j] = lerp(lerp(c[j][0], c[j][1], u), lerp(c[j][1], c[j][2], u), u);
            return lerp(lerp(row[0], row[1], v), lerp(row[1], row[2], v), v);
          };
          for (int j = 0; j < level; ++j)
            for (int i = 0; i < level; ++i) {
              const double u0 = double(i) / level, u1 = double(i + 1) / level, v0 = double(j) / level, v1 = double(j + 1) / level;
              const V3 a = at(u0, v0), b = at(u1, v0), cc = at(u1, v1), d = at(u0, v1);
              // Facing by the control points' normals, per patch.
              emit(a, b, cc, n);
              emit(a, cc, d, n);
            }
        }
    }
  }
  std::ofstream out(argv[2]);
  out << "# " << argv[1] << " (IBSP v" << version << "), world model, " << scale << " m per unit, y up\no world\n";
  char line[128];
  for (const V3& p : points) {
    std::snprintf(line, sizeof(line), "v %.5f %.5f %.5f\n", p[0], p[1], p[2]);
    out << line;
  }
  for (const auto& t : tris) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  std::fprintf(stderr,
               "%s: %zu triangles (%zu nodraw, %zu non-solid see-through, %zu inside opaque liquid and %zu sky "
               "faces skipped)\n",
               argv[2], tris.size(), skippedNodraw, skippedNonsolid, skippedInLiquid, skippedSky);
  return 0;
}
