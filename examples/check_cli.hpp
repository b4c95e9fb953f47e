#pragma once
// `blockdem check FILE`: a model file, or a geometry file alone (OBJ, a 3DEC deck, a COMPAS assembly), read and
// checked: the number of blocks, then each problem by block (docs/geometry-import.md); exit status 2 when a block
// cannot be used. `blockdem export FILE OUT`: the blocks of either written as OBJ or a 3DEC deck.

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/geometry_file.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "cli.hpp"

namespace blockdem::programs {

/// True if `path` is a model file: a .json whose text has the key "blockdem_model" (a COMPAS file has not).
inline bool is_model_file(const std::string& path) {
  if (io::geometry_format(path) != io::GeometryFormat::compas) return false;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str().find("\"blockdem_model\"") != std::string::npos;
}

inline io::JsonObject issues_json(const std::vector<geometry::BlockIssue>& issues) {
  io::JsonObject out;
  std::vector<std::string> lines[3];
  for (const auto& i : issues)
    lines[static_cast<int>(i.severity)].push_back(i.subject() + ": " + i.what);
  out.add("errors", lines[2]).add("warnings", lines[1]).add("notes", lines[0]);
  return out;
}

struct CheckCommand {
  std::string path;
  bool json = false, notes = false;
  double tolerance = 1e-3, planarity = geometry::PolyhedronCheckOptions{}.planarity;

  void add_to(CLI::App& app) {
    app.add_option("file", path, std::string("a model file (JSON, docs/model-file.md) or a geometry file: ") + io::geometry_extensions())
        ->required();
    app.add_flag("--json", json, "print JSON");
    app.add_flag("--notes", notes, "list every note (what was repaired: corners welded, faces merged), not only their counts");
    app.add_option("--tolerance", tolerance, "contact tolerance of a geometry file alone, m: closer blocks touch, deeper overlaps are errors")
                           ->check(CLI::Range(1e-7, 1.0));
    app.add_option("--planarity", planarity, "of a geometry file alone: how far a corner may lie off its face's plane, as a fraction of the block's size")
        ->check(CLI::Range(1e-12, 0.1));
  }

  int run() const {
    if (is_model_file(path)) return check_model();
    return check_geometry();
  }

  int finish(const std::vector<geometry::BlockIssue>& issues) const {
    const auto errors = analysis::count_issues(issues, geometry::BlockIssue::Severity::error);
    if (!json) {
      fmt::print("{}", analysis::issues_text(issues, 50, notes));
      if (errors > 0) std::fprintf(stderr, "blockdem check: %s: %zu problem%s make%s blocks unusable (listed above)\n", path.c_str(), errors,
                                   errors > 1 ? "s" : "", errors > 1 ? "" : "s");
    }
    return errors > 0 ? exit_bad_input : 0;
  }

  /// A geometry file alone: each block's checks, then the assembly's over the usable blocks (all taken as free).
  int check_geometry() const {
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    const auto blocks = io::read_geometry_file(path);
    const double read_seconds = std::chrono::duration<double>(clock::now() - t0).count();
    const auto t1 = clock::now();
    std::vector<geometry::BlockIssue> issues;
    geometry::PolyhedronCheckOptions o;
    o.planarity = planarity;
    std::vector<geometry::ConvexPolyhedron> shapes;
    std::vector<std::size_t> of;
    shapes.reserve(blocks.size());
    for (std::size_t i = 0; i < blocks.size(); ++i)
      if (auto s = geometry::check_polyhedron(blocks[i], issues, o)) {
        shapes.push_back(std::move(*s));
        of.push_back(i);
      }
    std::vector<geometry::AssemblyBlock> assembly;
    for (std::size_t k = 0; k < shapes.size(); ++k) assembly.push_back({&shapes[k], blocks[of[k]].name, blocks[of[k]].origin, true});
    const auto a = geometry::check_assembly(assembly, tolerance, issues);
    const double check_seconds = std::chrono::duration<double>(clock::now() - t1).count();
    double volume = 0;
    for (const auto& s : shapes) volume += geometry::mass_properties(s).volume;
    std::map<std::string, std::size_t> groups;
    for (const auto& b : blocks) ++groups[b.group];
    if (json) {
      io::JsonObject out, by_group;
      for (const auto& [g, n] : groups) by_group.add(g, static_cast<long long>(n));
      out.add("file", path).add("blocks", static_cast<long long>(blocks.size())).add("usable_blocks", static_cast<long long>(shapes.size()))
          .add("groups", by_group).add("volume_m3", volume).add("pairs_tested", static_cast<long long>(a.pairs_tested))
          .add("deepest_overlap_m", a.deepest_overlap).add("contact_tolerance_m", tolerance).add("issues", issues_json(issues))
          .add("read_seconds", read_seconds).add("check_seconds", check_seconds);
      fmt::print("{}\n", out.str());
    } else {
      fmt::print("{}: {} blocks ({} usable), {:.6g} m^3; groups:", path, blocks.size(), shapes.size(), volume);
      for (const auto& [g, n] : groups) fmt::print(" {} ({})", g.empty() ? "none" : "'" + g + "'", n);
      fmt::print("\n{} pairs within reach tested for overlaps (contact tolerance {:g} m), deepest overlap {:.3g} m; read in {:.2f} s, "
                 "checked in {:.2f} s\n", a.pairs_tested, tolerance, a.deepest_overlap, read_seconds, check_seconds);
    }
    return finish(issues);
  }

  /// A model file: the model as built, its contacts, the pairs of groups that touch without a law, and the checks.
  int check_model() const {
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    const auto file = analysis::read_model_file(path);
    const double load_seconds = std::chrono::duration<double>(clock::now() - t0).count();
    const auto& s = file.structure;
    s.validate();
    const auto c = analysis::check_structure_contacts(s, file.study.contacts, file.geometry_issues, file.block_origin);
    const auto& a = c.assembly;
    const auto& issues = c.issues;
    const auto& by_pair = c.contact_points_by_pair;
    const auto contacts = c.contact_points;
    const double detection_seconds = c.detection_seconds;
    if (json) {
      io::JsonObject out, pairs;
      for (const auto& [pair, n] : by_pair) pairs.add(s.laws.name(pair.first) + "-" + s.laws.name(pair.second), n);
      out.add("model", s.name).add("blocks", static_cast<long long>(s.model.bodies.size()))
          .add("deformable_blocks", static_cast<long long>(s.model.deformable.blocks.size()))
          .add("tetrahedra", static_cast<long long>(s.model.deformable.tetrahedra.size()))
          .add("ties", static_cast<long long>(s.model.deformable.trusses.size())).add("groups", s.groups())
          .add("free_mass_kg", s.model.total_mass()).add("contact_points", static_cast<long long>(contacts))
          .add("contact_points_by_group_pair", pairs).add("deepest_overlap_m", a.deepest_overlap)
          .add("monitor_points", static_cast<long long>(s.monitors.size())).add("table", s.table ? s.model.bodies.name[*s.table] : "")
          .add("issues", issues_json(issues)).add("load_seconds", load_seconds).add("detection_seconds", detection_seconds);
      fmt::print("{}\n", out.str());
    } else {
      fmt::print("model '{}': {} blocks ({} deformable, {} tetrahedra), {} ties, {:.1f} kg free; groups:", s.name, s.model.bodies.size(),
                 s.model.deformable.blocks.size(), s.model.deformable.tetrahedra.size(), s.model.deformable.trusses.size(), s.model.total_mass());
      for (const auto& g : s.groups()) fmt::print(" {}", g);
      fmt::print("\n{} contact points:", contacts);
      for (const auto& [pair, n] : by_pair) fmt::print(" {}-{} {}", s.laws.name(pair.first), s.laws.name(pair.second), n);
      fmt::print("\nmonitor points:");
      for (const auto& m : s.monitors) fmt::print(" {} (block '{}')", m.name, s.model.bodies.name[m.block]);
      fmt::print("\ntable: {}\ndeepest overlap {:.3g} m (contact tolerance {:g} m); read and built in {:.2f} s, contacts detected in {:.2f} s\n",
                 s.table ? "'" + s.model.bodies.name[*s.table] + "'" : std::string("none (no base block: no record can move it)"),
                 a.deepest_overlap, s.contacts.tolerance, load_seconds, detection_seconds);
    }
    return finish(issues);
  }
};

/// `blockdem export FILE OUT`: the blocks of a model file (as placed, with their groups) or of a geometry file (as
/// checked: welded, merged, turned outward), written as OBJ or a 3DEC deck by OUT's extension.
struct ExportCommand {
  std::string path, out;

  void add_to(CLI::App& app) {
    app.add_option("file", path, "a model file or a geometry file")->required();
    app.add_option("out", out, "the file to write: .obj (Wavefront OBJ) or .3ddat (a 3DEC deck)")->required();
  }

  int run() const {
    if (io::geometry_format(out) == io::GeometryFormat::compas) throw InvalidArgument("'" + out + "': blockdem writes .obj or .3ddat");
    std::vector<geometry::ImportedBlock> blocks;
    std::string title;
    if (is_model_file(path)) {
      const auto file = analysis::read_model_file(path);
      const auto& b = file.structure.model.bodies;
      for (std::size_t i = 0; i < b.size(); ++i) blocks.push_back(geometry::imported_block(b.world_shape(i), b.name[i], file.structure.group_of(i)));
      title = "'" + file.structure.name + "' from " + path;
    } else {
      std::vector<geometry::BlockIssue> issues;
      for (const auto& b : io::read_geometry_file(path))
        if (auto s = geometry::check_polyhedron(b, issues)) blocks.push_back(geometry::imported_block(*s, b.name, b.group));
      if (const auto errors = analysis::count_issues(issues, geometry::BlockIssue::Severity::error))
        throw InvalidArgument(path + ": " + std::to_string(errors) + (errors > 1 ? " blocks" : " block") + " cannot be used (blockdem check " +
                              path + " lists " + (errors > 1 ? "them)" : "it)"));
      title = "from " + path;
    }
    io::write_geometry_file(out, blocks, title);
    fmt::print("{} blocks written to {}\n", blocks.size(), out);
    return 0;
  }
};

}  // namespace blockdem::programs
