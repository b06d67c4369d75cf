#include "core/memory_budget.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace kasha {

void requireMemory(uint64_t bytes, const std::string& what, uint64_t limit) {
  if (bytes <= limit) return;
  throw MemoryLimitError(what + " needs " + (bytes == UINT64_MAX ? std::string("more than 16 EiB") : formatBytes(bytes)) +
                         ", more than the memory limit of " + formatBytes(limit) + " (raise it with --memory-limit)");
}

uint64_t parseByteSize(const std::string& text) {
  const std::string why = "expected a size in bytes with an optional K, M, G or T suffix, got '" + text + "'";
  size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
  if (i == 0) throw std::invalid_argument(why);
  const std::string number = text.substr(0, i);
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (*end != '\0' || !std::isfinite(value)) throw std::invalid_argument(why);
  std::string suffix;
  for (size_t k = i; k < text.size(); ++k) suffix += char(std::toupper(static_cast<unsigned char>(text[k])));
  int power = 0;
  if (!suffix.empty()) {
    const std::string units = "KMGT";
    const size_t p = units.find(suffix[0]);
    const std::string rest = suffix.substr(1);
    if (p != std::string::npos && (rest.empty() || rest == "B" || rest == "IB")) {
      power = int(p) + 1;
    } else if (suffix != "B") {
      throw std::invalid_argument(why);
    }
  }
  const double bytes = value * std::ldexp(1.0, 10 * power);
  if (!(bytes >= 1.0)) throw std::invalid_argument("must be at least 1 byte, got '" + text + "'");
  if (bytes >= 0x1p64) throw std::invalid_argument("'" + text + "' is too large");
  return uint64_t(bytes);
}

std::string formatBytes(uint64_t bytes) {
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double v = double(bytes) / 1024.0;
  int u = 0;
  while (v >= 1024.0 && u < 5) v /= 1024.0, ++u;
  char buf[64];
  std::snprintf(buf, sizeof buf, v < 10.0 ? "%.2f %s" : v < 100.0 ? "%.1f %s" : "%.0f %s", v, units[u]);
  return buf;
}

}  // namespace kasha
