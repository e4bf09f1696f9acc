#include "radiosity/lightmap/finite_result.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace cpgi {

void requireFiniteResult(const std::string& where, const LightmapAtlas& atlas,
                         std::span<const glm::vec3> radiosity,
                         std::span<const std::pair<const char*, double>> totals) {
  size_t bad = 0, first = radiosity.size();
  for (size_t i = 0; i < radiosity.size() && i < atlas.patch.size(); ++i)
    if (atlas.patch[i] >= 0 &&
        !(std::isfinite(radiosity[i].x) && std::isfinite(radiosity[i].y) && std::isfinite(radiosity[i].z))) {
      if (bad++ == 0) first = i;
    }
  std::ostringstream problem;
  for (const auto& [name, value] : totals)
    if (!std::isfinite(value))
      problem << (problem.tellp() > 0 ? ", " : "") << name << " energy " << value << " W";
  if (bad > 0)
    problem << (problem.tellp() > 0 ? ", " : "") << bad << " texel" << (bad == 1 ? "" : "s")
            << " not finite (the first at " << first % atlas.width << "," << first / atlas.width << ")";
  if (problem.tellp() > 0)
    throw InputError(where, "the solve went non-finite (" + problem.str() +
                                "): the scene's numbers overflow float arithmetic; nothing was written");
}

}  // namespace cpgi
