#pragma once
// Units in which strong-motion files state acceleration, and their conversion to m/s^2 (the library's unit).

#include <algorithm>
#include <cctype>
#include <optional>
#include <string>
#include <string_view>

#include "blockdem/core/units.hpp"

namespace blockdem::motion {

enum class AccelerationUnit { g, m_s2, cm_s2 };

/// Factor that turns a value in `unit` into m/s^2 (1 g = standard gravity, 9.80665 m/s^2).
constexpr double to_m_s2(AccelerationUnit unit) noexcept {
  switch (unit) {
    case AccelerationUnit::g: return standard_gravity;
    case AccelerationUnit::cm_s2: return 0.01;
    case AccelerationUnit::m_s2: return 1.0;
  }
  return 1.0;
}

constexpr const char* to_string(AccelerationUnit unit) noexcept {
  switch (unit) {
    case AccelerationUnit::g: return "g";
    case AccelerationUnit::cm_s2: return "cm/s2";
    case AccelerationUnit::m_s2: return "m/s2";
  }
  return "?";
}

/// The unit named by `text`, case-insensitive: g; m/s2, m/s^2, m/s/s, m/sec/sec, m/s**2; cm/s2, cm/s^2, cm/s/s,
/// cm/sec/sec, gal. Empty when the text names none of them.
inline std::optional<AccelerationUnit> parse_acceleration_unit(std::string_view text) {
  std::string s;
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "g") return AccelerationUnit::g;
  if (s == "gal") return AccelerationUnit::cm_s2;
  for (std::string_view tail : {"/s2", "/s^2", "/s/s", "/sec/sec", "/s**2", "/sec2", "/sec^2", "_s2"}) {
    if (s.size() > tail.size() && s.ends_with(tail)) {
      const std::string_view head(s.data(), s.size() - tail.size());
      if (head == "m") return AccelerationUnit::m_s2;
      if (head == "cm") return AccelerationUnit::cm_s2;
    }
  }
  return std::nullopt;
}

}  // namespace blockdem::motion
