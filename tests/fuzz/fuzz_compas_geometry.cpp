// Fuzzes the COMPAS JSON reader (io/compas_geometry.hpp) as `blockdem` reads a .json geometry file: the text parsed
// and every mesh in it read into a block, whose faces must refer to its vertices. A file is refused with
// InvalidArgument (or InputError) or read; nothing else may happen.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "blockdem/core/error.hpp"
#include "blockdem/io/compas_geometry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    for (const auto& b : blockdem::io::read_compas_json(text, "fuzz.json")) {
      if (b.name.empty() || b.origin.empty()) {
        std::fprintf(stderr, "fuzz_compas_geometry: a block without a name or origin\n");
        std::abort();
      }
      for (const auto& f : b.faces)
        for (int k : f)
          if (k < 0 || static_cast<std::size_t>(k) >= b.vertices.size()) {
            std::fprintf(stderr, "fuzz_compas_geometry: %s: a face refers to no vertex\n", b.origin.c_str());
            std::abort();
          }
    }
  } catch (const blockdem::InvalidArgument&) {
  } catch (const blockdem::InputError&) {
  }
  return 0;
}
