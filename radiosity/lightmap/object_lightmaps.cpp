#include "radiosity/lightmap/object_lightmaps.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "radiosity/lightmap/scene_uv.h"

namespace cpgi {
namespace {

// Per node, the atlas's charts holding its triangles, and those triangles, in node order.
struct NodeCharts {
  std::vector<size_t> patches;
  std::vector<uint32_t> triangles;
};

std::map<uint32_t, NodeCharts> chartsByNode(const Scene& scene, const LightmapAtlas& atlas) {
  std::map<uint32_t, NodeCharts> nodes;
  for (size_t p = 0; p < atlas.patches.size(); ++p) {
    std::set<uint32_t> seen;
    for (int32_t tri : atlas.patches[p].triangles) {
      const uint32_t node = scene.triangles[size_t(tri)].node;
      NodeCharts& n = nodes[node];
      n.triangles.push_back(uint32_t(tri));
      if (seen.insert(node).second) n.patches.push_back(p);
    }
  }
  return nodes;
}

// An object per node, named and given a file stem no other object has.
std::vector<ObjectLightmap> namedObjects(const Scene& scene, const std::map<uint32_t, NodeCharts>& nodes) {
  std::vector<ObjectLightmap> objects;
  std::set<std::string> stems;
  for (const auto& [node, charts] : nodes) {
    ObjectLightmap o;
    o.node = node;
    o.name = node < scene.nodePaths.size() ? scene.nodePaths[node] : std::string();
    const std::string base = "lightmap-" + safeFileName(o.name);
    o.fileStem = base;
    for (int k = 2; !stems.insert(o.fileStem).second; ++k) o.fileStem = base + "-" + std::to_string(k);
    o.triangles = charts.triangles;
    objects.push_back(std::move(o));
  }
  return objects;
}

size_t validTexelsOf(const LightmapAtlas& atlas, const std::vector<size_t>& patches) {
  size_t n = 0;
  for (size_t p : patches) {
    const Patch& c = atlas.patches[p];
    for (int y = c.y; y < c.y + c.h; ++y)
      for (int x = c.x; x < c.x + c.w; ++x) n += atlas.patch[size_t(y) * atlas.width + x] == int32_t(p);
  }
  return n;
}

// Shelf packing of the charts with their gutter rings, as the scene's atlas is packed (tallest first, a
// little wider than the square root). Returns the chart of each of o.copies.
std::vector<size_t> packCopies(const LightmapAtlas& atlas, const std::vector<size_t>& patches,
                               ObjectLightmap& o) {
  const int pad = atlas.padding;
  std::vector<size_t> order = patches;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Patch &pa = atlas.patches[a], &pb = atlas.patches[b];
    return pa.h != pb.h ? pa.h > pb.h : pa.w > pb.w;
  });
  double area = 0.0;
  int widest = 0;
  for (size_t p : order) {
    const Patch& c = atlas.patches[p];
    area += double(c.w + 2 * pad) * double(c.h + 2 * pad);
    widest = std::max(widest, c.w + 2 * pad);
  }
  const int width = std::max(widest, int(std::ceil(std::sqrt(area * 1.15))));
  int x = 0, y = 0, shelf = 0;
  for (size_t p : order) {
    const Patch& c = atlas.patches[p];
    const int w = c.w + 2 * pad, h = c.h + 2 * pad;
    if (x + w > width) y += shelf, x = 0, shelf = 0;
    o.copies.push_back({c.x - pad, c.y - pad, w, h, x, y});
    x += w;
    shelf = std::max(shelf, h);
  }
  o.width = std::max(width, 1);
  o.height = std::max(y + shelf, 1);
  return order;
}

}  // namespace

std::string safeFileName(const std::string& name) {
  std::string out;
  bool gap = false;
  for (const char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '_' || c == '.';
    if (!keep) {
      gap = true;
      continue;
    }
    if (gap && !out.empty()) out += '_';
    gap = false;
    out += c;
    if (out.size() >= 60) break;
  }
  // A name of dots only ("." or "..") would be a folder's.
  if (out.find_first_not_of('.') == std::string::npos) return "object";
  return out;
}

ObjectLightmaps layOutObjectLightmaps(const Scene& scene, const LightmapAtlas& atlas) {
  ObjectLightmaps out;
  out.objectOfTriangle.assign(scene.triangles.size(), -1);
  out.triangleUV.assign(scene.triangles.size(), std::array<glm::vec2, 3>{});
  const std::map<uint32_t, NodeCharts> nodes = chartsByNode(scene, atlas);
  out.objects = namedObjects(scene, nodes);
  const glm::vec2 atlasSize(float(atlas.width), float(atlas.height));
  size_t k = 0;
  for (const auto& [node, charts] : nodes) {
    ObjectLightmap& o = out.objects[k];
    const std::vector<size_t> order = packCopies(atlas, charts.patches, o);
    o.validTexels = validTexelsOf(atlas, charts.patches);
    // Each chart's triangles move with it, by the copy's offset in texels.
    const glm::vec2 size(float(o.width), float(o.height));
    for (size_t c = 0; c < order.size(); ++c) {
      const ObjectLightmap::Copy& copy = o.copies[c];
      const glm::vec2 offset(float(copy.dx - copy.x), float(copy.dy - copy.y));
      for (int32_t tri : atlas.patches[order[c]].triangles) {
        if (scene.triangles[size_t(tri)].node != node) continue;
        out.objectOfTriangle[size_t(tri)] = int(k);
        for (int v = 0; v < 3; ++v)
          out.triangleUV[size_t(tri)][v] = (atlas.triangleUV[size_t(tri)][v] * atlasSize + offset) / size;
      }
    }
    ++k;
  }
  return out;
}

ObjectLightmaps layOutObjectSceneUVs(const Scene& scene, const LightmapAtlas& atlas,
                                     std::vector<std::string>& refusals, std::vector<std::string>& warnings) {
  ObjectLightmaps out;
  out.sceneUVs = true;
  out.objectOfTriangle.assign(scene.triangles.size(), -1);
  out.triangleUV.assign(scene.triangles.size(), std::array<glm::vec2, 3>{});
  const std::map<uint32_t, NodeCharts> nodes = chartsByNode(scene, atlas);
  out.objects = namedObjects(scene, nodes);
  size_t k = 0;
  for (const auto& [node, charts] : nodes) {
    ObjectLightmap& o = out.objects[k];
    o.validTexels = validTexelsOf(atlas, charts.patches);
    o.width = o.height = sceneUvSize(scene, o.validTexels, 8192, o.triangles);
    const SceneUvCheck check = checkSceneUVs(scene, o.width, o.triangles);
    refusals.insert(refusals.end(), check.refusals.begin(), check.refusals.end());
    warnings.insert(warnings.end(), check.warnings.begin(), check.warnings.end());
    for (uint32_t tri : o.triangles) {
      const Triangle& t = scene.triangles[tri];
      out.objectOfTriangle[tri] = int(k);
      if (t.uv >= scene.looks.uvs.size() || !scene.looks.uvs[t.uv].has(1)) continue;
      for (int v = 0; v < 3; ++v) out.triangleUV[tri][v] = scene.looks.uvs[t.uv].at(t.p[v], 1);
    }
    ++k;
  }
  return out;
}

std::vector<glm::vec3> objectImage(const Scene& scene, const LightmapAtlas& atlas,
                                   const ObjectLightmaps& layout, size_t k,
                                   const std::vector<glm::vec3>& values) {
  const ObjectLightmap& o = layout.objects[k];
  if (layout.sceneUVs) {
    std::vector<std::array<glm::vec2, 3>> uvs;
    return resampleToSceneUVs(scene, atlas, values, o.width, uvs, 4, o.triangles);
  }
  std::vector<glm::vec3> image(size_t(o.width) * o.height, glm::vec3(0.0f));
  for (const ObjectLightmap::Copy& c : o.copies)
    for (int y = 0; y < c.h; ++y)
      std::copy_n(values.begin() + ptrdiff_t(size_t(c.y + y) * atlas.width + c.x), c.w,
                  image.begin() + ptrdiff_t(size_t(c.dy + y) * o.width + c.dx));
  return image;
}

}  // namespace cpgi
