// The last check before a lightmap is written (issue 15, item 5): a solve or a trace whose figures went
// non-finite (inf or NaN in a texel or an energy total) ends with exit 1 and one line, never with a
// report of null energies and a lightmap of NaN that looks like a success.
#pragma once

#include <span>
#include <string>
#include <utility>

#include <glm/vec3.hpp>

#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// Throws InputError(where, ...) naming how many valid texels of `radiosity` (one per atlas texel) and
/// which of the named `totals` (e.g. {"emitted", W}) are not finite. Padding texels (patch < 0) are not
/// looked at: they are filled from their neighbours later.
void requireFiniteResult(const std::string& where, const LightmapAtlas& atlas,
                         std::span<const glm::vec3> radiosity,
                         std::span<const std::pair<const char*, double>> totals = {});

}  // namespace cpgi
