#pragma once
// Results must not depend on the number of OpenMP threads (forces are gathered in a fixed order, no atomics).

#include <cstddef>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace blockdem::test {

/// `n` OpenMP threads while it lives, the number of processors again afterwards.
struct ScopedThreads {
  explicit ScopedThreads(int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
  }
  ~ScopedThreads() {
#ifdef _OPENMP
    omp_set_num_threads(omp_get_num_procs());
#endif
  }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;
};

/// Runs `run()` (returning a vector of values) on one thread and on two, and counts the entries that differ; the
/// thread count is the number of processors again afterwards, also when `run` throws.
template <class Run>
std::size_t differences_between_one_and_two_threads(Run run) {
  const auto on = [&](int threads) {
    const ScopedThreads scoped(threads);
    return run();
  };
  const auto one = on(1);
  const auto two = on(2);
  if (one.size() != two.size()) return one.size() + two.size();
  std::size_t different = 0;
  for (std::size_t i = 0; i < one.size(); ++i)
    if (one[i] != two[i]) ++different;
  return different;
}

/// One OpenMP thread for a test case (ctest runs two tests at once on two cores; threads that wait on a busy core
/// slow a run many times over).
struct OneThread : ScopedThreads {
  OneThread() : ScopedThreads(1) {}
};

}  // namespace blockdem::test
