// loadScene: dispatch by extension, then the checks every format shares and the cell graph.
#include "core/scene_io.h"
#include "core/units.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/lights.h"
#include "core/scene_files.h"
#include "core/scene_io_detail.h"

namespace fs = std::filesystem;

namespace cpgi {
namespace detail {

namespace {

bool startsWith(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

// Blender renames the second "portal:A:B" to "portal:A:B.001"; the suffix is not part of the cell name.
std::string stripBlenderSuffix(const std::string& name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos || dot + 4 != name.size() || dot == 0) return name;
  for (size_t i = dot + 1; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return name;
  return name.substr(0, dot);
}

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Far above any room's lamps (a 100 W bulb), far below float's 3.4e38 once the solver sums and scales.
constexpr double kMaxEmittedPower = 1e20;

// The farthest a position may lie from the origin once in metres. Float positions there are 6 cm apart
// (a room's walls already blur), Embree's ray checks fail past about 1e8 m, and the voxel grids and
// atlases sized from the bounds would ask for more than any machine has long before.
constexpr float kMaxCoordinate = 1e6f;

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Collinear within float precision: the doubled area is tiny against the longest edge squared.
bool isDegenerate(const Triangle& t) {
  const float twiceArea = glm::length(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
  float longest2 = 0.0f;
  for (int i = 0; i < 3; ++i) {
    const glm::vec3 e = t.p[(i + 1) % 3] - t.p[i];
    longest2 = std::max(longest2, glm::dot(e, e));
  }
  return longest2 == 0.0f || twiceArea <= 1e-7f * longest2;
}

// Same three positions in the same cyclic order (the opposite winding is a legitimate two-sided face).
using TriangleKey = std::array<float, 9>;
TriangleKey canonicalKey(const Triangle& t) {
  auto less = [](const glm::vec3& a, const glm::vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  int first = 0;
  for (int i = 1; i < 3; ++i)
    if (less(t.p[i], t.p[first])) first = i;
  TriangleKey key{};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) key[3 * i + c] = t.p[(first + i) % 3][c];
  return key;
}

std::string nodeOf(const Scene& scene, const Triangle& t) {
  return t.node < scene.nodePaths.size() ? scene.nodePaths[t.node] : std::string("?");
}

// Signed area-weighted mean distance of a cell's triangle centroids from the portal plane.
double meanSide(const Scene& scene, const Cell& cell, const glm::vec3& centre, const glm::vec3& normal) {
  double sum = 0.0, area = 0.0;
  for (uint32_t i : cell.triangles) {
    const Triangle& t = scene.triangles[i];
    const double a = t.area();
    sum += a * glm::dot(t.centroid() - centre, normal);
    area += a;
  }
  return area > 0.0 ? sum / area : 0.0;
}

void reverseCorners(PortalQuad& portal) {
  std::swap(portal.corners[1], portal.corners[3]);
}

}  // namespace

CellTag parseCellTag(const std::string& file, const std::string& name) {
  CellTag tag;
  auto requireName = [&](const std::string& cell) {
    if (cell.empty()) throw InputError(file, printable(name) + ": empty cell name");
    return cell;
  };
  if (startsWith(name, "cellvolume:")) {
    tag.kind = CellTag::Kind::CellVolume;
    tag.a =
        requireName(stripBlenderSuffix(name.substr(11)));  // a room of several volumes, as Blender names them
  } else if (startsWith(name, "seal:")) {
    tag.kind = CellTag::Kind::Seal;
    tag.a = name.substr(5);
  } else if (startsWith(name, "cell:")) {
    tag.kind = CellTag::Kind::Cell;
    tag.a = requireName(name.substr(5));
  } else if (startsWith(name, "portal:")) {
    tag.kind = CellTag::Kind::Portal;
    const std::string rest = name.substr(7);
    const size_t colon = rest.find(':');
    if (colon == std::string::npos || rest.find(':', colon + 1) != std::string::npos)
      throw InputError(file, printable(name) + ": a portal is named portal:CELL_A:CELL_B");
    tag.a = requireName(rest.substr(0, colon));
    tag.b = requireName(stripBlenderSuffix(rest.substr(colon + 1)));
  }
  return tag;
}

int RawScene::cellIndex(const std::string& name) {
  for (size_t i = 0; i < cellNames.size(); ++i)
    if (cellNames[i] == name) return static_cast<int>(i);
  cellNames.push_back(name);
  return static_cast<int>(cellNames.size() - 1);
}

uint32_t RawScene::nodeIndex(const std::string& path) {
  const auto [it, fresh] = nodeIndex_.emplace(path, static_cast<uint32_t>(scene.nodePaths.size()));
  if (fresh) scene.nodePaths.push_back(path);
  return it->second;
}

std::array<glm::vec3, 4> portalCorners(const std::string& file, const std::string& node,
                                       const std::vector<Triangle>& triangles) {
  std::vector<glm::vec3> unique;
  if (triangles.size() <= 16)  // enough to tell a user what they made; a huge mesh is just "not a quad"
    for (const Triangle& t : triangles)
      for (const glm::vec3& q : t.p)
        if (std::none_of(unique.begin(), unique.end(),
                         [&](const glm::vec3& u) { return glm::length(u - q) <= 1e-6f; }))
          unique.push_back(q);
  // Vertices are counted only for small meshes; a large one is said in triangles alone.
  auto notAQuad = [&] {
    return InputError(
        file,
        node + ": a portal must be one quad (2 triangles, 4 vertices), found " +
            std::to_string(triangles.size()) + " triangles" +
            (triangles.size() <= 16 ? " and " + std::to_string(unique.size()) + " vertices" : std::string()));
  };
  if (triangles.size() != 2 || unique.size() != 4) throw notAQuad();
  auto same = [](const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) <= 1e-6f; };
  auto inTriangle = [&](const Triangle& t, const glm::vec3& q) {
    return same(t.p[0], q) || same(t.p[1], q) || same(t.p[2], q);
  };
  // The diagonal is the edge both triangles share; walk the first triangle from its own vertex.
  const Triangle& t0 = triangles[0];
  const Triangle& t1 = triangles[1];
  int own0 = -1, shared = 0;
  for (int i = 0; i < 3; ++i) {
    if (inTriangle(t1, t0.p[i]))
      ++shared;
    else
      own0 = i;
  }
  glm::vec3 own1(0.0f);
  int own1Count = 0;
  for (const glm::vec3& q : t1.p)
    if (!inTriangle(t0, q)) own1 = q, ++own1Count;
  if (shared != 2 || own0 < 0 || own1Count != 1) throw notAQuad();
  return {t0.p[own0], t0.p[(own0 + 1) % 3], own1, t0.p[(own0 + 2) % 3]};
}

// --emit and --albedo, by material name, before the checks (an override is checked like the file's own).
void applyOverrides(const std::string& path, Scene& scene, const std::vector<MaterialOverride>& overrides) {
  for (const MaterialOverride& o : overrides) {
    bool found = false;
    for (size_t k = 0; k < scene.materials.size(); ++k) {
      Material& m = scene.materials[k];
      if (m.name != o.material) continue;
      found = true;
      if (o.emission) m.emission = *o.emission;
      if (o.albedo) m.albedo = *o.albedo;
      if (o.albedo && k < scene.looks.materials.size()) {  // the engine's base colour is the one baked with
        MaterialLook& look = scene.looks.materials[k];
        look.baseColorFactor = glm::vec4(*o.albedo, look.baseColorFactor.a);
        look.baseColorTexture = -1;
      }
    }
    if (found) continue;
    std::string names;
    for (size_t i = 0; i < scene.materials.size() && i < 12; ++i)
      names += (i ? ", " : "") + printable(scene.materials[i].name, 40);
    if (scene.materials.size() > 12) names += ", ...";
    throw InputError(o.emission ? "emit" : "albedo", "no material named '" + printable(o.material) + "' in " +
                                                         printable(path, 200) + " (it has: " + names + ")");
  }
}

// One rule for every format (README, "Numbers"): an albedo outside [0, 1] or a non-finite emission is
// refused, not clamped: either means a broken export, and the solver would run away (albedo 2 never
// converges) or overflow (float power → inf report energies, NaN lightmap). Lights count in the power:
// a point or spot light by what it emits, a directional one by what would cross the scene's bounds.
void checkMaterials(const std::string& path, const Scene& scene) {
  auto text = [](const glm::vec3& v) {
    std::ostringstream s;
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
  };
  for (const Material& m : scene.materials) {
    for (int i = 0; i < 3; ++i) {
      if (!(m.albedo[i] >= 0.0f && m.albedo[i] <= 1.0f))
        throw InputError(
            path, "material '" + printable(m.name) + "': albedo " + text(m.albedo) + " is not within [0, 1]");
      if (!(m.emission[i] >= 0.0f) || !std::isfinite(m.emission[i]))
        throw InputError(path, "material '" + printable(m.name) + "': emission " + text(m.emission) +
                                   " is negative or not finite");
    }
  }
  glm::dvec3 power(0.0);
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    // Finite corners far apart (±3e38) give an infinite area: every area, form factor and power after it
    // would be inf or NaN (it read "the scene emits -nan W").
    if (!std::isfinite(t.area()))
      throw InputError(path,
                       "triangle " + std::to_string(i) +
                           " is too large for float arithmetic (its area overflows; corners near 1e38)");
    if (t.material < scene.materials.size())
      power += glm::dvec3(scene.materials[t.material].emission) * double(t.area());
  }
  const glm::dvec3 size(scene.bounds().size());
  for (const PunctualLight& l : scene.lights)
    power += l.kind == PunctualLight::Kind::Directional ? glm::dvec3(l.intensity) * glm::dot(size, size)
                                                        : punctualPower(l);
  if (!(std::max({power.x, power.y, power.z}) <= kMaxEmittedPower)) {
    std::ostringstream s;
    s << "the scene emits " << std::max({power.x, power.y, power.z}) << " W, more than " << kMaxEmittedPower
      << " W (emission x area would overflow the solver's float arithmetic)";
    throw InputError(path, s.str());
  }
}

// Degenerate and duplicate triangles: dropped with one warning naming how many and the first one's node
// (real exports have a few slivers), or refused with `strict`. Returns a mark per triangle to drop.
// Edges of a volume mesh not shared by exactly two of its triangles (positions to 0.1 mm): 0 for a
// closed mesh, whose inside the parity of crossings decides.
size_t closedVolumeEdges(const std::vector<Triangle>& mesh) {
  using Key = std::array<int64_t, 3>;
  std::map<std::pair<Key, Key>, int> uses;
  auto key = [](const glm::vec3& p) {
    return Key{int64_t(std::llround(p.x * 1e4)), int64_t(std::llround(p.y * 1e4)),
               int64_t(std::llround(p.z * 1e4))};
  };
  for (const Triangle& t : mesh)
    for (int k = 0; k < 3; ++k) {
      Key a = key(t.p[k]), b = key(t.p[(k + 1) % 3]);
      if (b < a) std::swap(a, b);
      ++uses[{a, b}];
    }
  size_t open = 0;
  for (const auto& [edge, n] : uses) open += n != 2;
  return open;
}

std::vector<char> dropDegenerate(const std::string& path, const Scene& scene, const LoadOptions& options,
                                 std::vector<std::string>& warnings) {
  std::vector<char> drop(scene.triangles.size(), 0);
  size_t degenerate = 0, duplicate = 0;
  size_t first = scene.triangles.size();
  for (size_t i = 0; i < scene.triangles.size(); ++i)
    if (isDegenerate(scene.triangles[i])) {
      drop[i] = 1, ++degenerate;
      first = std::min(first, i);
    }
  std::vector<std::pair<TriangleKey, uint32_t>> keys;
  keys.reserve(scene.triangles.size());
  for (uint32_t i = 0; i < scene.triangles.size(); ++i)
    if (!drop[i]) keys.emplace_back(canonicalKey(scene.triangles[i]), i);
  std::sort(keys.begin(), keys.end());
  for (size_t k = 1; k < keys.size(); ++k)
    if (keys[k].first == keys[k - 1].first) {
      drop[keys[k].second] = 1, ++duplicate;
      first = std::min<size_t>(first, keys[k].second);
    }
  if (degenerate + duplicate == 0) return drop;
  auto count = [](size_t n, const char* what) {
    return std::to_string(n) + " " + what + " triangle" + (n > 1 ? "s" : "");
  };
  std::string what = degenerate ? count(degenerate, "zero-area") : "";
  if (duplicate) what += (degenerate ? " and " : "") + count(duplicate, "duplicate");
  what += " (first in node '" + nodeOf(scene, scene.triangles[first]) + "')";
  if (options.strict) throw InputError(path, what + "; without `strict` they are dropped");
  warnings.push_back("dropped " + what + "; --strict refuses them");
  return drop;
}

// LoadOptions::scale: the file's units to metres.
static void scaleRaw(RawScene& raw, float scale) {
  for (Triangle& t : raw.scene.triangles)
    for (glm::vec3& q : t.p) q *= scale;
  for (auto* meshes : {&raw.portals, &raw.volumes, &raw.seals})
    for (RawScene::TaggedMesh& m : *meshes)
      for (Triangle& t : m.triangles)
        for (glm::vec3& q : t.p) q *= scale;
  for (Camera& c : raw.scene.cameras) c.position *= scale;
  for (PunctualLight& l : raw.scene.lights) l.position *= scale, l.range *= scale;
}

static bool beyondBound(const glm::vec3& p) {
  return std::abs(p.x) > kMaxCoordinate || std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate;
}

// Every position against kMaxCoordinate, after --scale; one line naming the node.
static void checkCoordinates(const std::string& path, const RawScene& raw, double scale) {
  const std::string bound = " m from the origin, beyond the 1e6 m cpgi handles";
  const std::string hint =
      scale != 1.0 ? " (after --scale " + std::to_string(scale) + ")" : " (is --scale right?)";
  auto far = [](const glm::vec3& p) {
    std::ostringstream s;
    s << std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return s.str();
  };
  for (const Triangle& t : raw.scene.triangles)
    for (const glm::vec3& q : t.p)
      if (beyondBound(q))
        throw InputError(path, "node '" + nodeOf(raw.scene, t) + "': a vertex lies " + far(q) + bound + hint);
  for (const auto* meshes : {&raw.portals, &raw.volumes, &raw.seals})
    for (const RawScene::TaggedMesh& m : *meshes)
      for (const Triangle& t : m.triangles)
        for (const glm::vec3& q : t.p)
          if (beyondBound(q)) throw InputError(path, m.node + ": a vertex lies " + far(q) + bound + hint);
  for (const Camera& c : raw.scene.cameras)
    if (beyondBound(c.position))
      throw InputError(path, "camera '" + c.name + "' lies " + far(c.position) + bound + hint);
  for (const PunctualLight& l : raw.scene.lights)
    if (l.kind != PunctualLight::Kind::Directional && beyondBound(l.position))
      throw InputError(path, "light '" + l.name + "' lies " + far(l.position) + bound + hint);
}

// The file's texture coordinates of raw triangle `i` (placed as `t`, scaled) as maps over its plane.
static uint32_t keepSurfaceUV(RawScene& raw, size_t i, const Triangle& t) {
  SurfaceUV uv;
  if (raw.uvSets[i] & 1) uv.fit(t.p, raw.textureUVs[i], 0);
  if (raw.uvSets[i] & 2) uv.fit(t.p, raw.lightmapUVs[i], 1);
  raw.scene.looks.uvs.push_back(uv);
  return uint32_t(raw.scene.looks.uvs.size() - 1);
}

void requireReadingTime(const std::string& path, const LoadOptions& options, const std::string& step) {
  if (std::chrono::steady_clock::now() < options.deadline) return;
  throw InputError("time limit",
                   "came while " + path + " was read (" + step + "), before any light was solved; raise it");
}

LoadedScene finishScene(const std::string& path, RawScene raw, const LoadOptions& options) {
  requireReadingTime(path, options, "its triangles read, not yet checked");
  LoadedScene out;
  out.warnings = std::move(raw.warnings);
  Scene& scene = raw.scene;

  for (const Triangle& t : scene.triangles)
    for (const glm::vec3& q : t.p)
      if (!isFinite(q))
        throw InputError(path,
                         "node '" + nodeOf(scene, t) + "': a vertex position is not finite (NaN or inf)");
  for (const auto* meshes : {&raw.portals, &raw.volumes, &raw.seals})
    for (const RawScene::TaggedMesh& m : *meshes)
      for (const Triangle& t : m.triangles)
        for (const glm::vec3& q : t.p)
          if (!isFinite(q)) throw InputError(path, m.node + ": a vertex position is not finite (NaN or inf)");
  if (options.scale != 1.0) scaleRaw(raw, float(options.scale));
  checkCoordinates(path, raw, options.scale);
  applyOverrides(path, scene, options.overrides);
  checkMaterials(path, scene);
  const std::vector<char> drop = dropDegenerate(path, scene, options, out.warnings);
  const bool dropped = std::find(drop.begin(), drop.end(), 1) != drop.end();

  std::vector<int> cellOf;
  cellOf.reserve(scene.triangles.size());
  const bool lightmapUVs = raw.everyLightmapUV && raw.lightmapUVs.size() == scene.triangles.size();
  {
    std::vector<Triangle> kept;
    kept.reserve(scene.triangles.size());
    for (size_t i = 0; i < scene.triangles.size(); ++i)
      if (!drop[i]) {
        kept.push_back(scene.triangles[i]), cellOf.push_back(raw.cellOfTriangle[i]);
        if (lightmapUVs) out.lightmapUVs.push_back(raw.lightmapUVs[i]);
        if (i < raw.uvSets.size() && raw.uvSets[i]) kept.back().uv = keepSurfaceUV(raw, i, kept.back());
      }
    scene.triangles = std::move(kept);
  }
  for (const RawScene::TaggedMesh& m : raw.seals)
    for (const Triangle& t : m.triangles)
      if (!isDegenerate(t)) scene.seal.push_back(t);
  if (scene.triangles.empty())
    throw InputError(path, dropped ? "no triangles left once the degenerate ones are dropped"
                                   : "the scene has no triangles");
  for (Triangle& t : scene.triangles)
    for (glm::vec3& n : t.n) {
      const float len = glm::length(n);
      n = std::isfinite(len) && len > 0.0f ? n / len : t.geometricNormal();
    }

  // The cell graph.
  CellGraph& graph = out.cells;
  for (const std::string& name : raw.cellNames) graph.cells.push_back(Cell{name, {}, {}});
  for (uint32_t i = 0; i < cellOf.size(); ++i)
    if (cellOf[i] >= 0) graph.cells[cellOf[i]].triangles.push_back(i);
  // Rooms given only as volumes (no cell: or portal: node, as an IFC export's IfcSpace rooms): each
  // cellvolume: defines its cell; decomp::decomposeFromVolumes gives them their surfaces and portals.
  const bool volumesOnly = graph.cells.empty() && raw.portals.empty() && !raw.volumes.empty();
  for (RawScene::TaggedMesh& v : raw.volumes) {
    int c = graph.findCell(v.tag.a);
    if (c < 0 && volumesOnly) graph.cells.push_back(Cell{v.tag.a, {}, {}}), c = int(graph.cells.size()) - 1;
    if (c < 0)
      throw InputError(path, v.node +
                                 ": names a cell that does not exist (volumes define cells only in a "
                                 "scene without cell: and portal: nodes)");
    auto& volume = graph.cells[c].volume;
    volume.insert(volume.end(), v.triangles.begin(), v.triangles.end());
  }
  for (const RawScene::TaggedMesh& m : raw.portals) {
    PortalQuad portal;
    portal.name = m.node;
    portal.corners = portalCorners(path, m.node, m.triangles);
    portal.cellA = graph.findCell(m.tag.a);
    portal.cellB = graph.findCell(m.tag.b);
    computePortalFrame(portal);
    // Orient from A into B by where the cells' surfaces lie; the winding decides only when the
    // geometry cannot (empty cells, or cells symmetric about the portal plane).
    if (portal.cellA >= 0 && portal.cellB >= 0 && portal.cellA != portal.cellB) {
      const glm::vec3 c = portal.centre();
      const double score = meanSide(scene, graph.cells[portal.cellB], c, portal.normal) -
                           meanSide(scene, graph.cells[portal.cellA], c, portal.normal);
      if (score < -1e-6) reverseCorners(portal), computePortalFrame(portal);
    }
    graph.portals.push_back(portal);
  }
  if (volumesOnly) {
    for (const Cell& c : graph.cells)
      if (closedVolumeEdges(c.volume) != 0)
        out.warnings.push_back("cellvolume:" + c.name + ": is not a closed mesh (" +
                               std::to_string(closedVolumeEdges(c.volume)) +
                               " edges not shared by two of its triangles); its inside may be wrong");
  } else if (!graph.cells.empty() || !graph.portals.empty()) {
    const CellValidation v = validateCells(scene, graph);
    if (!v.errors.empty()) {
      std::string message = v.errors.front();
      if (v.errors.size() > 1) message += " (and " + std::to_string(v.errors.size() - 1) + " more problems)";
      throw InputError(path, message);
    }
    out.warnings.insert(out.warnings.end(), v.warnings.begin(), v.warnings.end());
  }
  if (options.cutContacts && out.lightmapUVs.empty()) out.contactCuts = cutAtContacts(scene, graph);
  out.scene = std::move(scene);
  if (const UnitsCheck units = checkUnits(out.scene); !units.warning.empty())
    out.warnings.push_back(units.warning);
  // Warnings quote node and material names: kept to one line of sane length, like errors.
  for (std::string& w : out.warnings) w = printable(w, 2000);
  return out;
}

}  // namespace detail

LoadedScene loadScene(const std::string& path, const LoadOptions& options) {
  const std::string ext = detail::lowerExtension(path);
  if (ext != ".glb" && ext != ".gltf" && ext != ".obj") {
    detail::readSceneFile(path, options.maxFileBytes);  // a missing file is the clearer message
    throw InputError(path, "unknown scene format '" + printable(ext) + "' (expected .glb, .gltf or .obj)");
  }
  detail::RawScene raw = ext == ".obj" ? detail::readObj(path, options) : detail::readGltf(path, options);
  return detail::finishScene(path, std::move(raw), options);
}

}  // namespace cpgi
