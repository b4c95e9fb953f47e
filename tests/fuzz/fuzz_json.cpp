// Fuzzes the JSON reader (io/json_reader.hpp) that sweep files and case.json records go through: parse_json on the
// whole input, then a walk over the document that checks every value's position and calls every accessor, as the
// readers built on it do.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "blockdem/core/error.hpp"
#include "blockdem/io/json_reader.hpp"

namespace {

using blockdem::io::JsonValue;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_json: %s\n", what.c_str());
  std::abort();
}

void walk(const JsonValue& v, std::size_t size) {
  if (v.line() < 1 || v.column() < 1 || static_cast<std::size_t>(v.line()) > size + 1 ||
      static_cast<std::size_t>(v.column()) > size + 1)
    finding("a value at " + v.where() + ", outside an input of " + std::to_string(size) + " bytes");
  switch (v.kind()) {
    case JsonValue::Kind::boolean: (void)v.as_bool(); break;
    case JsonValue::Kind::number: (void)v.as_number(); break;
    case JsonValue::Kind::string: (void)v.as_string().size(); break;
    case JsonValue::Kind::array:
      for (const auto& e : v.as_array()) walk(e, size);
      break;
    case JsonValue::Kind::object:
      for (const auto& [key, member] : v.as_object()) {
        if (v.find(key) != &member) finding("find(\"" + key + "\") is not the member of that name");
        walk(member, size);
      }
      break;
    case JsonValue::Kind::null: break;
  }
  // An accessor of the wrong kind throws InvalidArgument naming the place.
  try {
    if (v.is_number()) (void)v.as_string();
    else (void)v.as_number();
    finding("an accessor of the wrong kind did not throw at " + v.where());
  } catch (const blockdem::InvalidArgument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    walk(blockdem::io::parse_json(text, "fuzz.json"), size);
  } catch (const blockdem::InvalidArgument&) {
  } catch (const blockdem::InputError&) {
  }
  return 0;
}
