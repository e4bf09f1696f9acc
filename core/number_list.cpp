#include "core/number_list.h"

#include <cmath>
#include <exception>
#include <sstream>

namespace cpgi {

std::optional<std::vector<float>> parseNumberList(const std::string& text) {
  std::stringstream in(text);
  std::string part;
  std::vector<float> values;
  while (std::getline(in, part, ',')) {
    size_t used = 0;
    float v = 0.0f;
    try {
      v = std::stof(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || part.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(v))
      return std::nullopt;
    values.push_back(v);
  }
  return values;
}

}  // namespace cpgi
