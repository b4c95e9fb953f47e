// Fuzzes the OBJ reader (io/obj_geometry.hpp) and the checks `blockdem check blocks.obj` runs on what it read: each
// block's (geometry/polyhedron_check.hpp) and the assembly's (geometry/assembly_check.hpp). A file is refused with
// InputError or read; every block is then usable or named with an error, and a usable block is a valid convex
// polyhedron. Nothing else may happen.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/obj_geometry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace blockdem;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto blocks = io::read_obj(text, "fuzz.obj");
    std::vector<geometry::BlockIssue> issues;
    std::vector<geometry::ConvexPolyhedron> shapes;
    for (const auto& b : blocks) {
      const std::size_t before = issues.size();
      auto s = geometry::check_polyhedron(b, issues);
      if (s) {
        s->validate(b.name);  // a usable block is a valid convex polyhedron: throws (a finding) otherwise
        shapes.push_back(std::move(*s));
      } else if (issues.size() == before || issues.back().severity != geometry::BlockIssue::Severity::error) {
        std::fprintf(stderr, "fuzz_obj_geometry: block '%s' refused without an error\n", b.name.c_str());
        std::abort();
      }
    }
    if (shapes.size() <= 200) {  // a bounded number of blocks: the separating-axis test is quadratic in the faces
      std::vector<geometry::AssemblyBlock> assembly;
      for (const auto& s : shapes) assembly.push_back({&s, "b", "", true});
      (void)geometry::check_assembly(assembly, 1e-3, issues);
    }
  } catch (const InputError&) {
  }
  return 0;
}
