#include "radiosity/lightmap/bounce_limit.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cpgi {

std::string BounceEstimate::describe() const {
  std::ostringstream s;
  s << "mean albedo " << albedo << ": light would bounce "
    << (std::isinf(bounces) ? std::string("for ever") : "about " + std::to_string(int(bounces)) + " times");
  return s.str();
}

BounceEstimate estimateBounces(const LightmapAtlas& atlas, double share) {
  BounceEstimate e;
  double weighted = 0.0, area = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0) {
      const glm::vec3& a = atlas.albedo[i];
      weighted += double(atlas.area[i]) * std::max({a.r, a.g, a.b});
      area += atlas.area[i];
    }
  e.albedo = area > 0.0 ? weighted / area : 0.0;
  e.bounces = e.albedo >= 1.0 ? INFINITY : e.albedo > 0.0 ? std::log(share) / std::log(e.albedo) : 0.0;
  return e;
}

}  // namespace cpgi
