#pragma once
// A small JSON reader (RFC 8259) for input files such as sweep descriptions: every value keeps the line and column
// where it starts, so that errors about a file's content can point at it. Standard library only.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"

namespace blockdem::io {

namespace detail {
class JsonParser;
}

/// One JSON value: null, a boolean, a number (double), a string (UTF-8), an array or an object (keys in file order,
/// no key twice). The accessors of the wrong kind throw InvalidArgument naming the value's place.
class JsonValue {
 public:
  enum class Kind { null, boolean, number, string, array, object };

  Kind kind() const { return kind_; }
  bool is_null() const { return kind_ == Kind::null; }
  bool is_bool() const { return kind_ == Kind::boolean; }
  bool is_number() const { return kind_ == Kind::number; }
  bool is_string() const { return kind_ == Kind::string; }
  bool is_array() const { return kind_ == Kind::array; }
  bool is_object() const { return kind_ == Kind::object; }

  /// Where the value starts in the text, 1-based; the column counts characters (UTF-8 code points), not bytes.
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& source() const {
    static const std::string none;
    return source_ ? *source_ : none;
  }
  std::string where() const { return source() + ":" + std::to_string(line_) + ":" + std::to_string(column_); }

  bool as_bool() const { expect(Kind::boolean); return boolean_; }
  double as_number() const { expect(Kind::number); return number_; }
  const std::string& as_string() const { expect(Kind::string); return string_; }
  const std::vector<JsonValue>& as_array() const { expect(Kind::array); return array_; }
  const std::vector<std::pair<std::string, JsonValue>>& as_object() const { expect(Kind::object); return object_; }

  /// The member `key` of an object; nullptr if absent or if this is not an object.
  const JsonValue* find(std::string_view key) const {
    for (const auto& [k, v] : object_)
      if (k == key) return &v;
    return nullptr;
  }

  /// "a string", "an array", ...: for messages such as "expected a number, got a string".
  static const char* kind_name(Kind kind) {
    constexpr const char* names[] = {"null", "a boolean", "a number", "a string", "an array", "an object"};
    return names[static_cast<int>(kind)];
  }

 private:
  friend class detail::JsonParser;
  void expect(Kind kind) const {
    if (kind_ != kind) throw InvalidArgument(where() + ": expected " + kind_name(kind) + ", got " + kind_name(kind_));
  }

  Kind kind_ = Kind::null;
  int line_ = 0;
  int column_ = 0;
  bool boolean_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<JsonValue> array_;
  std::vector<std::pair<std::string, JsonValue>> object_;
  std::shared_ptr<const std::string> source_;  // shared by all values of one document
};

namespace detail {

/// A recursive-descent parser over the text with the position (line, column) of the next character. Newlines occur
/// only in whitespace (a string may not hold a raw control character), so only skip_whitespace changes lines.
class JsonParser {
 public:
  static constexpr int max_depth = 256;

  JsonParser(std::string_view text, std::string source)
      : text_(text), source_(std::make_shared<const std::string>(std::move(source))) {}

  JsonValue parse_document() {
    if (text_.starts_with("\xEF\xBB\xBF")) pos_ = 3;  // a UTF-8 byte order mark, which RFC 8259 lets us ignore
    skip_whitespace();
    if (at_end()) fail("expected a JSON value, got an empty input");
    JsonValue value = parse_value(0);
    skip_whitespace();
    if (!at_end()) fail("expected the end of the input after the value, got " + describe_next());
    return value;
  }

 private:
  [[noreturn]] void fail_at(int line, int column, const std::string& what) const {
    throw InvalidArgument(*source_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + what);
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(line_, column_, what); }

  bool at_end() const { return pos_ >= text_.size(); }
  unsigned char next() const { return static_cast<unsigned char>(text_[pos_]); }
  bool next_is(char c) const { return !at_end() && text_[pos_] == c; }
  void advance(std::size_t bytes = 1) {  // within a line
    for (; bytes > 0 && !at_end(); --bytes, ++pos_)
      if ((next() & 0xC0) != 0x80) ++column_;  // continuation bytes of UTF-8 do not start a character
  }
  void skip_whitespace() {
    for (; !at_end(); ++pos_) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        column_ = 1;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++column_;
      } else {
        return;
      }
    }
  }
  std::string describe_next() const {
    if (at_end()) return "the end of the input";
    const unsigned char c = next();
    char buffer[32];
    if (c >= 0x20 && c < 0x7F) std::snprintf(buffer, sizeof buffer, "'%c'", c);
    else if (c < 0x80) std::snprintf(buffer, sizeof buffer, "the control character U+%04X", c);
    else std::snprintf(buffer, sizeof buffer, "the byte 0x%02X (not ASCII)", c);
    return buffer;
  }
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }

  JsonValue parse_value(int depth) {
    JsonValue value;
    value.line_ = line_;
    value.column_ = column_;
    value.source_ = source_;
    if (at_end()) fail("expected a value, got the end of the input");
    const char c = text_[pos_];
    if (c == '{' || c == '[') {
      if (depth >= max_depth) fail("arrays and objects nested deeper than " + std::to_string(max_depth) + " levels");
      if (c == '{') parse_object(value, depth + 1);
      else parse_array(value, depth + 1);
    } else if (c == '"') {
      value.kind_ = JsonValue::Kind::string;
      value.string_ = parse_string();
    } else if (c == '-' || is_digit(c)) {
      value.kind_ = JsonValue::Kind::number;
      value.number_ = parse_number();
    } else if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) {
      std::size_t end = pos_;
      while (end < text_.size() && end - pos_ < 40 && std::isalnum(static_cast<unsigned char>(text_[end]))) ++end;
      const std::string_view word = text_.substr(pos_, end - pos_);
      if (word == "true" || word == "false") {
        value.kind_ = JsonValue::Kind::boolean;
        value.boolean_ = word == "true";
      } else if (word != "null") {
        if (word == "NaN" || word == "Infinity" || word == "nan" || word == "inf")
          fail("NaN and Infinity are not JSON numbers");
        fail("expected a value (an object, array, string, number, true, false or null), got '" +
             std::string(word) + "'");
      }
      advance(word.size());
    } else {
      fail("expected a value (an object, array, string, number, true, false or null), got " + describe_next());
    }
    return value;
  }

  void parse_array(JsonValue& array, int depth) {
    array.kind_ = JsonValue::Kind::array;
    advance();  // [
    skip_whitespace();
    if (next_is(']')) return advance();
    for (;;) {
      skip_whitespace();
      if (next_is(']')) fail("expected a value after ',', got ']' (a trailing comma is not allowed)");
      array.array_.push_back(parse_value(depth));
      skip_whitespace();
      if (next_is(']')) return advance();
      if (!next_is(','))
        fail("expected ',' or ']' after an element of the array at " + position(array) + ", got " + describe_next());
      advance();
    }
  }

  void parse_object(JsonValue& object, int depth) {
    object.kind_ = JsonValue::Kind::object;
    advance();  // {
    skip_whitespace();
    if (next_is('}')) return advance();
    std::unordered_map<std::string, std::pair<int, int>> seen;  // key -> where it first appears
    for (;;) {
      skip_whitespace();
      if (next_is('}')) fail("expected a key after ',', got '}' (a trailing comma is not allowed)");
      if (!next_is('"')) fail("expected a key (a string in double quotes), got " + describe_next());
      const int line = line_, column = column_;
      std::string key = parse_string();
      if (const auto [it, inserted] = seen.try_emplace(key, line, column); !inserted)
        fail_at(line, column, "duplicate key \"" + key + "\" in an object (first at " +
                                  std::to_string(it->second.first) + ":" + std::to_string(it->second.second) + ")");
      skip_whitespace();
      if (!next_is(':')) fail("expected ':' after the key \"" + key + "\", got " + describe_next());
      advance();
      skip_whitespace();
      JsonValue value = parse_value(depth);
      object.object_.emplace_back(std::move(key), std::move(value));
      skip_whitespace();
      if (next_is('}')) return advance();
      if (!next_is(','))
        fail("expected ',' or '}' after a member of the object at " + position(object) + ", got " + describe_next());
      advance();
    }
  }
  static std::string position(const JsonValue& v) { return std::to_string(v.line_) + ":" + std::to_string(v.column_); }

  std::string parse_string() {
    const int line = line_, column = column_;
    advance();  // "
    std::string out;
    for (;;) {
      if (at_end()) fail_at(line, column, "unterminated string: no closing '\"' before the end of the input");
      const unsigned char c = next();
      if (c == '"') {
        advance();
        return out;
      }
      if (c < 0x20) fail(describe_next() + " in a string; write it as an escape such as \\n, \\t or \\u00XX");
      if (c == '\\') {
        parse_escape(out);
      } else if (c < 0x80) {
        out += static_cast<char>(c);
        advance();
      } else {
        const std::size_t length = utf8_length();
        if (length == 0) fail("invalid UTF-8 in a string (the input must be UTF-8)");
        out.append(text_.substr(pos_, length));
        advance(length);
      }
    }
  }

  // The length of the valid UTF-8 sequence at pos_ (RFC 3629: no overlong forms, surrogates or code points above
  // U+10FFFF), or 0.
  std::size_t utf8_length() const {
    const auto byte = [&](std::size_t i) -> unsigned {
      return pos_ + i < text_.size() ? static_cast<unsigned char>(text_[pos_ + i]) : 0u;
    };
    const unsigned lead = byte(0);
    if (lead < 0xC2 || lead > 0xF4) return 0;
    const std::size_t length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : 2;
    const unsigned low = lead == 0xE0 ? 0xA0 : lead == 0xF0 ? 0x90 : 0x80;
    const unsigned high = lead == 0xED ? 0x9F : lead == 0xF4 ? 0x8F : 0xBF;
    if (byte(1) < low || byte(1) > high) return 0;
    for (std::size_t i = 2; i < length; ++i)
      if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
    return length;
  }

  void parse_escape(std::string& out) {
    const int line = line_, column = column_;
    advance();  // backslash
    if (at_end()) fail_at(line, column, "unterminated string: the input ends inside an escape");
    const char c = text_[pos_];
    advance();
    static constexpr std::string_view escapes = "\"\\/bfnrt", meanings = "\"\\/\b\f\n\r\t";
    if (const auto i = escapes.find(c); i != std::string_view::npos) {
      out += meanings[i];
      return;
    }
    if (c != 'u')
      fail_at(line, column, "invalid escape '\\" + std::string(1, c) +
                                "' in a string (allowed: \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)");
    unsigned code = hex4(line, column);
    if (code >= 0xDC00 && code <= 0xDFFF)
      fail_at(line, column, "a low surrogate \\u" + hex(code) + " without a high one before it");
    if (code >= 0xD800 && code <= 0xDBFF) {
      if (!text_.substr(pos_).starts_with("\\u"))
        fail_at(line, column, "a high surrogate \\u" + hex(code) + " must be followed by a low one \\uDC00-\\uDFFF");
      const int low_line = line_, low_column = column_;
      advance(2);
      const unsigned low = hex4(low_line, low_column);
      if (low < 0xDC00 || low > 0xDFFF)
        fail_at(low_line, low_column,
                "expected a low surrogate \\uDC00-\\uDFFF after \\u" + hex(code) + ", got \\u" + hex(low));
      code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    if (code < 0x80) {
      out += static_cast<char>(code);
      return;
    }
    const int tail = code < 0x800 ? 1 : code < 0x10000 ? 2 : 3;  // continuation bytes after the lead byte
    out += static_cast<char>(((0xF0u << (3 - tail)) & 0xFFu) | (code >> (6 * tail)));
    for (int i = tail - 1; i >= 0; --i) out += static_cast<char>(0x80u | ((code >> (6 * i)) & 0x3Fu));
  }
  static std::string hex(unsigned code) {
    char buffer[8];
    std::snprintf(buffer, sizeof buffer, "%04X", code);
    return buffer;
  }
  unsigned hex4(int line, int column) {  // the 4 hex digits after \u
    const std::string_view digits = text_.substr(pos_, 4);
    const auto is_hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
    if (digits.size() < 4 || !std::all_of(digits.begin(), digits.end(), is_hex))
      fail_at(line, column, "expected 4 hex digits after \\u");
    unsigned code = 0;
    std::from_chars(digits.data(), digits.data() + 4, code, 16);
    advance(4);
    return code;
  }

  // number = [ "-" ] ( "0" / 1-9 *DIGIT ) [ "." 1*DIGIT ] [ ( "e" / "E" ) [ "-" / "+" ] 1*DIGIT ]   (RFC 8259 sect. 6)
  double parse_number() {
    std::size_t end = pos_;
    const auto fail_at_end = [&](const std::string& what) {  // a number is ASCII: one column per byte
      fail_at(line_, column_ + static_cast<int>(end - pos_), what);
    };
    const auto digits = [&] {
      while (end < text_.size() && is_digit(text_[end])) ++end;
    };
    const auto digit_at_end = [&] { return end < text_.size() && is_digit(text_[end]); };
    if (text_[end] == '-') ++end;
    if (!digit_at_end()) {
      if (text_.substr(end).starts_with("Infinity")) fail("NaN and Infinity are not JSON numbers");
      fail_at_end("expected a digit after '-'");
    }
    if (text_[end] == '0') {
      if (++end < text_.size() && is_digit(text_[end]))
        fail_at_end("a number may not have a leading zero (write 7, not 07)");
    } else {
      digits();
    }
    if (end < text_.size() && text_[end] == '.') {
      ++end;
      if (!digit_at_end()) fail_at_end("expected a digit after the decimal point");
      digits();
    }
    if (end < text_.size() && (text_[end] == 'e' || text_[end] == 'E')) {
      ++end;
      if (end < text_.size() && (text_[end] == '+' || text_[end] == '-')) ++end;
      if (!digit_at_end()) fail_at_end("expected a digit in the exponent");
      digits();
    }
    double value = 0;
    const auto [ptr, error] = std::from_chars(text_.data() + pos_, text_.data() + end, value);
    if (error != std::errc{} || ptr != text_.data() + end) {
      std::string number(text_.substr(pos_, std::min<std::size_t>(end - pos_, 40)));
      if (end - pos_ > 40) number += "...";
      fail("the number " + number + " is outside the range of a double (magnitudes 4.9e-324 to 1.8e308)");
    }
    advance(end - pos_);
    return value;
  }

  std::string_view text_;
  std::shared_ptr<const std::string> source_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

}  // namespace detail

/// Parses a whole JSON text. Throws InvalidArgument "<source>:<line>:<column>: <what is wrong>" on malformed input,
/// including trailing commas, a key twice in one object, anything after the value, or nesting deeper than 256.
inline JsonValue parse_json(std::string_view text, std::string source = "<json>") {
  return detail::JsonParser(text, std::move(source)).parse_document();
}

/// Reads and parses a JSON file; messages name the path.
inline JsonValue read_json_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InvalidArgument(path + ": no such file");
  if (std::filesystem::is_directory(path, error)) throw InvalidArgument(path + ": is a folder, not a JSON file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(path + ": cannot open the file for reading");
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) throw InvalidArgument(path + ": reading the file failed");
  return parse_json(contents.str(), path);
}

}  // namespace blockdem::io
