#pragma once
// The checks `blockdem check` runs and `blockdem run` runs first (docs/geometry-import.md): those of the assembly
// (geometry/assembly_check.hpp) over a structure's blocks as placed, and the text that lists what they found.

#include <chrono>
#include <cstddef>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "blockdem/analysis/structure.hpp"
#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/model/contact_detection.hpp"

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

/// What `blockdem check` finds in a structure as built: the checks of check_structure(), its contact points by pair of
/// groups, and the pairs that touch without a joint law (each an error in `issues`, which also holds what the caller
/// passed in: the checks of imported blocks).
struct StructureCheck {
  geometry::AssemblyCheck assembly;
  std::vector<geometry::BlockIssue> issues;
  std::size_t contact_points = 0;
  std::map<std::pair<std::size_t, std::size_t>, long long> contact_points_by_pair;  // group indices, first <= second
  double detection_seconds = 0;
};

/// check_structure() and the contacts of `s` as built, detected with `kinds` (the study's).
inline StructureCheck check_structure_contacts(const Structure& s, model::ContactKinds kinds, std::vector<geometry::BlockIssue> issues,
                                               const std::vector<std::string>& origins = {}) {
  StructureCheck c;
  c.assembly = check_structure(s, issues, origins);
  auto settings = s.contacts;
  settings.kinds = kinds;
  s.laws.fill(settings);
  const auto t0 = std::chrono::steady_clock::now();
  const auto contacts = model::detect_contacts(s.model.bodies, settings);
  c.detection_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.contact_points = contacts.size();
  for (const auto& p : contacts) {
    auto ta = static_cast<std::size_t>(s.model.bodies.joint_tag[p.a]), tb = static_cast<std::size_t>(s.model.bodies.joint_tag[p.b]);
    if (ta > tb) std::swap(ta, tb);
    ++c.contact_points_by_pair[{ta, tb}];
  }
  for (const auto& [pair, n] : c.contact_points_by_pair)
    if (!s.laws.has(pair.first, pair.second))
      issues.push_back({geometry::BlockIssue::Severity::error, "*", "",
                        "groups '" + s.laws.name(pair.first) + "' and '" + s.laws.name(pair.second) + "' touch (" + std::to_string(n) +
                            " contact points) without a joint law: add the pair to \"joints\""});
  c.issues = std::move(issues);
  return c;
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

/// The checks of `blockdem check` that a run makes first: throws InvalidArgument listing what makes blocks of `s`
/// unusable; returns the warnings, one line each ("block 'c3 u5' (walls.obj:120): ..."). `issues`: those found so far
/// (a model file's imported blocks); `origins`: where each block is defined; `path`: the file, in the message.
inline std::vector<std::string> refuse_unusable(const Structure& s, std::vector<geometry::BlockIssue> issues,
                                                const std::vector<std::string>& origins, const std::string& path) {
  check_structure(s, issues, origins);
  if (count_issues(issues, geometry::BlockIssue::Severity::error) > 0) {
    std::string text = issues_text(issues);
    text.pop_back();
    throw InvalidArgument(path + ": the model cannot be run (blockdem check " + path + " says the same):\n" + text);
  }
  std::vector<std::string> warnings;
  for (const auto& i : issues)
    if (i.severity == geometry::BlockIssue::Severity::warning) warnings.push_back(i.subject() + ": " + i.what);
  return warnings;
}

}  // namespace blockdem::analysis
