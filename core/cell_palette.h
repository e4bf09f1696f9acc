// One colour per cell, the same in every output: decomposition.png's plans (decomposition/picture.h) and
// report.html's "colour by cell" view and legend (core/html_report: the page gets each cell's colour from
// here rather than choosing its own), keyed by the cell's index in its graph.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace cpgi {

/// A distinct colour for cell `index` (golden-ratio hue steps, so neighbouring indices are far apart in
/// hue), linear RGB in [0, 1]; a neutral grey for a negative index (no cell).
glm::vec3 cellColour(int index);

/// The same colour as a web page writes it: "#rrggbb", sRGB-encoded.
std::string cellColourHex(int index);

}  // namespace cpgi
