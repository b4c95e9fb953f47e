#pragma once
// Numbers in messages and labels: up to 6 significant digits, no trailing zeros ("0.25", "1e-05", "75").

#include <cstdio>
#include <string>

namespace blockdem {

inline std::string num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace blockdem
