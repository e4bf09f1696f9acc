// The world geometry of a Quake III BSP (version 46: OpenArena's maps) as triangles in metres, y up, for
// bench/q3bsp_to_obj.cpp (its header comment says what is kept and why). Header only, standard C++ alone:
// real_models.sh compiles the converter with the system's c++, and the tests include it as it is.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace q3bsp {

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

// The lumps read, by their index in the header.
enum LumpIndex {
  kTextures = 1,
  kPlanes = 2,
  kModels = 7,
  kBrushes = 8,
  kBrushSides = 9,
  kVertices = 10,
  kMeshverts = 11,
  kFaces = 13,
  kLumpCount = 17
};
// Surface flags and contents of a shader (q3map's surfaceflags.h).
enum : int32_t { kSurfSky = 0x4, kSurfNodraw = 0x80, kSurfNonsolid = 0x4000 };
enum : int32_t {
  kContentsSolid = 1,
  kContentsLava = 8,
  kContentsSlime = 16,
  kContentsWater = 32,
  kContentsFog = 64,
  kContentsTranslucent = 0x20000000  ///< `surfaceparm trans`: glass, grates; light and sight cross it
};

/// Light crosses water and fog in the game (a pool's floor is lit through its surface, a fog volume's
/// far side seen through it): a face whose shader holds water or fog and neither lava nor slime (lava's
/// shaders hold water and fog too) is no wall. Kept, hydronex's water surface sealed its lower level off
/// from the hall above as rooms without a door (issue 46).
inline bool seeThroughLiquid(const Texture& t) {
  return (t.contents & (kContentsWater | kContentsFog)) && !(t.contents & (kContentsLava | kContentsSlime));
}

struct Options {
  double scale = 0.03;        ///< metres per unit: a 56-unit player is 1.7 m
  bool keepNonsolid = false;  ///< keep the see-through faces (non-solid, water, fog)
  bool openSky = false;       ///< leave out the sky faces (and, in sealBrushes, the sky's brushes)
};

using V3 = std::array<double, 3>;

struct Mesh {
  std::string error;  ///< not empty: not a BSP this reads
  int32_t version = 0;
  std::vector<V3> points;
  std::vector<std::array<size_t, 3>> triangles;
  size_t skippedNodraw = 0, skippedNonsolid = 0, skippedLiquid = 0, skippedInLiquid = 0, skippedSky = 0;
  /// The shaders (textures lump) by index, and per triangle the index of its face's shader (−1: none).
  /// Triangles past the end of triangleShader have none either.
  std::vector<std::string> shaders;
  std::vector<int32_t> triangleShader;
};

/// The shader names of the textures lump, by index.
inline std::vector<std::string> shaderNames(const std::vector<Texture>& textures) {
  std::vector<std::string> names;
  for (const Texture& t : textures)
    names.emplace_back(t.name, std::find(t.name, t.name + sizeof(t.name), '\0'));
  return names;
}

namespace detail {

// The planes of a convex brush (outward normals): p is inside when no plane has it further out than `slack`.
using Hull = std::vector<Plane>;
inline bool inside(const Hull& hull, const double p[3], double slack) {
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

// The lump directory of an IBSP file; false when the file is too short for it or not an IBSP file.
inline bool lumpDirectory(const std::string& file, Lump (&lumps)[kLumpCount]) {
  if (file.size() < 8 + kLumpCount * 8 || file.compare(0, 4, "IBSP") != 0) return false;
  std::memcpy(lumps, file.data() + 8, sizeof(lumps));
  return true;
}

inline V3 lerp(const V3& a, const V3& b, double t) {
  return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// Opaque liquids' bodies (lava, slime) as convex hulls, from the world's brushes.
inline std::vector<Hull> opaqueLiquids(const Model& world, const std::vector<Brush>& brushes,
                                       const std::vector<BrushSide>& brushSides,
                                       const std::vector<Plane>& planes,
                                       const std::vector<Texture>& textures) {
  std::vector<Hull> liquids;
  for (int32_t b = world.brush; b < world.brush + world.nBrushes && b < int32_t(brushes.size()); ++b) {
    const Brush& br = brushes[size_t(b)];
    if (br.texture < 0 || size_t(br.texture) >= textures.size() ||
        !(textures[size_t(br.texture)].contents & (kContentsLava | kContentsSlime)))
      continue;
    Hull hull;
    for (int32_t k = br.side; k < br.side + br.nSides && k < int32_t(brushSides.size()); ++k)
      if (brushSides[size_t(k)].plane >= 0 && size_t(brushSides[size_t(k)].plane) < planes.size())
        hull.push_back(planes[size_t(brushSides[size_t(k)].plane)]);
    if (!hull.empty()) liquids.push_back(hull);
  }
  return liquids;
}

// A face lies in a liquid when all its points are inside (or on) the brush and a point just in front of
// its middle is inside too: it looks into the liquid.
inline bool looksIntoLiquid(const Face& f, const std::vector<Vertex>& vertices,
                            const std::vector<Hull>& liquids) {
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
      const double p[3] = {vertices[size_t(v)].pos[0], vertices[size_t(v)].pos[1],
                           vertices[size_t(v)].pos[2]};
      all = inside(hull, p, 0.5);
    }
    if (all) return true;
  }
  return false;
}

}  // namespace detail

/// The world model's faces of the BSP held in `file`, as triangles facing the way their faces do (into
/// the playable space), with what was left out counted.
inline Mesh convert(const std::string& file, const Options& options) {
  using namespace detail;
  Mesh mesh;
  Lump lumps[kLumpCount];
  if (!lumpDirectory(file, lumps)) {
    mesh.error = "not an IBSP file";
    return mesh;
  }
  std::memcpy(&mesh.version, file.data() + 4, 4);
  const auto textures = lump<Texture>(file, lumps[kTextures]);
  const auto models = lump<Model>(file, lumps[kModels]);
  const auto vertices = lump<Vertex>(file, lumps[kVertices]);
  const auto meshverts = lump<int32_t>(file, lumps[kMeshverts]);
  const auto faces = lump<Face>(file, lumps[kFaces]);
  const auto planes = lump<Plane>(file, lumps[kPlanes]);
  const auto brushes = lump<Brush>(file, lumps[kBrushes]);
  const auto brushSides = lump<BrushSide>(file, lumps[kBrushSides]);
  if (models.empty()) {
    mesh.error = "no world model";
    return mesh;
  }
  // Quake: z up, x/y horizontal. Ours: y up; (x, y, z) -> (x, z, -y) is a rotation, so winding survives.
  const double scale = options.scale;
  auto toWorld = [&](const V3& q) { return V3{q[0] * scale, q[2] * scale, -q[1] * scale}; };
  auto emit = [&](const V3& a, const V3& b, const V3& c, const V3& facing) {
    // Each triangle faces the same way as its face's normal (into the playable space).
    const bool flip = dot(cross(sub(b, a), sub(c, a)), facing) < 0.0;
    const size_t base = mesh.points.size();
    mesh.points.push_back(toWorld(a));
    mesh.points.push_back(toWorld(flip ? c : b));
    mesh.points.push_back(toWorld(flip ? b : c));
    mesh.triangles.push_back({base, base + 1, base + 2});
  };
  const Model& world = models[0];
  mesh.shaders = shaderNames(textures);
  // Opaque liquids (lava, slime): the faces seen only from inside one (a pit's walls and floor under the
  // surface, the surface's underside) are left out, as the compiler leaves out the faces towards the
  // void: no light reaches them, and kept they close the liquid's body off as a room without a door under
  // its surface (issue 46: oa_dm1's and oa_dm4's lava pits).
  const std::vector<Hull> liquids = opaqueLiquids(world, brushes, brushSides, planes, textures);
  for (int32_t fi = world.face; fi < world.face + world.nFaces && fi < int32_t(faces.size()); ++fi) {
    const Face& f = faces[size_t(fi)];
    const Texture* tex =
        f.texture >= 0 && size_t(f.texture) < textures.size() ? &textures[size_t(f.texture)] : nullptr;
    if (tex && (tex->flags & kSurfNodraw)) {
      ++mesh.skippedNodraw;
      continue;
    }
    if (!options.keepNonsolid && tex && (tex->flags & kSurfNonsolid) && !(tex->contents & kContentsSolid)) {
      ++mesh.skippedNonsolid;  // fog, beams, clear water
      continue;
    }
    if (!options.keepNonsolid && tex && seeThroughLiquid(*tex)) {
      ++mesh.skippedLiquid;
      continue;
    }
    if (looksIntoLiquid(f, vertices, liquids)) {
      ++mesh.skippedInLiquid;
      continue;
    }
    if (options.openSky && tex && (tex->flags & kSurfSky)) {
      ++mesh.skippedSky;  // where the level opens onto the sky, and daylight comes in
      continue;
    }
    auto pos = [&](int32_t v) {
      const Vertex& x = vertices[size_t(v)];
      return V3{x.pos[0], x.pos[1], x.pos[2]};
    };
    if (f.type == 1 || f.type == 3) {
      for (int32_t k = 0; k + 2 < f.nMeshverts; k += 3) {
        if (f.meshvert < 0 || size_t(f.meshvert + k + 2) >= meshverts.size()) break;
        const int32_t a = f.vertex + meshverts[size_t(f.meshvert + k)],
                      b = f.vertex + meshverts[size_t(f.meshvert + k + 1)],
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
      if (f.vertex < 0 || size_t(f.vertex) + size_t(std::max(w * h, 0)) > vertices.size()) continue;
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
            for (int j = 0; j < 3; ++j)
              row[j] = lerp(lerp(c[j][0], c[j][1], u), lerp(c[j][1], c[j][2], u), u);
            return lerp(lerp(row[0], row[1], v), lerp(row[1], row[2], v), v);
          };
          for (int j = 0; j < level; ++j)
            for (int i = 0; i < level; ++i) {
              const double u0 = double(i) / level, u1 = double(i + 1) / level, v0 = double(j) / level,
                           v1 = double(j + 1) / level;
              const V3 a = at(u0, v0), b = at(u1, v0), cc = at(u1, v1), d = at(u0, v1);
              // Facing by the control points' normals, per patch.
              emit(a, b, cc, n);
              emit(a, cc, d, n);
            }
        }
    }
    mesh.triangleShader.resize(mesh.triangles.size(), tex ? f.texture : -1);
  }
  return mesh;
}

/// The world's brushes that close the level, as their planes (outward normals, Quake units): every brush
/// whose sides' contents (OR-ed, as the compiler joins them) are opaque solid (solid and not `trans`) or an
/// opaque liquid (lava, slime). A compiled map is sealed by its brushes, not by its drawn faces: the top of a
/// wall under the sky box or the inside of a block no player sees has no face, and the faces alone let the
/// outside flood the playable space (issue 46: am_lavaarena, ctf_gate1, pul1duel-oa). Detail brushes are
/// kept too: their hidden sides would otherwise leave their insides open onto the wall behind them. A brush
/// with a sky side is kept only while the sky seals the level (not with Options::openSky). Water, fog,
/// clips and hints are no brush of the seal: light crosses them.
inline std::vector<std::vector<Plane>> sealBrushes(const std::string& file, const Options& options) {
  using namespace detail;
  std::vector<std::vector<Plane>> out;
  Lump lumps[kLumpCount];
  if (!lumpDirectory(file, lumps)) return out;
  const auto textures = lump<Texture>(file, lumps[kTextures]);
  const auto models = lump<Model>(file, lumps[kModels]);
  const auto planes = lump<Plane>(file, lumps[kPlanes]);
  const auto brushes = lump<Brush>(file, lumps[kBrushes]);
  const auto brushSides = lump<BrushSide>(file, lumps[kBrushSides]);
  if (models.empty()) return out;
  const Model& world = models[0];
  for (int32_t b = world.brush; b >= 0 && b < world.brush + world.nBrushes && b < int32_t(brushes.size());
       ++b) {
    const Brush& br = brushes[size_t(b)];
    int32_t contents = 0, flags = 0;
    std::vector<Plane> hull;
    for (int32_t k = br.side; k >= 0 && k < br.side + br.nSides && k < int32_t(brushSides.size()); ++k) {
      const BrushSide& side = brushSides[size_t(k)];
      if (side.texture >= 0 && size_t(side.texture) < textures.size())
        contents |= textures[size_t(side.texture)].contents, flags |= textures[size_t(side.texture)].flags;
      if (side.plane >= 0 && size_t(side.plane) < planes.size()) hull.push_back(planes[size_t(side.plane)]);
    }
    if (br.texture >= 0 && size_t(br.texture) < textures.size())
      contents |= textures[size_t(br.texture)].contents;
    const bool opaqueSolid = (contents & kContentsSolid) && !(contents & kContentsTranslucent);
    const bool opaqueLiquid = contents & (kContentsLava | kContentsSlime);
    if (!opaqueSolid && !opaqueLiquid) continue;
    if (options.openSky && (flags & kSurfSky)) continue;
    if (hull.size() >= 4) out.push_back(std::move(hull));
  }
  return out;
}

}  // namespace q3bsp
