#include "scenes/furniture.h"

#include <algorithm>
#include <cmath>

namespace cpgi {
namespace {

Box3 span(glm::vec3 lo, glm::vec3 hi) {
  return {glm::min(lo, hi), glm::max(lo, hi)};
}

// The unit vector a piece facing `f` faces, in the floor plane.
glm::vec3 toward(Facing f) {
  switch (f) {
    case Facing::PlusX:
      return {1, 0, 0};
    case Facing::MinusX:
      return {-1, 0, 0};
    case Facing::PlusZ:
      return {0, 0, 1};
    case Facing::MinusZ:
      break;
  }
  return {0, 0, -1};
}

// A box centred at `c` on the floor plane's axes: `along` across the facing direction, `deep` along it.
Box3 facingBox(glm::vec3 c, Facing f, float along, float deep, float y0, float y1) {
  const glm::vec3 d = toward(f);
  const glm::vec3 side(std::abs(d.z), 0, std::abs(d.x));
  const glm::vec3 half = 0.5f * (along * side + deep * glm::abs(d));
  return span({c.x - half.x, y0, c.z - half.z}, {c.x + half.x, y1, c.z + half.z});
}

}  // namespace

Furniture::Furniture(SceneBuilder& b) : b_(b) {
  wood_ = b.material("wood", {0.45f, 0.3f, 0.2f});
  fabric_ = b.material("fabric", {0.3f, 0.35f, 0.5f});
  metal_ = b.material("metal", glm::vec3(0.6f));
  white_ = b.material("white", glm::vec3(0.85f));
  books_ = {b.material("book-red", {0.6f, 0.15f, 0.1f}), b.material("book-blue", {0.15f, 0.3f, 0.55f}),
            b.material("book-cream", {0.7f, 0.65f, 0.4f})};
}

void Furniture::block(const Box3& box, uint32_t material, uint32_t node, float maxCell) {
  for (int a = 0; a < 3; ++a) {
    const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    const glm::vec2 lo(box.lo[a1], box.lo[a2]), hi(box.hi[a1], box.hi[a2]);
    b_.rect(a, box.lo[a], -1, lo, hi, material, node, maxCell);
    b_.rect(a, box.hi[a], +1, lo, hi, material, node, maxCell);
  }
}

void Furniture::column(glm::vec3 base, float radius, float height, int segments, uint32_t material,
                       uint32_t node) {
  auto rim = [&](int k, float y) {
    const float t = 2.0f * float(M_PI) * float(k % segments) / float(segments);
    return glm::vec3(base.x + radius * std::cos(t), y, base.z + radius * std::sin(t));
  };
  const glm::vec3 up(0, height, 0), top = base + up;
  for (int k = 0; k < segments; ++k) {
    const glm::vec3 a = rim(k, base.y), c = rim(k + 1, base.y);
    b_.quad(a, up, c - a, material, node);  // up × tangent points out
    b_.triangle(top, c + up, a + up, material, node);
    b_.triangle(base, a, c, material, node);
  }
}

void Furniture::table(glm::vec3 c, glm::vec2 size, bool round, uint32_t node) {
  const float top = 0.75f, thick = 0.04f;
  if (round) {
    column({c.x, c.y + top - thick, c.z}, 0.5f * size.x, thick, 40, wood_, node);
    column(c, 0.05f, top - thick, 16, metal_, node);
    column(c, 0.25f, 0.02f, 24, metal_, node);
    return;
  }
  block(span({c.x - size.x / 2, c.y + top - thick, c.z - size.y / 2},
             {c.x + size.x / 2, c.y + top, c.z + size.y / 2}),
        wood_, node, 0.25f);
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      column({c.x + sx * (size.x / 2 - 0.07f), c.y, c.z + sz * (size.y / 2 - 0.07f)}, 0.025f, top - thick, 12,
             wood_, node);
}

void Furniture::chair(glm::vec3 c, Facing f, uint32_t node) {
  const float seat = 0.45f, w = 0.44f;
  block(facingBox(c, f, w, w, c.y + seat - 0.04f, c.y + seat), wood_, node);
  block(facingBox(c - toward(f) * (w / 2 - 0.02f), f, w, 0.04f, c.y + seat, c.y + 0.9f), wood_, node);
  const glm::vec3 d = toward(f), side(std::abs(d.z), 0, std::abs(d.x));
  for (float s : {-1.0f, 1.0f})
    for (float t : {-1.0f, 1.0f})
      column(c + (w / 2 - 0.03f) * (s * side + t * d), 0.018f, seat - 0.04f, 10, wood_, node);
}

void Furniture::bed(glm::vec3 corner, glm::vec2 size, bool headAtMinusX, uint32_t node) {
  const glm::vec3 far = corner + glm::vec3(size.x, 0, size.y);
  block(span(corner + glm::vec3(0, 0.1f, 0), far + glm::vec3(0, 0.3f, 0)), wood_, node);
  block(span(corner + glm::vec3(0.02f, 0.3f, 0.02f), far + glm::vec3(-0.02f, 0.52f, -0.02f)), white_, node,
        0.1f);
  for (float x : {corner.x + 0.05f, far.x - 0.05f})
    for (float z : {corner.z + 0.05f, far.z - 0.05f}) column({x, corner.y, z}, 0.03f, 0.1f, 12, wood_, node);
  const float headX = headAtMinusX ? corner.x : far.x, inward = headAtMinusX ? 1.0f : -1.0f;
  block(span({headX, corner.y, corner.z}, {headX - inward * 0.05f, corner.y + 1.0f, far.z}), wood_, node,
        0.1f);
  const int pillows = size.y > 1.2f ? 2 : 1;
  const float pw = (size.y - 0.2f) / float(pillows);
  for (int k = 0; k < pillows; ++k) {
    const float z0 = corner.z + 0.1f + float(k) * pw;
    block(span({headX + inward * 0.08f, corner.y + 0.52f, z0 + 0.03f},
               {headX + inward * 0.48f, corner.y + 0.64f, z0 + pw - 0.03f}),
          white_, node, 0.05f);
  }
}

void Furniture::sofa(glm::vec3 c, glm::vec2 size, Facing f, uint32_t node) {
  const glm::vec3 d = toward(f), side(std::abs(d.z), 0, std::abs(d.x));
  const float along = size.x, deep = size.y;
  // Pieces that touch are not both cut into quads: two grids that meet would give coincident faces.
  block(facingBox(c, f, along, deep, c.y + 0.08f, c.y + 0.25f), fabric_, node);
  block(facingBox(c - d * (deep / 2 - 0.1f), f, along - 0.4f, 0.2f, c.y + 0.25f, c.y + 0.85f), fabric_, node,
        0.1f);
  for (float s : {-1.0f, 1.0f})
    block(facingBox(c + side * s * (along / 2 - 0.1f), f, 0.2f, deep, c.y + 0.25f, c.y + 0.62f), fabric_,
          node);
  const int cushions = 3;
  const float cw = (along - 0.4f) / float(cushions);
  for (int k = 0; k < cushions; ++k) {
    const glm::vec3 at = c + side * (-(along / 2 - 0.2f) + (float(k) + 0.5f) * cw) + d * 0.1f;
    block(facingBox(at, f, cw - 0.02f, deep - 0.22f, c.y + 0.25f, c.y + 0.42f), fabric_, node, 0.1f);
  }
  for (float s : {-1.0f, 1.0f})
    for (float t : {-1.0f, 1.0f})
      column(c + s * side * (along / 2 - 0.06f) + t * d * (deep / 2 - 0.06f), 0.025f, 0.08f, 12, metal_,
             node);
}

void Furniture::bookshelf(const Box3& unit, int shelves, Facing f, uint32_t seed, uint32_t node) {
  const glm::vec3 d = toward(f);
  const int along = std::abs(d.x) > 0 ? 2 : 0;  // the axis the shelf runs along
  const float board = 0.025f;
  // Sides, back (on the side away from `facing`) and boards.
  Box3 back = unit;
  if (d[2 - along] > 0)
    back.hi[2 - along] = back.lo[2 - along] + 0.02f;
  else
    back.lo[2 - along] = back.hi[2 - along] - 0.02f;
  block(back, wood_, node);
  for (int s : {0, 1}) {
    Box3 sideBoard = unit;
    if (s == 0)
      sideBoard.hi[along] = unit.lo[along] + board;
    else
      sideBoard.lo[along] = unit.hi[along] - board;
    block(sideBoard, wood_, node);
  }
  const float shelfGap = (unit.hi.y - unit.lo.y) / float(shelves);
  uint32_t state = seed * 2654435761u + 1u;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (int k = 0; k < shelves; ++k) {
    Box3 boardBox = unit;
    boardBox.lo[along] += board, boardBox.hi[along] -= board;
    boardBox.lo.y = unit.lo.y + float(k) * shelfGap;
    boardBox.hi.y = boardBox.lo.y + board;
    block(boardBox, wood_, node);
    // Books standing on this board from one side to the other, gaps now and then.
    float at = boardBox.lo[along] + 0.01f;
    while (true) {
      const float thick = 0.02f + 0.03f * next(), tall = (0.6f + 0.35f * next()) * (shelfGap - board - 0.02f);
      if (at + thick > boardBox.hi[along] - 0.01f) break;
      if (next() < 0.08f) {
        at += 0.05f;
        continue;
      }
      Box3 book = boardBox;
      book.lo[along] = at, book.hi[along] = at + thick;
      book.lo.y = boardBox.hi.y, book.hi.y = boardBox.hi.y + tall;
      const float depth = book.hi[2 - along] - book.lo[2 - along];
      const float inset = (0.1f + 0.15f * next()) * depth;
      if (d[2 - along] > 0)
        book.lo[2 - along] += 0.02f + 0.01f, book.hi[2 - along] -= inset;
      else
        book.hi[2 - along] -= 0.03f, book.lo[2 - along] += inset;
      block(book, books_[size_t(next() * 2.999f)], node);
      at += thick + 0.002f;
    }
  }
}

void Furniture::cabinets(const Box3& run, int doors, Facing f, uint32_t node) {
  const glm::vec3 d = toward(f);
  const int along = std::abs(d.x) > 0 ? 2 : 0;
  Box3 body = run;
  body.hi.y = run.hi.y - 0.04f;
  body.lo.y = run.lo.y + 0.1f;
  block(body, white_, node, 0.3f);
  Box3 plinth = body;
  plinth.lo.y = run.lo.y, plinth.hi.y = body.lo.y;
  if (d[2 - along] > 0)
    plinth.hi[2 - along] -= 0.06f;
  else
    plinth.lo[2 - along] += 0.06f;
  block(plinth, wood_, node);
  Box3 top = run;
  top.lo.y = body.hi.y;
  block(top, wood_, node);
  const float front = d[2 - along] > 0 ? run.hi[2 - along] : run.lo[2 - along];
  const float width = (run.hi[along] - run.lo[along]) / float(doors);
  for (int k = 0; k < doors; ++k) {
    glm::vec3 knob;
    knob[along] = run.lo[along] + (float(k) + 0.8f) * width;
    knob[2 - along] = front + 0.02f * d[2 - along];
    knob.y = body.hi.y - 0.15f;
    column(knob, 0.012f, 0.1f, 8, metal_, node);
  }
}

void Furniture::balustrade(const std::vector<glm::vec3>& path, float height, float spacing, uint32_t node) {
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const glm::vec3 from = path[i], to = path[i + 1], step = to - from;
    const int n = std::max(1, int(std::round(glm::length(step) / spacing)));
    for (int k = i == 0 ? 0 : 1; k <= n; ++k)  // a corner's spindle once
      column(from + step * (float(k) / float(n)), 0.02f, height - 0.05f, 8, wood_, node);
    const glm::vec3 lo = glm::min(from, to) - glm::vec3(0.03f, 0, 0.03f),
                    hi = glm::max(from, to) + glm::vec3(0.03f, 0, 0.03f);
    block(span({lo.x, from.y + height - 0.05f, lo.z}, {hi.x, from.y + height, hi.z}), wood_, node, 0.2f);
  }
}

void Furniture::pendant(glm::vec3 onCeiling, float drop, uint32_t node) {
  column(onCeiling - glm::vec3(0, 0.03f, 0), 0.06f, 0.03f, 24, white_, node);
  column(onCeiling - glm::vec3(0, drop, 0), 0.004f, drop - 0.03f, 6, metal_, node);
}

}  // namespace cpgi
