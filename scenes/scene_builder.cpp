#include "scenes/scene_builder.h"

#include <cmath>
#include <utility>

namespace cpgi {

uint32_t SceneBuilder::material(const std::string& name, glm::vec3 albedo, glm::vec3 emission) {
  scene_.materials.push_back({name, albedo, emission});
  return static_cast<uint32_t>(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::node(const std::string& path) {
  for (size_t i = 0; i < scene_.nodePaths.size(); ++i)
    if (scene_.nodePaths[i] == path) return static_cast<uint32_t>(i);
  scene_.nodePaths.push_back(path);
  return static_cast<uint32_t>(scene_.nodePaths.size() - 1);
}

void SceneBuilder::quad(glm::vec3 o, glm::vec3 u, glm::vec3 v, uint32_t material, uint32_t node) {
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  Triangle a, b;
  a.p = {o, o + u, o + u + v};
  b.p = {o, o + u + v, o + v};
  a.n = b.n = {n, n, n};
  a.material = b.material = material;
  a.node = b.node = node;
  scene_.triangles.push_back(a);
  scene_.triangles.push_back(b);
}

Triangle flatTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material, uint32_t node) {
  Triangle t;
  t.p = {a, b, c};
  const glm::vec3 n = t.geometricNormal();
  t.n = {n, n, n};
  t.material = material;
  t.node = node;
  return t;
}

void SceneBuilder::triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material, uint32_t node) {
  scene_.triangles.push_back(flatTriangle(a, b, c, material, node));
}

uint32_t SceneBuilder::rect(int axis, float at, float sign, glm::vec2 lo, glm::vec2 hi, uint32_t material,
                            uint32_t node, float maxCell) {
  const uint32_t first = static_cast<uint32_t>(scene_.triangles.size());
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const int n1 =
      maxCell > 0.0f ? std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / maxCell - 1e-4f))) : 1;
  const int n2 =
      maxCell > 0.0f ? std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / maxCell - 1e-4f))) : 1;
  for (int j = 0; j < n2; ++j) {
    for (int i = 0; i < n1; ++i) {
      glm::vec3 o(0.0f), u(0.0f), v(0.0f);
      o[axis] = at;
      o[a1] = lo.x + (hi.x - lo.x) * i / n1;
      o[a2] = lo.y + (hi.y - lo.y) * j / n2;
      u[a1] = (hi.x - lo.x) / n1;
      v[a2] = (hi.y - lo.y) / n2;
      // e_a1 × e_a2 = +e_axis for cyclic axes, so swapping the edges flips the facing.
      if (sign > 0.0f)
        quad(o, u, v, material, node);
      else
        quad(o, v, u, material, node);
    }
  }
  return first;
}

void SceneBuilder::boxOnFloor(glm::vec3 lo, glm::vec3 hi, uint32_t material, uint32_t node) {
  rect(0, lo.x, -1, {lo.y, lo.z}, {hi.y, hi.z}, material, node);
  rect(0, hi.x, +1, {lo.y, lo.z}, {hi.y, hi.z}, material, node);
  rect(1, hi.y, +1, {lo.z, lo.x}, {hi.z, hi.x}, material, node);
  rect(2, lo.z, -1, {lo.x, lo.y}, {hi.x, hi.y}, material, node);
  rect(2, hi.z, +1, {lo.x, lo.y}, {hi.x, hi.y}, material, node);
}

void SceneBuilder::room(const Room& r) {
  const glm::vec3 lo = r.lo, hi = r.hi;
  const float sub = r.maxCell;
  rect(1, lo.y, +1, {lo.z, lo.x}, {hi.z, hi.x}, r.floor, node(r.name + "/floor"), sub);
  rect(1, hi.y, -1, {lo.z, lo.x}, {hi.z, hi.x}, r.ceiling, node(r.name + "/ceiling"), sub);
  rect(2, lo.z, +1, {lo.x, lo.y}, {hi.x, hi.y}, r.south, node(r.name + "/wall-south"), sub);
  rect(2, hi.z, -1, {lo.x, lo.y}, {hi.x, hi.y}, r.north, node(r.name + "/wall-north"), sub);
  for (int side = 0; side < 2; ++side) {
    const float x = side == 0 ? lo.x : hi.x, sign = side == 0 ? 1.0f : -1.0f;
    const uint32_t mat = side == 0 ? r.west : r.east;
    const uint32_t n = node(r.name + (side == 0 ? "/wall-west" : "/wall-east"));
    if (!(side == 0 ? r.doorWest : r.doorEast)) {
      rect(0, x, sign, {lo.y, lo.z}, {hi.y, hi.z}, mat, n, sub);
      continue;
    }
    const Door& d = r.door;
    rect(0, x, sign, {lo.y, lo.z}, {hi.y, d.z0}, mat, n, sub);
    rect(0, x, sign, {lo.y, d.z1}, {hi.y, hi.z}, mat, n, sub);
    rect(0, x, sign, {d.top, d.z0}, {hi.y, d.z1}, mat, n, sub);
  }
}

void SceneBuilder::doorReveal(float x0, float x1, const Door& d, const std::string& west,
                              const std::string& east, uint32_t wallMaterial, uint32_t floorMaterial) {
  const float xm = 0.5f * (x0 + x1);
  for (int side = 0; side < 2; ++side) {
    const float a = side == 0 ? x0 : xm, c = side == 0 ? xm : x1;
    const uint32_t n = node((side == 0 ? west : east) + "/door-" + west + east);
    rect(2, d.z0, +1, {a, 0}, {c, d.top}, wallMaterial, n);
    rect(2, d.z1, -1, {a, 0}, {c, d.top}, wallMaterial, n);
    rect(1, d.top, -1, {d.z0, a}, {d.z1, c}, wallMaterial, n);
    rect(1, 0.0f, +1, {d.z0, a}, {d.z1, c}, floorMaterial, n);
  }
}

Camera lookAt(const std::string& name, glm::vec3 eye, glm::vec3 target) {
  Camera cam;
  cam.name = name;
  cam.position = eye;
  cam.forward = glm::normalize(target - eye);
  cam.up = glm::normalize(glm::vec3(0, 1, 0) - cam.forward * cam.forward.y);
  cam.yfov = glm::radians(60.0f);
  cam.aspect = 4.0f / 3.0f;
  return cam;
}

void cellsFromNodePaths(const Scene& scene, const std::vector<std::string>& names, CellGraph& cells) {
  for (const std::string& n : names) cells.cells.push_back({n, {}, {}});
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const std::string& path = scene.nodePaths[scene.triangles[t].node];
    const int c = cells.findCell(path.substr(0, path.find('/')));
    if (c >= 0) cells.cells[c].triangles.push_back(t);
  }
}

void appendBoxVolume(glm::vec3 lo, glm::vec3 hi, std::vector<Triangle>& out) {
  Scene tmp;
  SceneBuilder sb(tmp);
  sb.material("volume", glm::vec3(0.0f));
  const uint32_t node = sb.node("volume");
  for (int a = 0; a < 3; ++a) {
    const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    sb.rect(a, lo[a], -1, {lo[a1], lo[a2]}, {hi[a1], hi[a2]}, 0, node);
    sb.rect(a, hi[a], +1, {lo[a1], lo[a2]}, {hi[a1], hi[a2]}, 0, node);
  }
  out.insert(out.end(), tmp.triangles.begin(), tmp.triangles.end());
}

}  // namespace cpgi
