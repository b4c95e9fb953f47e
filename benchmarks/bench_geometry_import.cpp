// Geometry import at scale (goal: 10,000 blocks read from OBJ and checked in under 10 s): a running-bond wall of
// 100 courses x 100 units exported as a CAD program does (each face two triangles, each triangle with corners of its
// own), read, each block checked (welded, merged, turned outward) and the assembly checked for overlaps and blocks
// touching nothing by the bounding-box sweep. Also the same file as clean quads with shared corners.

#include <benchmark/benchmark.h>

#include <sstream>
#include <string>
#include <vector>

#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/obj_geometry.hpp"

namespace {

using namespace blockdem;

/// The wall as OBJ text: clean (quads, shared corners) or as CAD exports (triangles with their own corners).
std::string wall_obj(bool cad_style) {
  const auto wall = geometry::running_bond_wall(100, 100, 0.25, 0.12, 0.065);
  if (!cad_style) {
    std::vector<geometry::ImportedBlock> blocks;
    for (const auto& b : wall) blocks.push_back(geometry::imported_block(b.shape, b.name));
    std::ostringstream out;
    io::write_obj(out, blocks, "wall");
    return out.str();
  }
  std::ostringstream out;
  std::size_t base = 1;
  for (const auto& b : wall) {
    out << "o " << b.name << "\n";
    for (const auto& face : b.shape.faces)
      for (std::size_t i = 1; i + 1 < face.size(); ++i) {
        for (int k : {face[0], face[i], face[i + 1]}) {
          const auto& v = b.shape.vertices[static_cast<std::size_t>(k)];
          out << "v " << io::JsonObject::number(v.x()) << ' ' << io::JsonObject::number(v.y()) << ' ' << io::JsonObject::number(v.z()) << "\n";
        }
        out << "f " << base << ' ' << base + 1 << ' ' << base + 2 << "\n";
        base += 3;
      }
  }
  return out.str();
}

void import_and_check(benchmark::State& state, bool cad_style) {
  const std::string text = wall_obj(cad_style);
  std::size_t blocks = 0, errors = 0, pairs = 0;
  for (auto _ : state) {
    const auto imported = io::read_obj(text, "wall.obj");
    std::vector<geometry::BlockIssue> issues;
    std::vector<geometry::ConvexPolyhedron> shapes;
    shapes.reserve(imported.size());
    for (const auto& b : imported)
      if (auto s = geometry::check_polyhedron(b, issues)) shapes.push_back(std::move(*s));
    std::vector<geometry::AssemblyBlock> assembly;
    for (std::size_t i = 0; i < shapes.size(); ++i) assembly.push_back({&shapes[i], imported[i].name, imported[i].origin, true});
    pairs = geometry::check_assembly(assembly, 1e-3, issues).pairs_tested;
    blocks = imported.size();
    errors = 0;
    for (const auto& i : issues) errors += i.severity == geometry::BlockIssue::Severity::error;
    benchmark::DoNotOptimize(issues.data());
  }
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["errors"] = static_cast<double>(errors);
  state.counters["pairs_tested"] = static_cast<double>(pairs);
  state.counters["file_MB"] = static_cast<double>(text.size()) / 1e6;
}

void BM_ImportCheck_CadTriangles(benchmark::State& state) { import_and_check(state, true); }
void BM_ImportCheck_Quads(benchmark::State& state) { import_and_check(state, false); }

}  // namespace

BENCHMARK(BM_ImportCheck_CadTriangles)->Unit(benchmark::kSecond)->Iterations(3)->Repetitions(3)->ReportAggregatesOnly(false);
BENCHMARK(BM_ImportCheck_Quads)->Unit(benchmark::kSecond)->Iterations(3)->Repetitions(3)->ReportAggregatesOnly(false);
BENCHMARK_MAIN();
