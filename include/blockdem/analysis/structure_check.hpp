#pragma once
// The checks `blockdem check` runs and `blockdem run` runs first (docs/geometry-import.md): those of the assembly
// (geometry/assembly_check.hpp) over a structure's blocks as placed, and the text that lists what they found.

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "blockdem/analysis/structure.hpp"
#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"

namespace blockdem::analysis {

/// Overlaps deeper than the structure's contact tolerance, free blocks that touch nothing and repeated names;
/// `origins` (optional, one per block) say where each block is defined.
inline geometry::AssemblyCheck check_structure(const Structure& s, std::vector<geometry::BlockIssue>& issues,
                                               const std::vector<std::string>& origins = {}) {
  const auto& b = s.model.bodies;
  std::vector<geometry::ConvexPolyhedron> world(b.size());
  std::vector<geometry::AssemblyBlock> blocks(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    world[i] = b.world_shape(i);
    blocks[i] = {&world[i], b.name[i], i < origins.size() ? origins[i] : "", b.motion[i] == model::Motion::free};
  }
  return geometry::check_assembly(blocks, s.contacts.tolerance, issues);
}

inline std::size_t count_issues(const std::vector<geometry::BlockIssue>& issues, geometry::BlockIssue::Severity severity) {
  std::size_t n = 0;
  for (const auto& i : issues) n += i.severity == severity;
  return n;
}

/// One line per error and warning ("error: block 'c3 u5' (walls.obj:120): not convex: ..."), at most `most` of each,
/// and the notes counted by what they say unless `notes` (then one line each).
inline std::string issues_text(const std::vector<geometry::BlockIssue>& issues, std::size_t most = 50, bool notes = false) {
  using Severity = geometry::BlockIssue::Severity;
  std::string out;
  for (const auto severity : {Severity::error, Severity::warning}) {
    std::size_t shown = 0, all = 0;
    for (const auto& i : issues) {
      if (i.severity != severity) continue;
      if (all++ >= most) continue;
      ++shown;
      out += std::string(geometry::BlockIssue::severity_name(severity)) + ": " + i.subject() + ": " + i.what + "\n";
    }
    if (all > shown) out += "... and " + std::to_string(all - shown) + " more " + geometry::BlockIssue::severity_name(severity) + "s\n";
  }
  if (notes) {
    for (const auto& i : issues)
      if (i.severity == Severity::note)
        out += "note: " + i.subject() + ": " + i.what + "\n";
  } else {
    std::map<std::string, std::size_t> kinds;  // the note's text up to its first digit-free colon: what was done
    for (const auto& i : issues)
      if (i.severity == Severity::note) ++kinds[i.what.find("merged") != std::string::npos ? "faces on one plane merged into one face"
                                                : i.what.find("moved") != std::string::npos ? "corners moved onto their faces' planes"
                                                                                             : i.what];
    for (const auto& [what, n] : kinds) out += "note: " + what + " in " + std::to_string(n) + " block" + (n > 1 ? "s" : "") + "\n";
  }
  return out;
}

}  // namespace blockdem::analysis
