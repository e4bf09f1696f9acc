// Faces cut where other geometry runs through them (core/contact_cuts.h): the contact lines become edges,
// the pieces inside solids go, everything else stays as it was.
#include "core/contact_cuts.h"

#include <gtest/gtest.h>

namespace cpgi {
namespace {

// The rectangle from `o` along `u` and `v` as two triangles facing u × v.
void quad(Scene& s, glm::vec3 o, glm::vec3 u, glm::vec3 v, uint32_t material = 0, uint32_t node = 0) {
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  Triangle a{{o, o + u, o + u + v}, {n, n, n}, material, node};
  Triangle b{{o, o + u + v, o + v}, {n, n, n}, material, node};
  s.triangles.push_back(a), s.triangles.push_back(b);
}

// The closed box [lo, hi], its faces outward.
void box(Scene& s, glm::vec3 lo, glm::vec3 hi, uint32_t node = 1) {
  const glm::vec3 d = hi - lo, x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
  quad(s, lo, z, y, 0, node), quad(s, lo + x, y, z, 0, node);  // −x, +x
  quad(s, lo, x, z, 0, node), quad(s, lo + y, z, x, 0, node);  // −y, +y
  quad(s, lo, y, x, 0, node), quad(s, lo + z, x, y, 0, node);  // −z, +z
}

double area(const Scene& s, uint32_t node) {
  double a = 0.0;
  for (const Triangle& t : s.triangles)
    if (t.node == node) a += t.area();
  return a;
}

Scene twoNodes() {
  Scene s;
  s.materials.push_back(Material{});
  s.materials.push_back(Material{.name = "wall", .albedo = glm::vec3(0.3f)});
  s.nodePaths = {"face", "solid"};
  return s;
}

// A wall face (x = 0.5, facing +x) from y −1 to 1 through a 20 cm slab (y 0 to 0.2): cut at the slab's two
// faces, the strip inside dropped, its material, node and cell kept.
// The cut at the contacts leaves `s` as it was: no face cut, every triangle where it was.
void expectNothingCut(Scene& s) {
  const std::vector<Triangle> before = s.triangles;
  CellGraph cells;
  const ContactCuts c = cutAtContacts(s, cells);
  EXPECT_EQ(c.facesCut, 0u);
  ASSERT_EQ(s.triangles.size(), before.size());
  for (size_t i = 0; i < before.size(); ++i) EXPECT_EQ(s.triangles[i].p, before[i].p);
}

TEST(ContactCuts, AFaceThroughASlabIsCutAtItsFacesAndTheStripInsideDropped) {
  Scene s = twoNodes();
  quad(s, {0.5f, -1.0f, 0.2f}, {0, 2, 0}, {0, 0, 0.6f}, 1, 0);
  box(s, {0, 0, 0}, {1, 0.2f, 1});
  CellGraph cells;
  cells.cells.push_back(Cell{"room", {0, 1}, {}});
  const ContactCuts c = cutAtContacts(s, cells);
  EXPECT_EQ(c.buriedPieces, 1u);
  EXPECT_NEAR(c.buriedArea, 0.2 * 0.6, 1e-5);
  EXPECT_NEAR(area(s, 0), 1.8 * 0.6, 1e-5);
  // The strip dropped is kept aside, where it was, for the decomposition's solid.
  double buried = 0.0;
  for (const Triangle& t : s.buriedPieces) {
    buried += t.area();
    EXPECT_EQ(t.node, 0u);
    EXPECT_NEAR(t.centroid().x, 0.5f, 1e-5f);
    for (const glm::vec3& p : t.p) EXPECT_TRUE(p.y >= -1e-5f && p.y <= 0.2f + 1e-5f) << p.y;
  }
  EXPECT_NEAR(buried, 0.2 * 0.6, 1e-5);
  size_t faceTriangles = 0;
  for (const Triangle& t : s.triangles) {
    if (t.node != 0) continue;
    ++faceTriangles;
    EXPECT_EQ(t.material, 1u);
    EXPECT_GT(t.geometricNormal().x, 0.99f);
    const float lo = std::min({t.p[0].y, t.p[1].y, t.p[2].y}), hi = std::max({t.p[0].y, t.p[1].y, t.p[2].y});
    EXPECT_TRUE(hi <= 1e-5f || lo >= 0.2f - 1e-5f) << "a piece straddles the slab: y " << lo << " to " << hi;
  }
  EXPECT_EQ(faceTriangles, 4u);  // two rectangles, quads again
  ASSERT_EQ(cells.cells[0].triangles.size(), 4u);
  for (uint32_t i : cells.cells[0].triangles) EXPECT_EQ(s.triangles[i].node, 0u);
}

// A wall (a closed box) across a floor from edge to edge: the floor cut at its two faces, the strip under it
// dropped, as is the foot of a box standing inside the floor.
TEST(ContactCuts, AWallAcrossAFloorAndABoxStandingOnItCutIt) {
  Scene s = twoNodes();
  quad(s, {0, 0, 0}, {0, 0, 4}, {4, 0, 0});  // facing +y
  box(s, {1.9f, -0.3f, -1}, {2.1f, 2.5f, 5});
  box(s, {0.5f, 0, 0.5f}, {1.5f, 1, 1.5f});
  CellGraph cells;
  cutAtContacts(s, cells);
  EXPECT_NEAR(area(s, 0), 16.0 - 0.2 * 4.0 - 1.0, 1e-4);
  for (const Triangle& t : s.triangles)
    if (t.node == 0) {
      const float lo = std::min({t.p[0].x, t.p[1].x, t.p[2].x}),
                  hi = std::max({t.p[0].x, t.p[1].x, t.p[2].x});
      EXPECT_TRUE(hi <= 1.9f + 1e-5f || lo >= 2.1f - 1e-5f)
          << "a floor piece under the wall: x " << lo << " to " << hi;
    }
}

// The floor's pieces of node 0 outside the rectangle [lo, hi] of x and z (a foot), none inside it.
void expectFloorAroundFoot(const Scene& s, glm::vec2 lo, glm::vec2 hi) {
  size_t pieces = 0;
  for (const Triangle& t : s.triangles) {
    if (t.node != 0) continue;
    ++pieces;
    EXPECT_GT(t.geometricNormal().y, 0.99f);
    const glm::vec3 c = t.centroid();
    EXPECT_FALSE(c.x > lo.x && c.x < hi.x && c.z > lo.y && c.z < hi.y)
        << "a floor piece under the foot at " << c.x << ", " << c.z;
    for (const glm::vec3& p : t.p) {  // no piece straddles the foot's outline
      const bool inX = p.x > lo.x + 1e-4f && p.x<hi.x - 1e-4f, inZ = p.z> lo.y + 1e-4f && p.z < hi.y - 1e-4f;
      EXPECT_FALSE(inX && inZ) << "a corner under the foot at " << p.x << ", " << p.z;
    }
  }
  EXPECT_EQ(pieces % 2, 0u);  // rectangles, quads again
}

// A cabinet standing on a floor (its foot on the floor's plane, or a few millimetres above it): the floor
// is cut along its outline into rectangles, the piece under it gone, the floor round it whole.
TEST(ContactCuts, ABoxStandingOnAFloorTakesTheFloorUnderItAway) {
  for (const float gap : {0.0f, 0.003f}) {
    Scene s = twoNodes();
    quad(s, {0, 0, 0}, {0, 0, 4}, {4, 0, 0}, 1, 0);  // facing +y
    box(s, {1.0f, gap, 1.5f}, {2.0f, 0.8f, 2.1f});
    CellGraph cells;
    cells.cells.push_back(Cell{"room", {0, 1}, {}});
    const ContactCuts c = cutAtContacts(s, cells);
    EXPECT_EQ(c.facesCut, 1u) << "gap " << gap;
    EXPECT_NEAR(c.buriedArea, 0.6, 1e-4) << "gap " << gap;
    EXPECT_NEAR(area(s, 0), 16.0 - 0.6, 1e-4) << "gap " << gap;
    expectFloorAroundFoot(s, {1.0f, 1.5f}, {2.0f, 2.1f});
    for (const Triangle& t : s.triangles) {
      if (t.node == 0) {
        EXPECT_EQ(t.material, 1u);
      }
    }
    size_t inCell = 0;
    for (uint32_t i : cells.cells[0].triangles) inCell += s.triangles[i].node == 0;
    EXPECT_EQ(inCell, cells.cells[0].triangles.size());
    EXPECT_GT(inCell, 2u);
  }
}

// A wardrobe against a wall, standing on the floor 2 mm off the wall: the wall behind it and the floor under
// it go, and no 2 mm sliver of floor stays behind it.
TEST(ContactCuts, AWardrobeAgainstAWallTakesTheWallBehindItAndTheFloorUnderItAway) {
  Scene s = twoNodes();
  quad(s, {0, 0, 0}, {0, 0, 4}, {4, 0, 0});           // floor, facing +y
  quad(s, {0, 0, 0}, {0, 2.5f, 0}, {0, 0, 4}, 0, 2);  // wall x = 0, facing +x
  box(s, {0.002f, 0, 1.0f}, {0.6f, 2.0f, 2.2f});
  CellGraph cells;
  const ContactCuts c = cutAtContacts(s, cells);
  EXPECT_EQ(c.facesCut, 2u);
  EXPECT_NEAR(area(s, 0), 16.0 - 0.6 * 1.2, 1e-4);       // the floor: to the wall's foot
  EXPECT_NEAR(area(s, 2), 2.5 * 4.0 - 2.0 * 1.2, 1e-4);  // the wall: the wardrobe 2 mm off it
  expectFloorAroundFoot(s, {0.0f, 1.0f}, {0.6f, 2.2f});
  for (const Triangle& t : s.triangles)
    if (t.node == 2) {
      const glm::vec3 m = t.centroid();
      EXPECT_FALSE(m.y < 2.0f && m.z > 1.0f && m.z < 2.2f) << "a wall piece behind the wardrobe";
    }
}

// A box near a floor but not on it (2 cm up: a shelf's underside), a table's leg on it (5 cm square), and a
// box under the floor's back: the floor stays as it was.
// A triangle whose edge crosses the floor's plane within the stand-off, shorter than twice it, is no foot:
// the edge projects to a point (CGAL asserted on that degenerate segment, an internal error on three
// OpenArena maps: oa_dm5, kaos, ctf_inyard).
TEST(ContactCuts, AnEdgeAcrossTheFloorWithinTheStandOffIsNoFoot) {
  Scene s = twoNodes();
  quad(s, {0, 0, 0}, {0, 0, 2}, {2, 0, 0});  // the floor, facing +y
  Triangle t{{glm::vec3(1.0f, 0.002f, 1.0f), glm::vec3(1.0f, -0.003f, 1.0f), glm::vec3(1.0f, 1.0f, 1.5f)}};
  t.n.fill(t.geometricNormal());
  s.triangles.push_back(t);
  CellGraph cells;
  EXPECT_NO_THROW(cutAtContacts(s, cells));
}

TEST(ContactCuts, AFloorNearAFootOrUnderALegIsNotCut) {
  Scene s = twoNodes();
  quad(s, {0, 0, 0}, {0, 0, 4}, {4, 0, 0});  // facing +y
  box(s, {1.0f, 0.02f, 1.0f}, {2.0f, 0.8f, 2.0f});
  box(s, {3.0f, 0.0f, 3.0f}, {3.05f, 0.7f, 3.05f});
  box(s, {0.5f, -1.0f, 2.5f}, {1.5f, 0.0f, 3.5f});
  expectNothingCut(s);
}

// A floor that is one loose triangle (no quad) is cut by a constrained triangulation in its plane.
TEST(ContactCuts, ALooseTriangleIsCutByATriangulationInItsPlane) {
  Scene s = twoNodes();
  s.triangles.push_back(Triangle{{glm::vec3(0, 0, 0), glm::vec3(0, 0, 4), glm::vec3(4, 0, 0)},
                                 {glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)}});
  box(s, {1.0f, -0.3f, -1}, {1.5f, 1, 5});
  CellGraph cells;
  const ContactCuts c = cutAtContacts(s, cells);
  EXPECT_EQ(c.buriedPieces > 0, true);
  EXPECT_NEAR(area(s, 0), 8.0 - 1.375, 1e-4);  // the strip 1 < x < 1.5 of x + z < 4 gone
  for (const Triangle& t : s.triangles)
    if (t.node == 0) {
      EXPECT_GT(t.geometricNormal().y, 0.99f);
      EXPECT_FALSE(t.centroid().x > 1.0f && t.centroid().x < 1.5f);
    }
}

// A 5 cm panel standing on a floor: its ends too short to cut, its long sides cut the floor into a strip
// that runs past its ends; that strip is not under the panel and stays, so the floor has no hole.
TEST(ContactCuts, APanelsStripPastItsEndsStays) {
  Scene s = twoNodes();
  quad(s, {0, 0, 0}, {0, 0, 4}, {4, 0, 0});  // facing +y
  box(s, {1.0f, 0, 2.0f}, {3.0f, 1.5f, 2.05f});
  CellGraph cells;
  cutAtContacts(s, cells);
  EXPECT_NEAR(area(s, 0), 16.0, 1e-4);
}

// A loose-triangle floor under a box standing on it: cut by the triangulation along the foot, the area
// under it gone exactly.
TEST(ContactCuts, ABoxOnALooseTriangleIsCutOutByTheTriangulation) {
  Scene s = twoNodes();
  s.triangles.push_back(Triangle{{glm::vec3(0, 0, 0), glm::vec3(0, 0, 4), glm::vec3(4, 0, 0)},
                                 {glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)}});
  box(s, {0.5f, 0, 0.5f}, {1.5f, 1, 1.5f});
  CellGraph cells;
  cutAtContacts(s, cells);
  EXPECT_NEAR(area(s, 0), 8.0 - 1.0, 1e-4);
  for (const Triangle& t : s.triangles)
    if (t.node == 0) {
      const glm::vec3 c = t.centroid();
      EXPECT_FALSE(c.x > 0.5f && c.x < 1.5f && c.z > 0.5f && c.z < 1.5f);
    }
}

// Faces that only meet along their edges (a closed box's own faces, two boxes apart) stay as they were.
TEST(ContactCuts, FacesMeetingOnlyAtTheirEdgesStayAsTheyWere) {
  Scene s = twoNodes();
  box(s, {0, 0, 0}, {1, 1, 1});
  box(s, {1, 0, 0}, {2, 1, 1});  // touching the first along a whole face
  expectNothingCut(s);
}

}  // namespace
}  // namespace cpgi
