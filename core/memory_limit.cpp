#include "core/memory_limit.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace cpgi {

uint64_t physicalMemory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemTotal:") return kib * 1024;
  return 0;
}

uint64_t defaultMemoryLimit() {
  const uint64_t total = physicalMemory();
  return total > 0 ? total / 4 * 3 : uint64_t(8) << 30;
}

std::string formatBytes(double bytes) {
  static const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
  char text[48];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return text;
}

uint64_t parseByteSize(const std::string& text) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return 0;
  }
  std::string unit = text.substr(used);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  double scale = 1.0;
  if (unit == "" || unit == "B")
    scale = 1.0;
  else if (unit == "K" || unit == "KB" || unit == "KIB")
    scale = 1024.0;
  else if (unit == "M" || unit == "MB" || unit == "MIB")
    scale = 1024.0 * 1024.0;
  else if (unit == "G" || unit == "GB" || unit == "GIB")
    scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "T" || unit == "TB" || unit == "TIB")
    scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else
    return 0;
  const double bytes = value * scale;
  if (!(bytes >= 1.0 && bytes < 1.8e19)) return 0;
  return uint64_t(bytes);
}

void requireMemory(double bytes, uint64_t limit, const std::string& where, const std::string& what,
                   const std::string& remedy) {
  if (limit == 0 || bytes <= double(limit)) return;
  throw InputError(where, what + " needs about " + formatBytes(bytes) + ", more than `maximum memory` " +
                              formatBytes(double(limit)) + "; " + remedy);
}

}  // namespace cpgi
