#pragma once
// Which thread does which part of the deformable step. The passes over elements, node contacts and nodes split
// their items over the threads of an OpenMP team by ranges that follow the blocks: thread t takes the nodes of a run
// of whole blocks, the elements of the same blocks and the node contacts whose node is one of those nodes (a group
// is in node order: NodeContactGroup::sort_by_node). What a thread reads in one pass it then wrote itself in the
// pass before, but for the contacts across the seam between two runs, and it stays in that core's caches.
//
// Even splits of each pass gave the threads elements, nodes and contacts of different blocks: on the deformable
// vault 10 % of the reads of element forces and 82 % of those of contact forces were of what the other thread had
// written, each a trip between two cores' caches. That is cheap when the two cores share their last-level cache and
// costs 180 ns a cache line when they do not (two vCPUs that the host places on two core complexes, for tens of
// seconds at a time here): the step then took 1,900 us on two threads against 1,470 on one (docs/performance.md).
//
// The ranges decide who computes what, never how: every item is computed alike, nothing is summed across items of
// two threads, and results do not depend on the ranges nor on the number of threads.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace blockdem::parallel {

/// Threads of the team running this code (1 outside a parallel region or without OpenMP), and this one's index.
inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}
inline int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
/// Threads a parallel region started here would get at most.
inline int available_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// Bounds of the ranges of `threads` threads over some items: threads + 1 increasing values, from 0 to the count.
using Bounds = std::vector<std::uint32_t>;

/// The items [first, end) of thread `t` of a team of `team` threads: from `bounds` when they were made for a team of
/// that size over `count` items, else an even split (a team of another size, or bounds out of date).
inline std::pair<std::size_t, std::size_t> range_of(const Bounds& bounds, std::size_t count, int t, int team) {
  if (team <= 1) return {0, count};
  if (bounds.size() == static_cast<std::size_t>(team) + 1 && bounds.back() == count)
    return {bounds[static_cast<std::size_t>(t)], bounds[static_cast<std::size_t>(t) + 1]};
  const auto cut = [&](int i) { return count * static_cast<std::size_t>(i) / static_cast<std::size_t>(team); };
  return {cut(t), cut(t + 1)};
}

/// The calling thread's range in its team (range_of).
inline std::pair<std::size_t, std::size_t> my_range(const Bounds& bounds, std::size_t count) {
  return range_of(bounds, count, thread_index(), team_size());
}

}  // namespace blockdem::parallel
