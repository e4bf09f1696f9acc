// `--view-size W×H` (or WxH) of the commands that write view-*.png / .exr.
#pragma once

#include <cstdio>
#include <string>

#include "core/error.h"
#include "radiosity/views.h"

namespace cpgi::cli {

/// The view parameters for `text` ("" keeps the defaults: 640 wide, the camera's aspect). Throws
/// InputError naming `option` unless it is two whole numbers in [16, 8192] joined by x, X or ×.
inline ViewParams parseViewSize(const std::string& text, const std::string& option = "--view-size") {
  ViewParams params;
  if (text.empty()) return params;
  std::string ascii = text;
  for (size_t at = ascii.find("×"); at != std::string::npos; at = ascii.find("×")) ascii.replace(at, 2, "x");
  int w = 0, h = 0;
  char x = 0, rest = 0;
  if (std::sscanf(ascii.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X') || w < 16 ||
      w > 8192 || h < 16 || h > 8192)
    throw InputError(option, "must be WIDTHxHEIGHT in pixels, each in [16, 8192], got " + text);
  params.width = w;
  params.height = h;
  return params;
}

}  // namespace cpgi::cli
