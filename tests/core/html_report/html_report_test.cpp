// report.html's writer: the page carries its data intact (lightmap, cells, portals, report.json) and
// nothing in the data can end its script elements early; each cell's view is the camera given for it.
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/cell_palette.h"
#include "core/html_report/html_report.h"

namespace cpgi {
namespace {

Triangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  Triangle t;
  t.p = {a, b, c};
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  t.n = {n, n, n};
  return t;
}

// A box room [x0, x0+w] × [0, h] × [0, d]: floor (up), ceiling (down) and two walls, as cell `name`.
void addRoom(Scene& scene, CellGraph& graph, const std::string& name, float x0, float w, float h, float d) {
  Cell cell{name, {}, {}};
  const auto add = [&](const Triangle& t) {
    cell.triangles.push_back(uint32_t(scene.triangles.size()));
    scene.triangles.push_back(t);
  };
  const float x1 = x0 + w;
  add(triangle({x0, 0, 0}, {x0, 0, d}, {x1, 0, 0}));  // floor, normal +y
  add(triangle({x1, 0, 0}, {x0, 0, d}, {x1, 0, d}));
  add(triangle({x0, h, 0}, {x1, h, 0}, {x0, h, d}));  // ceiling, normal -y
  add(triangle({x0, 0, 0}, {x1, 0, 0}, {x1, h, 0}));  // wall
  graph.cells.push_back(cell);
}

std::string scriptText(const std::string& page, const std::string& id) {
  const std::string open = "<script id=\"" + id + "\"";
  const size_t start = page.find('>', page.find(open)) + 1;
  return page.substr(start, page.find("</script>", start) - start);
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(HtmlReport, PageCarriesItsDataIntact) {
  Scene scene;
  CellGraph graph;
  addRoom(scene, graph, "hall", 0.0f, 4.0f, 3.0f, 2.0f);
  addRoom(scene, graph, "</script><b>kitchen", 4.0f, 2.0f, 3.0f, 2.0f);
  PortalQuad door;
  door.name = "portal:hall:kitchen";
  door.corners = {glm::vec3(4, 0, 0.5f), glm::vec3(4, 0, 1.5f), glm::vec3(4, 2, 1.5f), glm::vec3(4, 2, 0.5f)};
  door.cellA = 0, door.cellB = 1;
  graph.portals.push_back(door);

  ReportLightmap lightmap;
  lightmap.width = 3, lightmap.height = 2;
  lightmap.radiosity = {glm::vec3(1, 2, 3), glm::vec3(0.5f), glm::vec3(0),
                        glm::vec3(4),       glm::vec3(0),    glm::vec3(1)};
  lightmap.area = {0.5f, 0.5f, 0.0f, 0.25f, 0.0f, 0.25f};
  lightmap.cellOfTexel = {0, 0, -1, 1, -1, 1};

  HtmlReportInput input;
  input.title = "bake of </script>.glb";
  input.kind = "bake";
  input.report = {{"method", "cells"}, {"note", "</SCRIPT> and </script>"}};
  input.glb = std::string("glTF\x02\0\0\0", 8);
  Camera inHall;
  inHall.name = "hall";
  inHall.position = {1, 1.6f, 1};
  inHall.forward = {1, 0, 0};
  input.cellCameras = {inHall};
  input.cells = &graph;
  input.lightmap = &lightmap;
  const std::string page = renderHtmlReport(input);

  // Exactly the page's three script elements end: data, glb, viewer.
  EXPECT_EQ(count(page, "</script>"), 3u);
  EXPECT_EQ(count(page, "@CPGI_"), 0u);
  EXPECT_EQ(scriptText(page, "cpgi-glb"), "Z2xURgIAAAA=");

  const nlohmann::json data = nlohmann::json::parse(scriptText(page, "cpgi-data"));
  EXPECT_EQ(data["title"], input.title);
  EXPECT_EQ(data["report"], input.report);
  EXPECT_EQ(data["lightmap"]["width"], 3);
  EXPECT_EQ(data["lightmap"]["height"], 2);
  // RGBA half floats (8 bytes a texel), int16 cells, float32 areas, in base64.
  EXPECT_EQ(data["lightmap"]["rgb"].get<std::string>().size(), 4 * ((6 * 8 + 2) / 3));
  EXPECT_EQ(data["lightmap"]["cell"].get<std::string>().size(), 4 * ((6 * 2 + 2) / 3));
  ASSERT_EQ(data["cells"].size(), 2u);
  EXPECT_EQ(data["cells"][1]["name"], graph.cells[1].name);
  EXPECT_EQ(data["cells"][0]["texels"], 2);
  EXPECT_DOUBLE_EQ(data["cells"][0]["area_m2"].get<double>(), 1.0);
  // Σ B·A with B the mean of R, G, B: (2 × 0.5) + (0.5 × 0.5).
  EXPECT_NEAR(data["cells"][0]["power_w"].get<double>(), 1.25, 1e-9);
  EXPECT_NEAR(data["cells"][1]["power_w"].get<double>(), 4 * 0.25 + 1 * 0.25, 1e-9);
  // The hall's view from its camera; the kitchen has none.
  EXPECT_EQ(data["cells"][0]["eye"], nlohmann::json({1.0, 1.6f, 1.0}));
  EXPECT_EQ(data["cells"][0]["look"], nlohmann::json({2.0, 1.6f, 1.0}));
  EXPECT_FALSE(data["cells"][1].contains("eye"));
  ASSERT_EQ(data["portals"].size(), 1u);
  EXPECT_EQ(data["portals"][0]["cell_b"], graph.cells[1].name);
  EXPECT_EQ(data["portals"][0]["corners"][2], nlohmann::json({4.0, 2.0, 1.5}));
}

// Issue 49, item 7: a name "<!--<script>" put the HTML parser in its double-escaped state, where the data
// element's end tag no longer ends it and the page's own script became data. Inside the inline JSON no
// '<' is left at all (nor '>', '&', U+2028, U+2029), and the data reads back the same.
TEST(HtmlReport, NoNameCanOpenACommentOrScriptInsideTheInlineData) {
  Scene scene;
  CellGraph graph;
  const std::vector<std::string> names = {"<!--<script>", "<script>alert(1)</script>", "a\u2028b\u2029c</",
                                          "<img src=x onerror=alert(1)>", "&lt;not an entity&gt;"};
  for (size_t i = 0; i < names.size(); ++i)
    addRoom(scene, graph, names[i], 4.0f * float(i), 4.0f, 3.0f, 2.0f);
  HtmlReportInput input;
  input.title = "<!--<script>";
  input.kind = "bake";
  input.report = {{"warnings", names}, {"<!--", "<script"}};
  input.glb = "glTF";
  input.cells = &graph;
  const std::string page = renderHtmlReport(input);
  EXPECT_EQ(count(page, "</script>"), 3u);
  EXPECT_EQ(count(page, "<!--"), 0u);
  EXPECT_EQ(count(page, "<script"), 3u);  // the page's own three elements
  const std::string inline_ = scriptText(page, "cpgi-data");
  for (const char* forbidden : {"<", ">", "&", "\u2028", "\u2029"})
    EXPECT_EQ(inline_.find(forbidden), std::string::npos) << forbidden;
  const nlohmann::json data = nlohmann::json::parse(inline_);
  EXPECT_EQ(data["title"], input.title);
  EXPECT_EQ(data["report"], input.report);
  ASSERT_EQ(data["cells"].size(), names.size());
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(data["cells"][i]["name"], names[i]);
}

TEST(HtmlReport, RefusesALightmapOfTheWrongSize) {
  ReportLightmap lightmap;
  lightmap.width = 2, lightmap.height = 2;
  lightmap.radiosity.assign(3, glm::vec3(1.0f));
  lightmap.area.assign(4, 1.0f);
  HtmlReportInput input;
  input.lightmap = &lightmap;
  EXPECT_THROW(renderHtmlReport(input), std::invalid_argument);
}

// One palette for every output (issue 50 item 4): each cell reaches the page with the colour
// decomposition.png paints it, by its index, as sRGB hex; distinct cells get distinct colours.
TEST(HtmlReport, EachCellCarriesThePicturesColour) {
  Scene scene;
  CellGraph graph;
  for (int i = 0; i < 6; ++i)
    addRoom(scene, graph, "room" + std::to_string(i), 4.0f * float(i), 4.0f, 3.0f, 2.0f);
  HtmlReportInput input;
  input.cells = &graph;
  const nlohmann::json data = nlohmann::json::parse(scriptText(renderHtmlReport(input), "cpgi-data"));
  ASSERT_EQ(data["cells"].size(), 6u);
  std::set<std::string> seen;
  for (int i = 0; i < 6; ++i) {
    const std::string hex = data["cells"][size_t(i)]["colour"];
    EXPECT_EQ(hex, cellColourHex(i));
    EXPECT_TRUE(seen.insert(hex).second) << hex;
    // The hex is the linear colour the picture writes, sRGB-encoded (within a step of 8 bits).
    const glm::vec3 linear = cellColour(i);
    const float red = float(std::stoi(hex.substr(1, 2), nullptr, 16)) / 255.0f;
    const float encoded =
        linear.r <= 0.0031308f ? 12.92f * linear.r : 1.055f * std::pow(linear.r, 1.0f / 2.4f) - 0.055f;
    EXPECT_NEAR(red, encoded, 0.5f / 255.0f + 1e-6f);
  }
  EXPECT_EQ(cellColourHex(-1), "#a0a0a0");  // no cell: the page's grey (0.35 linear)
}

// The overview frames the building, not a terrain many times its size: the rooms' triangles when cells
// are known (the outside's left out), else the triangles within the middle of the triangles' centres.
TEST(HtmlReport, TheOverviewFramesTheBuildingNotTheTerrain) {
  Scene scene;
  CellGraph graph;
  addRoom(scene, graph, "hall", 0.0f, 4.0f, 3.0f, 2.0f);
  addRoom(scene, graph, "kitchen", 4.0f, 2.0f, 3.0f, 2.0f);
  addRoom(scene, graph, "outside", -200.0f, 400.0f, 0.1f, 400.0f);  // the terrain
  Bounds b = buildingBounds(scene, &graph);
  EXPECT_NEAR(b.lo.x, 0.0f, 1e-5f);
  EXPECT_NEAR(b.hi.x, 6.0f, 1e-5f);
  EXPECT_NEAR(b.hi.z, 2.0f, 1e-5f);
  // Without cells: many small triangles of the building and two of a huge ground plane.
  Scene raw;
  CellGraph none;
  for (int i = 0; i < 30; ++i) addRoom(raw, none, "r", 0.5f * float(i), 0.5f, 3.0f, 8.0f);
  raw.triangles.push_back(triangle({-500, -0.1f, -500}, {-500, -0.1f, 500}, {500, -0.1f, -500}));
  raw.triangles.push_back(triangle({500, -0.1f, -500}, {-500, -0.1f, 500}, {500, -0.1f, 500}));
  b = buildingBounds(raw, nullptr);
  EXPECT_NEAR(b.lo.x, 0.0f, 1e-5f);
  EXPECT_NEAR(b.hi.x, 15.0f, 1e-5f);
  EXPECT_NEAR(b.hi.z, 8.0f, 1e-5f);
  // The page carries it for the viewer.
  HtmlReportInput input;
  input.frame = b;
  const nlohmann::json data = nlohmann::json::parse(scriptText(renderHtmlReport(input), "cpgi-data"));
  EXPECT_EQ(data["frame"][1], nlohmann::json({15.0, 3.0, 8.0}));
}

}  // namespace
}  // namespace cpgi
