// Wavefront OBJ + MTL → RawScene via tinyobjloader: Kd is the albedo, Ke the emission (W/m²); objects
// and groups named `cell:NAME`, `portal:A:B`, `cellvolume:NAME`, `seal:NAME` follow the glTF convention.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include <tiny_obj_loader.h>

#include "core/error.h"
#include "core/scene_files.h"
#include "core/scene_io_detail.h"

namespace cpgi::detail {

namespace {

// tinyobjloader reads "v abc", "Kd inf", "Kd nan" and "Kd 0.5" (for 0.5 0 0) as numbers without a word,
// so the lines whose numbers cpgi uses are checked first: each number finite as a float, and as many as
// the keyword takes.
struct NumberedKeyword {
  std::string_view name;
  int minCount, maxCount;
};
const std::vector<NumberedKeyword> kObjNumbers = {{"v", 3, 7}, {"vn", 3, 3}};
const std::vector<NumberedKeyword> kMtlNumbers = {{"Kd", 3, 3}, {"Ke", 3, 3}};

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Calls visit(line, its number from 1) for each line of text, without its '\n'.
template <typename Visit>
void forEachLine(std::string_view text, Visit visit) {
  size_t lineNumber = 0;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    visit(text.substr(start, end - start), ++lineNumber);
    start = end + 1;
  }
}

// Throws InputError(where, "<file> line N: ...") for the first bad line.
void checkNumbers(const std::string& where, const std::string& file, std::string_view text,
                  const std::vector<NumberedKeyword>& keywords) {
  forEachLine(text, [&](std::string_view line, size_t lineNumber) {
    size_t at = 0;
    auto nextToken = [&]() -> std::string_view {
      while (at < line.size() && isBlank(line[at])) ++at;
      const size_t from = at;
      while (at < line.size() && !isBlank(line[at])) ++at;
      return line.substr(from, at - from);
    };
    const std::string_view keyword = nextToken();
    const auto rule = std::find_if(keywords.begin(), keywords.end(),
                                   [&](const NumberedKeyword& k) { return k.name == keyword; });
    if (rule == keywords.end()) return;
    auto bad = [&](const std::string& problem) {
      return InputError(where, file + "line " + std::to_string(lineNumber) + " '" +
                                   printable(std::string(line), 60) + "': " + problem);
    };
    int count = 0;
    for (std::string_view token = nextToken(); !token.empty() && token[0] != '#'; token = nextToken()) {
      if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
      float value = 0.0f;
      const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value))
        throw bad("'" + printable(std::string(token), 40) + "' is not a finite number");
      ++count;
    }
    if (count < rule->minCount || count > rule->maxCount)
      throw bad(std::string(rule->name) + " takes " + std::to_string(rule->minCount) +
                (rule->maxCount > rule->minCount ? " to " + std::to_string(rule->maxCount) : std::string()) +
                " numbers, found " + std::to_string(count));
  });
}

// tinyobjloader's triangulation of a polygon grows with the square of its vertices (a 100,000-vertex face
// took 27 CPU-s, 16,384 about 0.5 s): faces are refused once the sum of their squared vertex counts passes
// that of one 16,384-vertex face, naming the largest.
void checkFaceSizes(const std::string& path, std::string_view text) {
  constexpr double kMaxSquares = 16384.0 * 16384.0;
  double squares = 0.0;
  size_t largest = 0, largestLine = 0;
  forEachLine(text, [&](std::string_view line, size_t lineNumber) {
    size_t at = 0;
    while (at < line.size() && isBlank(line[at])) ++at;
    if (at + 1 >= line.size() || line[at] != 'f' || !isBlank(line[at + 1])) return;
    size_t vertices = 0;
    for (++at; at < line.size() && line[at] != '#';) {
      while (at < line.size() && isBlank(line[at])) ++at;
      if (at >= line.size() || line[at] == '#') break;
      ++vertices;
      while (at < line.size() && !isBlank(line[at])) ++at;
    }
    squares += double(vertices) * double(vertices);
    if (vertices > largest) largest = vertices, largestLine = lineNumber;
    if (squares > kMaxSquares)
      throw InputError(path, "line " + std::to_string(largestLine) + ": a face of " +
                                 std::to_string(largest) +
                                 " vertices; faces this large (the sum of their squared vertex counts past " +
                                 "16384^2) take minutes to triangulate: triangulate them before export");
  });
}

// tinyobjloader's own reader opens any path an mtllib line names; this one goes through the scene's
// reference policy (scene_files.h).
class PolicyMaterialReader : public tinyobj::MaterialReader {
 public:
  explicit PolicyMaterialReader(ReferencePolicy& policy) : policy_(policy) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* byName, std::string* warn, std::string* err) override {
    const std::optional<std::string> bytes = readReferencedFile(policy_, name);
    if (!bytes) {
      if (warn) *warn += "Material file '" + printable(name) + "' not found\n";
      return false;
    }
    checkNumbers(policy_.sceneFile, "material file '" + printable(name) + "' ", *bytes, kMtlNumbers);
    std::istringstream in(*bytes);
    tinyobj::LoadMtl(byName, materials, &in, warn, err);
    return true;
  }

 private:
  ReferencePolicy& policy_;
};

std::string firstLineOf(std::string text) {
  if (const size_t nl = text.find('\n'); nl != std::string::npos) text.resize(nl);
  return text;
}

}  // namespace

RawScene readObj(const std::string& path, const LoadOptions& options) {
  ReferencePolicy policy = referencePolicy(path, options);
  const std::string bytes = readSceneFile(path, options.maxFileBytes);
  checkNumbers(path, "", bytes, kObjNumbers);
  checkFaceSizes(path, bytes);
  std::istringstream text(bytes);
  PolicyMaterialReader materialReader(policy);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &text, &materialReader,
                        /*triangulate=*/true, /*default_vcols_fallback=*/false)) {
    error = firstLineOf(error);
    throw InputError(path, "invalid OBJ: " + (error.empty() ? std::string("rejected by the parser") : error));
  }
  requireReadingTime(path, options, "parsed, no object read yet");
  RawScene raw;
  if (!warning.empty()) {
    warning = firstLineOf(warning);
    if (warning.find("Material") != std::string::npos || warning.find("material") != std::string::npos)
      raw.warnings.push_back(printable(warning, 200));
  }

  for (const tinyobj::material_t& m : materials) {
    Material mat;
    mat.name = m.name;
    mat.albedo = glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    mat.emission = glm::vec3(m.emission[0], m.emission[1], m.emission[2]);
    for (int i = 0; i < 3; ++i)
      if (!(mat.albedo[i] >= 0.0f) || !(mat.emission[i] >= 0.0f) || !std::isfinite(mat.emission[i]))
        throw InputError(path, "material '" + m.name + "': Kd or Ke is negative or not a number");
    raw.scene.materials.push_back(mat);
  }
  int defaultMaterial = -1;
  auto materialFor = [&](int id) -> uint32_t {
    if (id >= 0 && id < static_cast<int>(raw.scene.materials.size())) return static_cast<uint32_t>(id);
    if (defaultMaterial < 0) {
      defaultMaterial = static_cast<int>(raw.scene.materials.size());
      raw.scene.materials.push_back(Material{"default", glm::vec3(0.5f), glm::vec3(0.0f)});
    }
    return static_cast<uint32_t>(defaultMaterial);
  };

  auto vertex = [&](const std::vector<tinyobj::real_t>& array, int index, const std::string& what) {
    if (index < 0) return glm::vec3(0.0f);
    if (size_t(index) * 3 + 2 >= array.size()) throw InputError(path, what + ": vertex index out of range");
    return glm::vec3(array[3 * index], array[3 * index + 1], array[3 * index + 2]);
  };

  size_t objectsRead = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    requireReadingTime(
        path, options,
        std::to_string(objectsRead++) + " of " + std::to_string(shapes.size()) + " objects read");
    const std::string name = shape.name.empty() ? "object" : shape.name;
    const CellTag tag = parseCellTag(path, name);
    RawScene::TaggedMesh* tagged = nullptr;
    if (tag.kind == CellTag::Kind::Portal || tag.kind == CellTag::Kind::CellVolume ||
        tag.kind == CellTag::Kind::Seal) {
      auto& list = tag.kind == CellTag::Kind::Portal       ? raw.portals
                   : tag.kind == CellTag::Kind::CellVolume ? raw.volumes
                                                           : raw.seals;
      list.push_back({name, tag, {}});
      tagged = &list.back();
    }
    const int cell = tag.kind == CellTag::Kind::Cell ? raw.cellIndex(tag.a) : -1;
    const uint32_t node = tagged ? 0 : raw.nodeIndex(name);
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t n = mesh.num_face_vertices[f];
      if (n != 3 || offset + 3 > mesh.indices.size()) {
        offset += n;
        continue;  // lines and points: OBJ "l"/"p" never reach faces; a bad count is skipped
      }
      Triangle t;
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& idx = mesh.indices[offset + k];
        if (idx.vertex_index < 0)
          throw InputError(path, "object '" + name + "': face without a vertex index");
        t.p[k] = vertex(attrib.vertices, idx.vertex_index, "object '" + name + "'");
        t.n[k] = vertex(attrib.normals, idx.normal_index, "object '" + name + "'");
      }
      offset += 3;
      const int materialId = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      t.node = node;
      if (tagged) {
        tagged->triangles.push_back(t);
      } else {
        t.material = materialFor(materialId);
        raw.scene.triangles.push_back(t);
        raw.cellOfTriangle.push_back(cell);
      }
    }
  }
  return raw;
}

}  // namespace cpgi::detail
