#pragma once
// Blocks of a model file that come from geometry files (docs/geometry-import.md): an entry of "blocks" with
// "geometry": "walls.obj" takes every block of the file whose name matches "objects" (a pattern with * and ?; all of
// them by default) and that no earlier entry took, each checked by geometry/polyhedron_check.hpp; what cannot be used is gathered over all entries
// and refused at once, naming every block and its problem.

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/geometry/imported_block.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/geometry_file.hpp"
#include "blockdem/io/json_fields.hpp"

namespace blockdem::analysis::detail {

/// True if `name` matches `pattern`: '*' any run of characters, '?' any one.
inline bool name_matches(std::string_view pattern, std::string_view name) {
  std::size_t p = 0, n = 0, star = std::string_view::npos, mark = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
      ++p;
      ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = n;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      n = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

/// The geometry files a model file names, each read once, and which entry took each of their blocks.
struct GeometryFiles {
  struct File {
    std::vector<geometry::ImportedBlock> blocks;
    std::vector<std::string> taken_by;  // the entry's path ("blocks[2]") that took each block, "" none
  };
  std::map<std::string, File> files;
  std::vector<geometry::BlockIssue> issues;  // of every block taken, in order
  std::size_t unusable = 0;

  /// The usable blocks an entry takes (name, group, shape, origin); their problems go to `issues`.
  struct Taken {
    std::string name, group, origin;
    geometry::ConvexPolyhedron shape;
  };
  std::vector<Taken> take(const io::JsonFields& f, const std::string& base_dir) {
    const auto& file_value = f.required("geometry", "a geometry file: " + std::string(io::geometry_extensions()));
    const std::string& file_name = io::string_value(file_value, f.path("geometry"));
    const std::string path = base_dir.empty() || std::filesystem::path(file_name).is_absolute()
                                 ? file_name
                                 : (std::filesystem::path(base_dir) / file_name).string();
    auto it = files.find(path);
    if (it == files.end()) {
      try {
        auto blocks = io::read_geometry_file(path);
        const std::size_t n = blocks.size();
        it = files.emplace(path, File{std::move(blocks), std::vector<std::string>(n)}).first;
      } catch (const InvalidArgument& e) {
        io::field_error(file_value, f.path("geometry"), e.what());
      } catch (const InputError& e) {
        io::field_error(file_value, f.path("geometry"), e.what());
      }
    }
    File& file = it->second;
    const std::string pattern = f.string("objects", "*");
    geometry::PolyhedronCheckOptions check;
    check.planarity = f.number("planarity_tolerance", check.planarity, {0, 0.1, true, false, "of the block's size"});
    std::vector<Taken> out;
    std::size_t matched = 0, refused = 0;
    for (std::size_t i = 0; i < file.blocks.size(); ++i) {
      const auto& b = file.blocks[i];
      if (!name_matches(pattern, b.name)) continue;
      ++matched;
      if (!file.taken_by[i].empty()) continue;  // an earlier entry took it: the first entry that matches a block wins
      file.taken_by[i] = f.path();
      auto shape = geometry::check_polyhedron(b, issues, check);
      if (!shape) {
        ++refused;
        continue;
      }
      out.push_back({b.name, b.group, b.origin, std::move(*shape)});
    }
    unusable += refused;
    if (out.empty() && refused == 0) {
      std::string names;
      for (std::size_t i = 0; i < file.blocks.size() && i < 5; ++i) names += (i ? ", " : "") + ("'" + file.blocks[i].name + "'");
      if (file.blocks.size() > 5) names += ", ...";
      const auto& at = f.has("objects") ? *f.find("objects") : file_value;
      const std::string at_path = f.has("objects") ? f.path("objects") : f.path("geometry");
      if (matched > 0)
        io::field_error(at, at_path, "every block of " + file_name + " that matches \"" + pattern + "\" is taken by an earlier entry");
      io::field_error(at, at_path, "no block of " + file_name + " matches \"" + pattern + "\" (" + std::to_string(file.blocks.size()) +
                                       " blocks: " + names + ")");
    }
    return out;
  }

  /// Warns of the blocks of a file that no entry took, then throws InvalidArgument listing every block that cannot be
  /// used, if any.
  void finish(const std::string& source) {
    for (const auto& [path, file] : files) {
      std::string names;
      std::size_t left = 0;
      for (std::size_t i = 0; i < file.blocks.size(); ++i)
        if (file.taken_by[i].empty() && left++ < 5) names += (left > 1 ? ", '" : "'") + file.blocks[i].name + "'";
      if (left > 0)
        issues.push_back({geometry::BlockIssue::Severity::warning, "", path,
                          std::to_string(left) + " block" + (left > 1 ? "s" : "") + " of " + path + " taken by no entry of \"blocks\" (" + names +
                              (left > 5 ? ", ...)" : ")") + ": left out of the model"});
    }
    if (unusable == 0) return;
    std::string list;
    for (const auto& i : issues)
      if (i.severity == geometry::BlockIssue::Severity::error)
        list += "\n  '" + i.block + "' (" + i.origin + "): " + i.what;
    throw InvalidArgument(source + ": " + std::to_string(unusable) + " block" + (unusable > 1 ? "s" : "") +
                          " of the geometry files cannot be used:" + list);
  }
};

}  // namespace blockdem::analysis::detail
