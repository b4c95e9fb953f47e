#pragma once
// The objects of an input file (a model file, ...) read field by field: every error names the file, line and column,
// the field's path in the file (blocks[3].density) and the allowed values or range; a key the object does not know
// is an error (a typo never falls back to a default silently).

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/io/json_reader.hpp"

namespace blockdem::io {

/// An interval of allowed numbers, open or closed at each end, with its unit for messages.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  std::string_view unit;

  static Range positive(std::string_view unit, double hi = std::numeric_limits<double>::infinity()) { return {0, hi, true, false, unit}; }
  static Range at_least(double lo, std::string_view unit, double hi = std::numeric_limits<double>::infinity()) { return {lo, hi, false, false, unit}; }
  static Range any(std::string_view unit) { return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), false, false, unit}; }

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string text() const {
    auto bound = [](double b) { return std::isinf(b) ? std::string(b < 0 ? "-inf" : "inf") : num(b); };
    // Appended piece by piece: "(" + std::string makes GCC 12 warn, wrongly, of an overlap.
    std::string s(1, lo_open || std::isinf(lo) ? '(' : '[');
    ((s += bound(lo)) += ", ") += bound(hi);
    s += hi_open || std::isinf(hi) ? ')' : ']';
    if (!unit.empty()) (s += ' ') += unit;
    return s;
  }
};

[[noreturn]] inline void field_error(const JsonValue& at, const std::string& path, const std::string& what) {
  throw InvalidArgument(at.where() + ": " + path + ": " + what);
}

inline std::string join_words(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

/// A number within `range`.
inline double number_value(const JsonValue& v, const std::string& path, const Range& range) {
  if (!v.is_number()) field_error(v, path, std::string("expected a number, got ") + JsonValue::kind_name(v.kind()));
  const double x = v.as_number();
  if (!range.contains(x)) field_error(v, path, "must be in " + range.text() + ", got " + num(x));
  return x;
}

/// A point or vector [x, y, z], each within `range`.
inline Vec3 vec3_value(const JsonValue& v, const std::string& path, const Range& range = Range::any("m")) {
  if (!v.is_array() || v.as_array().size() != 3)
    field_error(v, path, std::string("expected three numbers [x, y, z], got ") +
                             (v.is_array() ? std::to_string(v.as_array().size()) + " values" : JsonValue::kind_name(v.kind())));
  Vec3 x;
  for (int k = 0; k < 3; ++k) x[k] = number_value(v.as_array()[static_cast<std::size_t>(k)], path + "[" + std::to_string(k) + "]", range);
  return x;
}

/// A string.
inline const std::string& string_value(const JsonValue& v, const std::string& path) {
  if (!v.is_string()) field_error(v, path, std::string("expected a string, got ") + JsonValue::kind_name(v.kind()));
  return v.as_string();
}

/// An array (of any length in [min, max]).
inline const std::vector<JsonValue>& array_value(const JsonValue& v, const std::string& path, std::size_t min = 0,
                                                 std::size_t max = static_cast<std::size_t>(-1)) {
  if (!v.is_array()) field_error(v, path, std::string("expected a list, got ") + JsonValue::kind_name(v.kind()));
  const auto n = v.as_array().size();
  if (n < min || n > max)
    field_error(v, path, "expected " + (min == max ? std::to_string(min) : "between " + std::to_string(min) + " and " +
                                                                               (max == static_cast<std::size_t>(-1) ? std::string("any number of") : std::to_string(max))) +
                             " values, got " + std::to_string(n));
  return v.as_array();
}

/// An object of the file with the keys it may hold.
class JsonFields {
 public:
  JsonFields(const JsonValue& object, std::string path, std::initializer_list<std::string_view> allowed) : object_(&object), path_(std::move(path)) {
    if (!object.is_object())
      field_error(object, path_, std::string("expected an object { ... }, got ") + JsonValue::kind_name(object.kind()));
    for (const auto& [key, value] : object.as_object())
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::vector<std::string> names(allowed.begin(), allowed.end());
        field_error(value, path_, "unknown key \"" + key + "\" (allowed: " + join_words(names) + ")");
      }
  }

  const JsonValue& object() const { return *object_; }
  const std::string& path() const { return path_; }
  std::string path(std::string_view key) const { return path_.empty() ? std::string(key) : path_ + "." + std::string(key); }

  const JsonValue* find(std::string_view key) const { return object_->find(key); }
  bool has(std::string_view key) const { return find(key) != nullptr; }
  const JsonValue& required(std::string_view key, std::string_view expected) const {
    const JsonValue* v = find(key);
    if (!v) field_error(*object_, path_.empty() ? std::string("the file") : path_, "\"" + std::string(key) + "\" is missing (" + std::string(expected) + ")");
    return *v;
  }

  double number(std::string_view key, double fallback, const Range& range) const {
    const JsonValue* v = find(key);
    return v ? number_value(*v, path(key), range) : fallback;
  }
  double required_number(std::string_view key, const Range& range) const {
    return number_value(required(key, "a number in " + range.text()), path(key), range);
  }
  std::string string(std::string_view key, std::string fallback) const {
    const JsonValue* v = find(key);
    return v ? string_value(*v, path(key)) : fallback;
  }
  bool boolean(std::string_view key, bool fallback) const {
    const JsonValue* v = find(key);
    if (!v) return fallback;
    if (!v->is_bool()) field_error(*v, path(key), std::string("expected true or false, got ") + JsonValue::kind_name(v->kind()));
    return v->as_bool();
  }
  Vec3 vec3(std::string_view key, const Vec3& fallback, const Range& range = Range::any("m")) const {
    const JsonValue* v = find(key);
    return v ? vec3_value(*v, path(key), range) : fallback;
  }
  /// One of the named choices.
  template <class T>
  T choice(std::string_view key, T fallback, std::initializer_list<std::pair<std::string_view, T>> choices) const {
    const JsonValue* v = find(key);
    if (!v) return fallback;
    return choice_value(*v, path(key), choices);
  }
  template <class T>
  static T choice_value(const JsonValue& v, const std::string& path, std::initializer_list<std::pair<std::string_view, T>> choices) {
    std::vector<std::string> names;
    for (const auto& [name, value] : choices) names.emplace_back(name);
    if (!v.is_string()) field_error(v, path, "expected one of " + join_words(names) + ", got " + JsonValue::kind_name(v.kind()));
    for (const auto& [name, value] : choices)
      if (v.as_string() == name) return value;
    field_error(v, path, "unknown value \"" + v.as_string() + "\" (allowed: " + join_words(names) + ")");
  }

 private:
  const JsonValue* object_;
  std::string path_;
};

}  // namespace blockdem::io
