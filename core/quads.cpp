#include "core/quads.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace cpgi {
namespace {

// Index of the vertex opposite the longest edge: in a right triangle it is the right-angle corner.
int rightAngleCorner(const Triangle& t) {
  float best = -1.0f;
  int corner = 0;
  for (int i = 0; i < 3; ++i) {
    const float len = glm::length(t.p[(i + 1) % 3] - t.p[(i + 2) % 3]);
    if (len > best) best = len, corner = i;
  }
  return corner;
}

struct EdgeKey {
  glm::vec3 a, b;  // ordered lexicographically so both triangles produce the same key
  bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b; }
};
struct EdgeHash {
  size_t operator()(const EdgeKey& k) const {
    auto h = [](const glm::vec3& v) {
      return std::hash<float>()(v.x) ^ (std::hash<float>()(v.y) * 31) ^ (std::hash<float>()(v.z) * 131);
    };
    return h(k.a) ^ (h(k.b) * 7919);
  }
};
bool lexLess(const glm::vec3& a, const glm::vec3& b) {
  return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
}
EdgeKey makeKey(glm::vec3 a, glm::vec3 b) {
  if (lexLess(b, a)) std::swap(a, b);
  return {a, b};
}

}  // namespace

size_t QuadSet::looseTriangles() const {
  return static_cast<size_t>(std::count(quadOfTriangle.begin(), quadOfTriangle.end(), -1));
}

QuadSet findQuads(const Scene& scene, float angleTolerance) {
  QuadSet out;
  const auto& tris = scene.triangles;
  out.quadOfTriangle.assign(tris.size(), -1);

  // Hypotenuse -> triangles whose right angle faces it. Vertices shared exactly (as exporters write
  // them) are what we pair on; nearly-equal vertices stay loose, which is safe.
  std::unordered_map<EdgeKey, std::vector<uint32_t>, EdgeHash> byHypotenuse;
  std::vector<int> corner(tris.size(), -1);
  for (uint32_t i = 0; i < tris.size(); ++i) {
    const Triangle& t = tris[i];
    if (t.area() <= 0.0f) continue;
    const int c = rightAngleCorner(t);
    const glm::vec3 e1 = glm::normalize(t.p[(c + 1) % 3] - t.p[c]);
    const glm::vec3 e2 = glm::normalize(t.p[(c + 2) % 3] - t.p[c]);
    if (std::abs(glm::dot(e1, e2)) > angleTolerance) continue;
    corner[i] = c;
    byHypotenuse[makeKey(t.p[(c + 1) % 3], t.p[(c + 2) % 3])].push_back(i);
  }

  for (uint32_t i = 0; i < tris.size(); ++i) {
    if (corner[i] < 0 || out.quadOfTriangle[i] >= 0) continue;
    const Triangle& a = tris[i];
    const int ca = corner[i];
    const auto& candidates = byHypotenuse[makeKey(a.p[(ca + 1) % 3], a.p[(ca + 2) % 3])];
    for (uint32_t j : candidates) {
      if (j == i || out.quadOfTriangle[j] >= 0) continue;
      const Triangle& b = tris[j];
      if (b.material != a.material || b.node != a.node) continue;
      const glm::vec3 na = a.geometricNormal(), nb = b.geometricNormal();
      if (glm::dot(na, nb) < 1.0f - angleTolerance) continue;
      // Corners around the boundary: right angle of a, next vertex of a, right angle of b, last of a.
      const glm::vec3 o = a.p[ca], p1 = a.p[(ca + 1) % 3], opp = b.p[corner[j]], p3 = a.p[(ca + 2) % 3];
      // A rectangle's diagonals bisect each other.
      if (glm::length((o + opp) - (p1 + p3)) > angleTolerance * glm::length(p1 - p3)) continue;
      Quad q;
      q.triangles = {i, j};
      q.corners = {o, p1, opp, p3};
      q.normal = na;
      if (glm::dot(glm::cross(p1 - o, p3 - o), na) < 0.0f) q.corners = {o, p3, opp, p1};
      out.quadOfTriangle[i] = out.quadOfTriangle[j] = static_cast<int32_t>(out.quads.size());
      out.quads.push_back(q);
      break;
    }
  }
  return out;
}

}  // namespace cpgi
