#include "core/html_report/html_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/packing.hpp>

#include "core/cell_palette.h"
#include "core/error.h"
#include "core/html_report/embedded_web.h"  // generated: kViewerScript (viewer.js + three.js), kPageTemplate

namespace cpgi {
namespace {

using nlohmann::json;

std::string base64(const void* data, size_t size) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const uint8_t*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    uint32_t n = uint32_t(in[i]) << 16;
    if (i + 1 < size) n |= uint32_t(in[i + 1]) << 8;
    if (i + 2 < size) n |= uint32_t(in[i + 2]);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < size ? table[(n >> 6) & 63] : '=';
    out += i + 2 < size ? table[n & 63] : '=';
  }
  return out;
}

template <class T>
std::string base64(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

// JSON placed inside <script type="application/json">: besides "</", which closes the element, "<!--"
// followed by "<script" would make the HTML parser read past the element's end tag (its "double
// escaped" state), so no '<' may appear at all. Outside strings JSON has none, and inside them \u003c
// means the same to JSON.parse; '>' and '&' likewise, and U+2028/U+2029, which end a line in older
// JavaScript, are written as escapes too.
std::string escapeJsonForScript(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<')
      out += "\\u003c";
    else if (c == '>')
      out += "\\u003e";
    else if (c == '&')
      out += "\\u0026";
    else if (c == '\xe2' && i + 2 < json.size() && json[i + 1] == '\x80' &&
             (json[i + 2] == '\xa8' || json[i + 2] == '\xa9'))
      out += json[i + 2] == '\xa8' ? "\\u2028" : "\\u2029", i += 2;
    else
      out += c;
  }
  return out;
}

// cpgi's own script (viewer.js and three.js) inside <script>: "</" becomes "<\/", the same in its string
// and regular-expression literals, the only places it can occur. "<!--" and "<script" cannot be escaped
// so without knowing where they stand; the code has none, and a change that brings one is refused here.
std::string escapeScript(std::string text) {
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower.find("<!--") != std::string::npos || lower.find("<script") != std::string::npos)
    throw std::logic_error("renderHtmlReport: the viewer script holds \"<!--\" or \"<script\"");
  for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.replace(at, 2, "<\\/");
  return text;
}

// The page template with its markers filled in one pass, so a value can never be taken for a marker.
std::string fillTemplate(const std::string& page,
                         const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  size_t from = 0;
  while (true) {
    size_t at = std::string::npos;
    const std::pair<std::string, std::string>* hit = nullptr;
    for (const auto& v : values) {
      const size_t found = page.find(v.first, from);
      if (found < at) at = found, hit = &v;
    }
    if (!hit) break;
    out.append(page, from, at - from);
    out += hit->second;
    from = at + hit->first.size();
  }
  out.append(page, from, std::string::npos);
  return out;
}

json vec(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

json lightmapJson(const ReportLightmap& lm) {
  const size_t count = size_t(lm.width) * size_t(lm.height);
  if (lm.radiosity.size() != count || lm.area.size() != count ||
      (!lm.cellOfTexel.empty() && lm.cellOfTexel.size() != count) ||
      (!lm.error.empty() && lm.error.size() != count))
    throw std::invalid_argument("renderHtmlReport: lightmap arrays do not match its width × height");
  for (const auto& v : lm.irradianceVector)
    if (!v.empty() && v.size() != count)
      throw std::invalid_argument("renderHtmlReport: lightmap arrays do not match its width × height");
  // Half floats, RGBA: what WebGL 2 filters linearly everywhere; A unused.
  const auto halves = [&](const std::vector<glm::vec3>& values) {
    std::vector<uint16_t> rgba(4 * count);
    for (size_t i = 0; i < count; ++i) {
      const glm::vec3 b = values[i];
      for (int k = 0; k < 3; ++k)
        rgba[4 * i + k] = uint16_t(glm::packHalf1x16(std::isfinite(b[k]) ? b[k] : 0.0f));
      rgba[4 * i + 3] = uint16_t(glm::packHalf1x16(1.0f));
    }
    return base64(rgba);
  };
  json out = {
      {"width", lm.width}, {"height", lm.height}, {"rgb", halves(lm.radiosity)}, {"area", base64(lm.area)}};
  if (!lm.irradianceVector[0].empty())
    out["vector"] = {halves(lm.irradianceVector[0]), halves(lm.irradianceVector[1]),
                     halves(lm.irradianceVector[2])};
  if (!lm.cellOfTexel.empty()) {
    std::vector<int16_t> cell(count);
    for (size_t i = 0; i < count; ++i)
      cell[i] = int16_t(std::clamp(lm.cellOfTexel[i], -1, int(std::numeric_limits<int16_t>::max())));
    out["cell"] = base64(cell);
  }
  if (!lm.error.empty()) out["error"] = base64(lm.error);
  return out;
}

// Per cell: its viewpoint, and what its texels hold (texels, area, Σ B·A over the mean of R, G, B).
json cellsJson(const HtmlReportInput& in) {
  json cells = json::array();
  if (!in.cells) return cells;
  std::vector<size_t> texels(in.cells->cells.size(), 0);
  std::vector<double> area(texels.size(), 0.0), power(texels.size(), 0.0);
  if (in.lightmap)
    for (size_t i = 0; i < in.lightmap->cellOfTexel.size(); ++i) {
      const int c = in.lightmap->cellOfTexel[i];
      if (c < 0 || size_t(c) >= texels.size() || !(in.lightmap->area[i] > 0.0f)) continue;
      const glm::vec3 b = in.lightmap->radiosity[i];
      texels[c] += 1;
      area[c] += in.lightmap->area[i];
      power[c] += double(b.r + b.g + b.b) / 3.0 * in.lightmap->area[i];
    }
  for (size_t c = 0; c < in.cells->cells.size(); ++c) {
    json cell = {{"name", in.cells->cells[c].name}, {"colour", cellColourHex(int(c))}};
    for (const Camera& cam : in.cellCameras)
      if (cam.name == in.cells->cells[c].name)
        cell["eye"] = vec(cam.position), cell["look"] = vec(cam.position + cam.forward);
    if (in.lightmap && !in.lightmap->cellOfTexel.empty())
      cell["texels"] = texels[c], cell["area_m2"] = area[c], cell["power_w"] = power[c];
    cells.push_back(cell);
  }
  return cells;
}

json portalsJson(const CellGraph* graph) {
  json portals = json::array();
  if (!graph) return portals;
  for (const PortalQuad& p : graph->portals) {
    const auto name = [&](int c) {
      return c >= 0 && size_t(c) < graph->cells.size() ? graph->cells[c].name : "";
    };
    portals.push_back(
        {{"name", p.name},
         {"cell_a", name(p.cellA)},
         {"cell_b", name(p.cellB)},
         {"corners", {vec(p.corners[0]), vec(p.corners[1]), vec(p.corners[2]), vec(p.corners[3])}}});
  }
  return portals;
}

// The bounds of the triangles whose centre lies within `box` grown by a quarter of its size, whole.
Bounds trianglesWithin(const Scene& scene, const Bounds& box) {
  const glm::vec3 margin = 0.25f * box.size();
  Bounds out;
  for (const Triangle& t : scene.triangles) {
    const glm::vec3 centre = (t.p[0] + t.p[1] + t.p[2]) / 3.0f;
    if (glm::all(glm::greaterThanEqual(centre, box.lo - margin)) &&
        glm::all(glm::lessThanEqual(centre, box.hi + margin)))
      for (const glm::vec3& q : t.p) out.extend(q);
  }
  return out;
}

}  // namespace

Bounds buildingBounds(const Scene& scene, const CellGraph* cells) {
  Bounds rooms;
  if (cells && !cells->empty()) {
    const std::vector<int> cellOf = cells->cellOfTriangle(scene.triangles.size());
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
      const int c = cellOf[t];
      if (c < 0 || size_t(c) >= cells->cells.size() || cells->cells[size_t(c)].name == "outside") continue;
      for (const glm::vec3& q : scene.triangles[t].p) rooms.extend(q);
    }
    for (const Cell& c : cells->cells)  // rooms given as volumes alone hold no triangles
      if (c.name != "outside")
        for (const Triangle& t : c.volume)
          for (const glm::vec3& q : t.p) rooms.extend(q);
  }
  if (!rooms.empty() || scene.triangles.empty()) return rooms;
  Bounds middle;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<float> centres;
    centres.reserve(scene.triangles.size());
    for (const Triangle& t : scene.triangles)
      centres.push_back((t.p[0][axis] + t.p[1][axis] + t.p[2][axis]) / 3.0f);
    const size_t lo = centres.size() * 2 / 100, hi = centres.size() - 1 - lo;
    std::nth_element(centres.begin(), centres.begin() + long(lo), centres.end());
    middle.lo[axis] = centres[lo];
    std::nth_element(centres.begin(), centres.begin() + long(hi), centres.end());
    middle.hi[axis] = centres[hi];
  }
  const Bounds within = trianglesWithin(scene, middle);
  return within.empty() ? middle : within;
}

std::string renderHtmlReport(const HtmlReportInput& in) {
  json data = {{"kind", in.kind}, {"title", in.title}, {"report", in.report}};
  data["cells"] = cellsJson(in);
  data["portals"] = portalsJson(in.cells);
  if (in.lightmap) data["lightmap"] = lightmapJson(*in.lightmap);
  if (!in.frame.empty()) data["frame"] = {vec(in.frame.lo), vec(in.frame.hi)};
  if (!in.bench.is_null()) data["bench"] = in.bench;
  if (!in.probes.is_null()) data["probes"] = in.probes;
  return fillTemplate(
      embedded::kPageTemplate,
      {{"@CPGI_DATA@", escapeJsonForScript(data.dump(-1, ' ', false, json::error_handler_t::replace))},
       {"@CPGI_GLB@", base64(in.glb.data(), in.glb.size())},
       {"@CPGI_SCRIPT@", escapeScript(embedded::kViewerScript)}});
}

void writeHtmlReport(OutputDir& out, const HtmlReportInput& input) {
  writeFileAtomically(out.file("report.html"), renderHtmlReport(input));
}

std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw SystemError(path + ": cannot read");
  return bytes.str();
}

}  // namespace cpgi
