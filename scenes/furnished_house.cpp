// The furnished two-storey house (`house-furnished`): the spiral house with what a real model of a house
// brings (issue 12): ~34k triangles, most of them in furniture and books, point and spot lights and no
// emissive surface, terrain that pulls the bounds below the ground floor.
#include <algorithm>
#include <cmath>

#include "scenes/furniture.h"

namespace cpgi {
namespace {

constexpr float kUpper = 2.95f;  // the upper floor's level (buildings.cpp's kLevel2)
constexpr float kCeiling = 2.7f, kUpperCeiling = kUpper + 2.7f;

// The ground round the house as a height field of `cell`-metre quads, sloping away from the apron
// (x in [-1, 11], z in [-1, 9], at y = 0) with a gentle wave; its own quads are left out.
void terrain(SceneBuilder& b, uint32_t material, uint32_t node, float cell) {
  const glm::vec2 lo(-9.0f, -9.0f), hi(19.0f, 17.0f), apronLo(-1.0f, -1.0f), apronHi(11.0f, 9.0f);
  auto height = [&](float x, float z) {
    const float dx = std::max({apronLo.x - x, 0.0f, x - apronHi.x}),
                dz = std::max({apronLo.y - z, 0.0f, z - apronHi.y});
    const float d = std::sqrt(dx * dx + dz * dz);
    return -0.03f - 0.05f * d +
           0.04f * std::sin(0.6f * x + 0.3f) * std::sin(0.45f * z) * std::min(1.0f, d / 2.0f);
  };
  const int nx = int(std::round((hi.x - lo.x) / cell)), nz = int(std::round((hi.y - lo.y) / cell));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nz; ++j) {
      const float x0 = lo.x + float(i) * cell, z0 = lo.y + float(j) * cell, x1 = x0 + cell, z1 = z0 + cell;
      if (x0 >= apronLo.x - 1e-4f && x1 <= apronHi.x + 1e-4f && z0 >= apronLo.y - 1e-4f &&
          z1 <= apronHi.y + 1e-4f)
        continue;
      const glm::vec3 p00(x0, height(x0, z0), z0), p10(x1, height(x1, z0), z0), p11(x1, height(x1, z1), z1),
          p01(x0, height(x0, z1), z1);
      b.triangle(p00, p11, p10, material, node);  // wound to face up
      b.triangle(p00, p01, p11, material, node);
    }
}

PunctualLight pointLight(const std::string& name, glm::vec3 at, float watts) {
  PunctualLight l;
  l.kind = PunctualLight::Kind::Point;
  l.name = name;
  l.position = at;
  l.intensity = glm::vec3(watts / (4.0f * float(M_PI)));
  return l;
}

}  // namespace

void furnishSpiralHouse(SceneBuilder& b, std::vector<PunctualLight>& lights) {
  Furniture f(b);
  auto in = [&](const char* room) { return b.node(std::string(room) + "/furniture"); };
  const float y2 = kUpper;

  // Hall: shoe cabinet, coat stand, a bookshelf between the doors, the front door's leaf open.
  f.cabinets({{0.2f, 0, 0.6f}, {0.6f, 0.9f, 1.5f}}, 2, Facing::PlusX, in("hall"));
  f.column({3.1f, 0, 0.5f}, 0.02f, 1.8f, 12, f.wood(), in("hall"));
  f.column({3.1f, 0, 0.5f}, 0.2f, 0.02f, 24, f.wood(), in("hall"));
  f.bookshelf({{3.05f, 0, 2.3f}, {3.4f, 2.0f, 3.6f}}, 5, Facing::MinusX, 1, in("hall"));
  f.block({{2.6f, 0, 0.2f}, {2.64f, 2.05f, 1.05f}}, f.wood(), in("hall"));

  // Living room: dining table and chairs under a spot, a sofa and an armchair, a bookshelf, a side table.
  f.table({5.0f, 0, 2.0f}, {1.6f, 0.9f}, false, in("living"));
  for (float x : {4.6f, 5.4f}) {
    f.chair({x, 0, 1.3f}, Facing::PlusZ, in("living"));
    f.chair({x, 0, 2.7f}, Facing::MinusZ, in("living"));
  }
  f.sofa({6.8f, 0, 4.35f}, {2.2f, 0.9f}, Facing::MinusZ, in("living"));
  f.sofa({9.15f, 0, 4.0f}, {0.9f, 0.85f}, Facing::MinusX, in("living"));
  f.table({6.8f, 0, 3.1f}, {0.8f, 0.8f}, true, in("living"));
  f.bookshelf({{3.6f, 0, 2.6f}, {3.95f, 2.2f, 4.7f}}, 6, Facing::PlusX, 2, in("living"));
  f.block({{3.62f, 0, 0.22f}, {3.66f, 2.05f, 1.0f}}, f.wood(),
          in("living"));  // the hall door's leaf, back to the wall

  // Kitchen: a run of cabinets under the window, a fridge, a table with four chairs.
  f.cabinets({{4.6f, 0, 7.2f}, {9.6f, 0.9f, 7.8f}}, 8, Facing::MinusZ, in("kitchen"));
  f.block({{3.7f, 0, 5.2f}, {4.4f, 1.9f, 5.9f}}, f.fabric(), in("kitchen"), 0.3f);
  f.table({6.0f, 0, 6.0f}, {1.2f, 0.8f}, false, in("kitchen"));
  for (float x : {5.6f, 6.4f}) {
    f.chair({x, 0, 5.45f}, Facing::PlusZ, in("kitchen"));
    f.chair({x, 0, 6.55f}, Facing::MinusZ, in("kitchen"));
  }

  // Landing: a balustrade round the stair hole (open where the stair arrives), a bookshelf, a plant.
  const float rail = 0.9f, spacing = 0.12f;
  f.balustrade({{0.35f, y2, 3.95f}, {2.35f, y2, 3.95f}, {2.35f, y2, 4.45f}}, rail, spacing, in("landing"));
  f.balustrade({{2.35f, y2, 5.25f}, {2.35f, y2, 6.05f}, {0.35f, y2, 6.05f}}, rail, spacing, in("landing"));
  f.bookshelf({{0.2f, y2, 0.6f}, {0.55f, y2 + 2.0f, 2.2f}}, 5, Facing::PlusX, 3, in("landing"));
  f.column({3.0f, y2, 0.6f}, 0.2f, 0.45f, 32, f.wood(), in("landing"));
  f.column({3.0f, y2 + 0.45f, 0.6f}, 0.08f, 0.5f, 16, f.fabric(), in("landing"));

  // Bedrooms: a double bed with nightstands, a wardrobe and a desk; two single beds, a wardrobe, a shelf.
  f.bed({7.75f, y2, 1.25f}, {2.0f, 1.6f}, false, in("bedroom1"));
  f.block({{9.3f, y2, 0.7f}, {9.75f, y2 + 0.5f, 1.15f}}, f.wood(), in("bedroom1"));
  f.block({{9.3f, y2, 2.95f}, {9.75f, y2 + 0.5f, 3.4f}}, f.wood(), in("bedroom1"));
  f.block({{3.7f, y2, 2.4f}, {4.3f, y2 + 2.1f, 3.8f}}, f.wood(), in("bedroom1"), 0.3f);
  f.table({5.6f, y2, 0.6f}, {1.2f, 0.6f}, false, in("bedroom1"));
  f.chair({5.6f, y2, 1.1f}, Facing::MinusZ, in("bedroom1"));
  f.block({{3.6f, y2, 1.86f}, {4.45f, y2 + 2.05f, 1.9f}}, f.wood(), in("bedroom1"));  // its door's leaf
  for (float z : {4.4f, 6.6f}) f.bed({7.95f, y2, z}, {1.8f, 0.9f}, false, in("bedroom2"));
  f.block({{4.0f, y2, 7.2f}, {5.2f, y2 + 2.1f, 7.75f}}, f.wood(), in("bedroom2"), 0.3f);
  f.bookshelf({{5.6f, y2, 4.15f}, {6.8f, y2 + 1.8f, 4.5f}}, 4, Facing::PlusZ, 4, in("bedroom2"));

  // Pendants and the lights under them (18 W each, the panel lamps' power), a spot over the table.
  struct Lamp {
    const char* room;
    glm::vec3 at;
  };
  const Lamp lamps[] = {
      {"hall", {1.8f, kCeiling, 2.0f}},           {"living", {6.7f, kCeiling, 2.55f}},
      {"kitchen", {6.7f, kCeiling, 6.45f}},       {"landing", {1.8f, kUpperCeiling, 2.0f}},
      {"bedroom1", {6.7f, kUpperCeiling, 2.05f}}, {"bedroom2", {6.7f, kUpperCeiling, 5.95f}}};
  const float drop = 0.5f;
  for (const Lamp& l : lamps) {
    f.pendant(l.at, drop, in(l.room));
    lights.push_back(pointLight(std::string("lamp-") + l.room, l.at - glm::vec3(0, drop + 0.03f, 0), 18.0f));
  }
  PunctualLight spot;
  spot.kind = PunctualLight::Kind::Spot;
  spot.name = "spot-dining";
  spot.position = {5.0f, kCeiling - 0.05f, 2.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.innerCone = 0.45f, spot.outerCone = 0.6f;
  spot.intensity = glm::vec3(3.0f);
  lights.push_back(spot);

  terrain(b, b.material("terrain", {0.3f, 0.35f, 0.25f}), b.node("outside/terrain"), 0.4f);
}

}  // namespace cpgi
