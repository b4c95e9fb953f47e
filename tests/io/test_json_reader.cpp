// The JSON reader (io/json_reader.hpp): values, escapes and numbers as RFC 8259 defines them, the positions of
// values, and malformed input refused with the line and column of the fault.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "blockdem/io/json_reader.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_json_reader {
using blockdem::io::JsonValue;

namespace {

/// The message of the InvalidArgument that parsing `text` throws, or "no error".
std::string parse_error(const std::string& text) {
  try {
    io::parse_json(text, "t.json");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("json reader: literals, numbers, strings, arrays and objects") {
  const JsonValue v = io::parse_json(R"( {"a": true, "b": false, "c": null, "n": -0.5e-3, "m": 1E2, "z": -0,
    "s": "text", "list": [1, 2.5, [], {}], "o": {"k": "v"}} )");
  REQUIRE(v.is_object());
  const auto& members = v.as_object();
  REQUIRE(members.size() == 9);
  CHECK(members[0].first == "a");  // file order
  CHECK(members[8].first == "o");
  CHECK(v.find("a")->as_bool());
  CHECK_FALSE(v.find("b")->as_bool());
  CHECK(v.find("c")->is_null());
  CHECK(v.find("n")->as_number() == -0.5e-3);
  CHECK(v.find("m")->as_number() == 100);
  CHECK(v.find("z")->as_number() == 0);
  CHECK(v.find("s")->as_string() == "text");
  const auto& list = v.find("list")->as_array();
  REQUIRE(list.size() == 4);
  CHECK(list[1].as_number() == 2.5);
  CHECK(list[2].as_array().empty());
  CHECK(list[3].as_object().empty());
  CHECK(v.find("o")->find("k")->as_string() == "v");
  CHECK(v.find("missing") == nullptr);
  CHECK(list[0].find("a") == nullptr);  // not an object
  CHECK(io::parse_json("123456789012345678").as_number() == 123456789012345678.0);
  CHECK(io::parse_json("4.9e-324").as_number() > 0);  // the smallest subnormal
  CHECK(io::parse_json("\xEF\xBB\xBF[]").is_array());  // a byte order mark is skipped
}

TEST_CASE("json reader: escapes, \\u and surrogate pairs to UTF-8") {
  CHECK(io::parse_json(R"("\"\\\/\b\f\n\r\t")").as_string() == "\"\\/\b\f\n\r\t");
  CHECK(io::parse_json(R"("caf\u00e9")").as_string() == "caf\xC3\xA9");
  CHECK(io::parse_json(R"("\u20AC")").as_string() == "\xE2\x82\xAC");
  CHECK(io::parse_json(R"("\ud83d\ude00")").as_string() == "\xF0\x9F\x98\x80");  // U+1F600, 4 bytes
  CHECK(io::parse_json(R"("a\u0000b")").as_string() == std::string("a\0b", 3));
  CHECK(io::parse_json("\"caf\xC3\xA9\"").as_string() == "caf\xC3\xA9");  // raw UTF-8 passes through
}

TEST_CASE("json reader: values know their line and column, nesting to 256 levels is allowed") {
  const JsonValue v = io::parse_json("{\n  \"a\": [1,\n        {\"b\": \"x\"}]\n}", "sweep.json");
  CHECK(v.line() == 1);
  CHECK(v.column() == 1);
  const JsonValue& inner = v.find("a")->as_array()[1];
  CHECK(inner.line() == 3);
  CHECK(inner.column() == 9);
  CHECK(inner.find("b")->column() == 15);
  CHECK(inner.find("b")->where() == "sweep.json:3:15");
  CHECK(inner.source() == "sweep.json");
  // Columns count characters, not bytes: "é" is one.
  CHECK(io::parse_json("[\"\xC3\xA9\", 7]").as_array()[1].column() == 7);
  CHECK(io::parse_json(std::string(256, '[') + std::string(256, ']')).is_array());
}

TEST_CASE("json reader: the wrong accessor names the value's place and both kinds") {
  const JsonValue v = io::parse_json("{\"a\":\n \"3\"}", "f.json");
  try {
    static_cast<void>(v.find("a")->as_number());
    FAIL("no exception");
  } catch (const InvalidArgument& e) {
    CHECK(std::string(e.what()) == "f.json:2:2: expected a number, got a string");
  }
  CHECK_THROWS_AS(static_cast<void>(v.as_array()), InvalidArgument);
}

TEST_CASE("json reader: malformed input is refused with its line, column and what was expected") {
  struct Bad {
    std::string text;
    std::string position;  // "line:column"
    std::string word;      // in the message
  };
  const std::vector<Bad> bad{
      {"", "1:1", "empty input"},
      {"  \n ", "2:2", "empty input"},
      {"[1, 2,]", "1:7", "trailing comma"},
      {"{\"a\": 1,\n}", "2:1", "trailing comma"},
      {"{\"a\": 1, \"a\": 2}", "1:10", "duplicate key \"a\""},
      {"[1] 2", "1:5", "end of the input"},
      {"[\"abc", "1:2", "unterminated string"},
      {"\"a\nb\"", "1:3", "control character U+000A"},
      {"[01]", "1:3", "leading zero"},
      {"-", "1:2", "digit after '-'"},
      {"[1.]", "1:4", "decimal point"},
      {"[1e+]", "1:5", "exponent"},
      {"NaN", "1:1", "NaN"},
      {"[-Infinity]", "1:2", "Infinity"},
      {"1e400", "1:1", "outside the range"},
      {"\n  [tru]", "2:4", "got 'tru'"},
      {"{\"a\" 1}", "1:6", "expected ':'"},
      {"{\"a\": 1 \"b\": 2}", "1:9", "expected ',' or '}'"},
      {"[1 2]", "1:4", "expected ',' or ']'"},
      {"{a: 1}", "1:2", "a string in double quotes"},
      {"[\"\\x\"]", "1:3", "invalid escape"},
      {"\"\\u12g4\"", "1:2", "4 hex digits"},
      {"\"\\ud83d\"", "1:2", "high surrogate"},
      {"\"\\ude00\"", "1:2", "low surrogate"},
      {"\"\xFF\"", "1:2", "UTF-8"},
      {"[1, 2", "1:6", "got the end of the input"},
      {"[+1]", "1:2", "got '+'"},
      {std::string(257, '['), "1:257", "nested deeper than 256"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.text);
    const std::string message = parse_error(b.text);
    CAPTURE(message);
    CHECK(message.rfind("t.json:" + b.position + ": ", 0) == 0);
    CHECK(message.find(b.word) != std::string::npos);
  }
}

TEST_CASE("json reader: a very deep nesting is refused, not a stack overflow") {
  const std::string message = parse_error(std::string(100000, '['));
  CHECK(message.find("t.json:1:257: arrays and objects nested deeper than 256") == 0);
  CHECK(parse_error(std::string(100000, '{')).find("expected a key") != std::string::npos);
  CHECK(parse_error(std::string(50000, '[') + "{\"a\":" + std::string(50000, '[')).find("nested deeper") !=
        std::string::npos);
}

TEST_CASE("json reader: files are read and named in messages") {
  const auto path = (std::filesystem::temp_directory_path() / "blockdem_test_json_reader.json").string();
  std::ofstream(path) << "{\"x\": [1,\n 2,]}";
  try {
    io::read_json_file(path);
    FAIL("no exception");
  } catch (const InvalidArgument& e) {
    CHECK(std::string(e.what()) ==
          path + ":2:4: expected a value after ',', got ']' (a trailing comma is not allowed)");
  }
  std::ofstream(path) << "{\"x\": 1}";
  CHECK(io::read_json_file(path).find("x")->as_number() == 1);
  std::filesystem::remove(path);
  const std::string absent = (std::filesystem::temp_directory_path() / "blockdem_no_such.json").string();
  CHECK_THROWS_WITH_AS(io::read_json_file(absent), (absent + ": no such file").c_str(), InvalidArgument);
}

}  // namespace test_json_reader
