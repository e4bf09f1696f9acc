#include "radiosity/lightmap/scene_uv.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <span>

#include "core/error.h"
#include "radiosity/lightmap/lightmap_sampling.h"

namespace cpgi {
namespace {

constexpr float kUvSlack = 1e-4f;  // coordinates this far outside [0,1] are rounding, not a problem

std::array<glm::vec2, 3> cornersOf(const Scene& scene, const Triangle& t) {
  const SurfaceUV& map = scene.looks.uvs[t.uv];
  return {map.at(t.p[0], 1), map.at(t.p[1], 1), map.at(t.p[2], 1)};
}

bool hasSceneUV(const Scene& scene, const Triangle& t) {
  return t.uv < scene.looks.uvs.size() && scene.looks.uvs[t.uv].has(1);
}

float uvArea(const std::array<glm::vec2, 3>& c) {
  const glm::vec2 a = c[1] - c[0], b = c[2] - c[0];
  return 0.5f * (a.x * b.y - a.y * b.x);
}

// Calls visit(x, y, barycentrics) for every texel centre of a `size` layout within the triangle `c` (texel
// units), those within `slack` of its edges included (in barycentric units).
template <typename Visit>
void rasterize(const std::array<glm::vec2, 3>& uv, int size, float slack, Visit&& visit) {
  std::array<glm::vec2, 3> c;
  for (int k = 0; k < 3; ++k) c[k] = uv[k] * float(size);
  const float area = uvArea(c);
  if (!(std::abs(area) > 1e-12f)) return;
  const glm::vec2 lo = glm::min(c[0], glm::min(c[1], c[2])), hi = glm::max(c[0], glm::max(c[1], c[2]));
  const int x0 = std::max(0, int(std::floor(lo.x - 0.5f))),
            x1 = std::min(size - 1, int(std::ceil(hi.x - 0.5f)));
  const int y0 = std::max(0, int(std::floor(lo.y - 0.5f))),
            y1 = std::min(size - 1, int(std::ceil(hi.y - 0.5f)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
      const glm::vec3 b(uvArea({p, c[1], c[2]}) / area, uvArea({c[0], p, c[2]}) / area,
                        uvArea({c[0], c[1], p}) / area);
      if (b.x >= -slack && b.y >= -slack && b.z >= -slack) visit(x, y, b);
    }
}

std::string meshName(const Scene& scene, const Triangle& t) {
  return t.node < scene.nodePaths.size() ? scene.nodePaths[t.node] : std::string("(unnamed)");
}

// Union-find over triangles, for charts: triangles of a mesh that share an edge in the layout.
struct Charts {
  std::vector<uint32_t> parent;
  uint32_t find(uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
};

Charts chartsOf(const Scene& scene) {
  Charts charts;
  charts.parent.resize(scene.triangles.size());
  std::iota(charts.parent.begin(), charts.parent.end(), 0u);
  std::map<std::tuple<uint32_t, int64_t, int64_t, int64_t, int64_t>, uint32_t> edges;
  auto key = [](glm::vec2 a) {
    return std::pair<int64_t, int64_t>(std::llround(a.x * 1e6), std::llround(a.y * 1e6));
  };
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    if (!hasSceneUV(scene, t)) continue;
    const std::array<glm::vec2, 3> c = cornersOf(scene, t);
    for (int k = 0; k < 3; ++k) {
      auto a = key(c[k]), b = key(c[(k + 1) % 3]);
      if (b < a) std::swap(a, b);
      const auto [it, fresh] =
          edges.emplace(std::make_tuple(t.node, a.first, a.second, b.first, b.second), i);
      if (!fresh) charts.parent[charts.find(i)] = charts.find(it->second);
    }
  }
  return charts;
}

// Calls visit(i) for every triangle index of `subset`, or of the scene when it is empty.
template <typename Visit>
void forEachTriangle(const Scene& scene, std::span<const uint32_t> subset, Visit&& visit) {
  if (subset.empty()) {
    for (uint32_t i = 0; i < scene.triangles.size(); ++i) visit(i);
  } else {
    for (uint32_t i : subset) visit(i);
  }
}

}  // namespace

int sceneUvSize(const Scene& scene, size_t texels, int maxSize, std::span<const uint32_t> triangles) {
  double area = 0.0;
  forEachTriangle(scene, triangles, [&](uint32_t i) {
    const Triangle& t = scene.triangles[i];
    if (hasSceneUV(scene, t)) area += std::abs(uvArea(cornersOf(scene, t)));
  });
  const double side = area > 0.0 ? std::sqrt(double(texels) / std::min(area, 1.0)) : 16.0;
  const int size = int(std::ceil(std::clamp(side, 16.0, double(maxSize)) / 4.0)) * 4;
  return std::min(size, maxSize / 4 * 4);
}

SceneUvCheck checkSceneUVs(const Scene& scene, int size, std::span<const uint32_t> triangles) {
  SceneUvCheck check;
  check.size = size;
  struct MeshFigures {
    size_t missing = 0, outside = 0, texels = 0, shared = 0;
    double area = 0.0, smallChartArea = 0.0;
  };
  std::map<std::string, MeshFigures> meshes;
  std::vector<int32_t> owner(size_t(size) * size, -1);
  std::vector<uint8_t> twice(owner.size(), 0);
  Charts charts = chartsOf(scene);
  std::vector<size_t> chartTexels(scene.triangles.size(), 0);
  forEachTriangle(scene, triangles, [&](uint32_t i) {
    const Triangle& t = scene.triangles[i];
    MeshFigures& m = meshes[meshName(scene, t)];
    if (!hasSceneUV(scene, t)) {
      ++m.missing;
      return;
    }
    const std::array<glm::vec2, 3> c = cornersOf(scene, t);
    for (const glm::vec2& q : c)
      if (q.x < -kUvSlack || q.y < -kUvSlack || q.x > 1.0f + kUvSlack || q.y > 1.0f + kUvSlack) {
        ++m.outside;
        break;
      }
    // Strictly inside: a texel centre on the edge two triangles share belongs to neither here.
    const uint32_t chart = charts.find(i);
    rasterize(c, size, -1e-4f, [&](int x, int y, const glm::vec3&) {
      const size_t at = size_t(y) * size + x;
      ++chartTexels[chart];
      if (owner[at] < 0) {
        owner[at] = int32_t(i);
      } else if (!twice[at]) {
        twice[at] = 1;
        ++meshes[meshName(scene, scene.triangles[size_t(owner[at])])].shared;
      }
    });
  });
  forEachTriangle(scene, triangles, [&](uint32_t i) {
    const Triangle& t = scene.triangles[i];
    if (!hasSceneUV(scene, t)) return;
    MeshFigures& m = meshes[meshName(scene, t)];
    m.area += t.area();
    if (chartTexels[charts.find(i)] < 4) m.smallChartArea += t.area();
  });
  for (size_t at = 0; at < owner.size(); ++at)
    if (owner[at] >= 0)
      ++meshes[meshName(scene, scene.triangles[size_t(owner[at])])].texels, ++check.coveredTexels;
  for (const auto& [name, m] : meshes) {
    const std::string mesh = "mesh '" + printable(name, 80) + "'";
    if (m.missing > 0)
      check.refusals.push_back(mesh + ": " + std::to_string(m.missing) + " triangles without TEXCOORD_1");
    if (m.outside > 0)
      check.refusals.push_back(mesh + ": " + std::to_string(m.outside) +
                               " triangles with TEXCOORD_1 outside [0,1]");
    // A few texels on shared edges are rounding; a hundredth of the mesh's is a layout laid twice.
    if (m.shared > 0 && m.shared * 100 > std::max<size_t>(m.texels, 1))
      check.refusals.push_back(mesh + ": " + std::to_string(m.shared) +
                               " texels of TEXCOORD_1 lie under two triangles (overlapping charts)");
    if (m.area > 0.0 && m.smallChartArea > 0.5 * m.area)
      check.warnings.push_back(mesh +
                               ": most of its surface lies in TEXCOORD_1 charts of fewer than 4 texels at " +
                               std::to_string(size) + "x" + std::to_string(size));
  }
  return check;
}

std::vector<glm::vec3> resampleToSceneUVs(const Scene& scene, const LightmapAtlas& own,
                                          const std::vector<glm::vec3>& values, int size,
                                          std::vector<std::array<glm::vec2, 3>>& uvs, int gutter,
                                          std::span<const uint32_t> triangles) {
  std::vector<glm::vec3> out(size_t(size) * size, glm::vec3(0.0f));
  std::vector<uint8_t> filled(out.size(), 0);
  uvs.assign(scene.triangles.size(), std::array<glm::vec2, 3>{});
  const std::span<const glm::vec3> lightmap(values);
  forEachTriangle(scene, triangles, [&](uint32_t i) {
    const Triangle& t = scene.triangles[i];
    if (!hasSceneUV(scene, t) || i >= own.triangleUV.size()) return;
    uvs[i] = cornersOf(scene, t);
    const std::array<glm::vec2, 3>& at = own.triangleUV[i];
    rasterize(uvs[i], size, 1e-4f, [&](int x, int y, const glm::vec3& b) {
      const glm::vec2 uv = b.x * at[0] + b.y * at[1] + b.z * at[2];
      const size_t k = size_t(y) * size + x;
      out[k] = sampleBilinear(own.width, own.height, lightmap, uv);
      filled[k] = 1;
    });
  });
  // The gutter: each empty texel next to filled ones takes their mean, ring by ring, so that bilinear
  // filtering and mipmaps at a chart's edge do not pull in black.
  for (int ring = 0; ring < gutter; ++ring) {
    std::vector<uint8_t> next = filled;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const size_t k = size_t(y) * size + x;
        if (filled[k]) continue;
        glm::vec3 sum(0.0f);
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= size || ny >= size || !filled[size_t(ny) * size + nx]) continue;
            sum += out[size_t(ny) * size + nx], ++n;
          }
        if (n > 0) out[k] = sum / float(n), next[k] = 1;
      }
    filled = std::move(next);
  }
  return out;
}

}  // namespace cpgi
