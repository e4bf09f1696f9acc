// Comma-separated numbers as the command line and the settings give them ("1,2.5, 3", "X,Y,Z").
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cpgi {

/// The finite numbers of `text`, comma-separated (spaces after a number allowed); nothing when any part
/// is not one.
std::optional<std::vector<float>> parseNumberList(const std::string& text);

}  // namespace cpgi
