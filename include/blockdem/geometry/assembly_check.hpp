#pragma once
// The checks of an assembly of convex blocks as a whole: names given twice, two blocks overlapping by more than the
// contact tolerance (by pair and depth) and blocks that touch nothing. Pairs come from a sweep over bounding boxes
// (sort and prune along the longest side of the assembly), so 10,000 blocks check in about a second.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "blockdem/core/number_text.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/geometry/queries.hpp"

namespace blockdem::geometry {

/// A block of the assembly, as the checks see it.
struct AssemblyBlock {
  const ConvexPolyhedron* shape = nullptr;  // world, m
  std::string name, origin;
  bool free = true;  // false: fixed or a base block (a pair of them may overlap; it need not touch anything)
};

struct AssemblyCheck {
  std::size_t pairs_tested = 0;  // pairs whose bounding boxes meet, tested by separating axes
  double deepest_overlap = 0;    // m (>= 0)
};

/// Appends to `issues` what makes the assembly unusable: overlaps deeper than `tolerance` (m) between blocks not both
/// fixed (errors), free blocks within `tolerance` of no other block (errors; warnings for fixed ones), and names given
/// to more than one block (warnings: such blocks can be used, but not referred to by name).
inline AssemblyCheck check_assembly(const std::vector<AssemblyBlock>& blocks, double tolerance, std::vector<BlockIssue>& issues) {
  using Severity = BlockIssue::Severity;
  const std::size_t n = blocks.size();
  AssemblyCheck result;
  {
    std::map<std::string, std::vector<std::size_t>> by_name;
    for (std::size_t i = 0; i < n; ++i) by_name[blocks[i].name].push_back(i);
    for (const auto& [name, list] : by_name)
      if (list.size() > 1) {
        std::string where;
        for (std::size_t k = 0; k < list.size() && k < 4; ++k) where += (k ? ", " : "") + (blocks[list[k]].origin.empty() ? "block " + std::to_string(list[k]) : blocks[list[k]].origin);
        issues.push_back({Severity::warning, name, blocks[list[0]].origin,
                          "the name is given to " + std::to_string(list.size()) + " blocks (" + where + (list.size() > 4 ? ", ..." : "") +
                              "): refer to them by index, or rename them"});
      }
  }
  if (n == 0) return result;
  std::vector<Vec3> lo(n), hi(n);
  Vec3 all_lo = Vec3::Constant(std::numeric_limits<double>::infinity()), all_hi = -all_lo;
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = hi[i] = blocks[i].shape->vertices.front();
    for (const auto& x : blocks[i].shape->vertices) {
      lo[i] = lo[i].cwiseMin(x);
      hi[i] = hi[i].cwiseMax(x);
    }
    lo[i].array() -= tolerance;
    hi[i].array() += tolerance;
    all_lo = all_lo.cwiseMin(lo[i]);
    all_hi = all_hi.cwiseMax(hi[i]);
  }
  int axis = 0;
  (all_hi - all_lo).maxCoeff(&axis);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo[a][axis] < lo[b][axis]; });
  std::vector<char> touches(n, 0);
  struct Overlap {
    std::size_t a, b;
    double depth;
  };
  std::vector<Overlap> overlaps;
  for (std::size_t u = 0; u < n; ++u)
    for (std::size_t w = u + 1; w < n && lo[order[w]][axis] <= hi[order[u]][axis]; ++w) {
      const std::size_t a = std::min(order[u], order[w]), b = std::max(order[u], order[w]);
      if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
      ++result.pairs_tested;
      const double s = separation(*blocks[a].shape, *blocks[b].shape);
      if (s > tolerance) continue;
      touches[a] = touches[b] = 1;
      if (-s > tolerance && (blocks[a].free || blocks[b].free)) overlaps.push_back({a, b, -s});
      if (blocks[a].free || blocks[b].free) result.deepest_overlap = std::max(result.deepest_overlap, -s);
    }
  std::sort(overlaps.begin(), overlaps.end(), [](const Overlap& x, const Overlap& y) { return x.depth > y.depth; });
  for (const auto& o : overlaps)
    issues.push_back({Severity::error, blocks[o.a].name, blocks[o.a].origin,
                      "overlaps '" + blocks[o.b].name + "'" + (blocks[o.b].origin.empty() ? "" : " (" + blocks[o.b].origin + ")") + " by " +
                          num(o.depth) + " m, more than the contact tolerance " + num(tolerance) + " m"});
  for (std::size_t i = 0; i < n; ++i)
    if (!touches[i] && n > 1)
      issues.push_back({blocks[i].free ? Severity::error : Severity::warning, blocks[i].name, blocks[i].origin,
                        std::string("touches no other block (none within the contact tolerance ") + num(tolerance) + " m)" +
                            (blocks[i].free ? ": it would fall" : "")});
  return result;
}

}  // namespace blockdem::geometry
