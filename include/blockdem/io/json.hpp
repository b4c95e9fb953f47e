#pragma once
// A minimal JSON object writer for run reports and program output: numbers in shortest round-trip form,
// NaN and infinities as null, strings escaped. No dependency beyond the standard library.

#include <charconv>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace blockdem::io {

class JsonObject {
 public:
  JsonObject() : text_("{") {}

  JsonObject& add(std::string_view key, double value) {
    write_key(key);
    write_number(value);
    return *this;
  }
  JsonObject& add(std::string_view key, int value) {
    write_key(key);
    text_ += std::to_string(value);
    return *this;
  }
  JsonObject& add(std::string_view key, long long value) {
    write_key(key);
    text_ += std::to_string(value);
    return *this;
  }
  JsonObject& add(std::string_view key, bool value) {
    write_key(key);
    text_ += value ? "true" : "false";
    return *this;
  }
  JsonObject& add(std::string_view key, std::string_view value) {
    write_key(key);
    write_string(value);
    return *this;
  }
  JsonObject& add(std::string_view key, const char* value) { return add(key, std::string_view(value)); }
  JsonObject& add(std::string_view key, std::span<const double> values) {
    write_key(key);
    text_ += '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i) text_ += ", ";
      write_number(values[i]);
    }
    text_ += ']';
    return *this;
  }
  JsonObject& add(std::string_view key, const std::vector<std::string>& values) {
    write_key(key);
    text_ += '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i) text_ += ", ";
      write_string(values[i]);
    }
    text_ += ']';
    return *this;
  }
  /// A value that is already JSON (a nested object or array).
  JsonObject& add_raw(std::string_view key, std::string_view json) {
    write_key(key);
    text_ += json;
    return *this;
  }
  /// A nested object, indented one level deeper.
  JsonObject& add(std::string_view key, const JsonObject& value) {
    write_key(key);
    append_indented(value.str());
    return *this;
  }
  /// An array of objects, one per line group, indented one level deeper.
  JsonObject& add(std::string_view key, const std::vector<JsonObject>& values) {
    write_key(key);
    text_ += '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
      text_ += i ? ",\n    " : "\n    ";
      const std::string item = values[i].str();
      for (char c : item) {
        text_ += c;
        if (c == '\n') text_ += "    ";
      }
    }
    text_ += values.empty() ? "]" : "\n  ]";
    return *this;
  }

  /// A number as this writer prints it (shortest round trip; null if not finite), for building raw values.
  static std::string number(double value) {
    JsonObject o;
    o.write_number(value);
    return o.text_.substr(1);
  }

  /// A string as a JSON value, quoted and escaped.
  static std::string quoted(std::string_view value) {
    JsonObject o;
    o.write_string(value);
    return o.text_.substr(1);
  }

  std::string str() const { return text_ + (first_ ? "}" : "\n}"); }

 private:
  void write_key(std::string_view key) {
    text_ += first_ ? "\n  " : ",\n  ";
    first_ = false;
    write_string(key);
    text_ += ": ";
  }
  void write_number(double value) {
    if (!std::isfinite(value)) {
      text_ += "null";
      return;
    }
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    text_.append(buffer, result.ptr);
  }
  void append_indented(const std::string& nested) {
    for (char c : nested) {
      text_ += c;
      if (c == '\n') text_ += "  ";
    }
  }
  void write_string(std::string_view value) {
    text_ += '"';
    for (char c : value) {
      switch (c) {
        case '"': text_ += "\\\""; break;
        case '\\': text_ += "\\\\"; break;
        case '\n': text_ += "\\n"; break;
        case '\t': text_ += "\\t"; break;
        case '\r': text_ += "\\r"; break;
        default:
          if (static_cast<unsigned char>(c) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            text_ += escaped;
          } else {
            text_ += c;
          }
      }
    }
    text_ += '"';
  }

  std::string text_;
  bool first_ = true;
};

}  // namespace blockdem::io
