#pragma once
// Sharing out independent tasks (the cases of a sweep) over the processes of a run. A farm runs
// `work(k, poll) -> std::string` for every task k exactly once somewhere and hands the lead process every task's
// result, in task order; `poll` is what a task calls now and then during a long computation (the MPI farm's lead
// answers its workers there). SerialFarm runs the tasks one after another in this process; MpiFarm
// (parallel/mpi_farm.hpp, only with MPI) hands them out one at a time to every rank, the lead included.
// After an interrupt (SIGINT/SIGTERM with stop_on_interrupt()) no task is started; those never started come back empty.

#include <concepts>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/integrate/run.hpp"

namespace blockdem::parallel {

using Poll = std::function<void()>;

template <class F>
concept FarmWork = std::invocable<F&, std::size_t, const Poll&> &&
                   std::convertible_to<std::invoke_result_t<F&, std::size_t, const Poll&>, std::string>;

/// A farm: which process this is (rank, of size; the lead gets the results) and run(tasks, work).
template <class F>
concept TaskFarm = requires(const F& farm) {
  { farm.rank() } -> std::convertible_to<int>;
  { farm.size() } -> std::convertible_to<int>;
  { farm.lead() } -> std::convertible_to<bool>;
  { farm.serve_seconds() } -> std::convertible_to<double>;
};

/// Every task in order, in this process; each gets `poll` (may be empty: Python's Ctrl-C is heard there).
class SerialFarm {
 public:
  explicit SerialFarm(Poll poll = {}) : poll_(std::move(poll)) {}
  int rank() const { return 0; }
  int size() const { return 1; }
  bool lead() const { return true; }
  double serve_seconds() const { return 0; }

  template <FarmWork Work>
  std::vector<std::string> run(std::size_t tasks, Work&& work) {
    std::vector<std::string> out(tasks);
    for (std::size_t k = 0; k < tasks && !interrupted(); ++k) out[k] = work(k, poll_);
    return out;
  }

 private:
  Poll poll_;
};

}  // namespace blockdem::parallel
