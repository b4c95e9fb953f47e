#pragma once
// Running a simulation for a duration: a progress line (simulated time of this run, steps per second, ETA) on
// stderr, and a clean stop on Ctrl-C (SIGINT) or SIGTERM that keeps everything written so far.

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <functional>
#include <type_traits>
#include <utility>

namespace blockdem {

namespace detail {
inline std::atomic<bool>& interrupt_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}
extern "C" inline void blockdem_on_signal(int) { interrupt_flag().store(true); }
}  // namespace detail

/// Installs handlers so that SIGINT and SIGTERM ask running simulations to stop after the current step.
inline void stop_on_interrupt() {
  std::signal(SIGINT, detail::blockdem_on_signal);
  std::signal(SIGTERM, detail::blockdem_on_signal);
}
inline bool interrupted() { return detail::interrupt_flag().load(std::memory_order_relaxed); }

struct RunOptions {
  bool progress = true;                 // a progress line on stderr, refreshed about once a second
  const char* label = "run";
};

struct RunSummary {
  long long steps = 0;
  double wall_seconds = 0;
  bool interrupted = false;  // stopped before t_end: by a signal, or by each_step
  bool stopped_by_caller = false;  // each_step returned false (the caller says why)
};

/// Steps `simulation` until its time reaches `t_end` (s; the last step may end half a step short of it), calling
/// `each_step()` after every step (for recorders; if it returns bool, false stops the run as an interrupt does, and
/// the caller reports why). Stops early, with `interrupted` set, on SIGINT/SIGTERM once stop_on_interrupt() was
/// called, and says so on stderr. The number of steps depends only on the simulation's time and t_end, so a run
/// continued from a checkpoint ends on the same step.
template <class Simulation, class EachStep = void (*)()>
RunSummary run_until(Simulation& simulation, double t_end, EachStep each_step = [] {}, RunOptions options = {}) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_print = start;
  const double t_start = simulation.time();
  const double duration = t_end - t_start;
  RunSummary summary;
  while (simulation.time() < t_end - 0.5 * simulation.timestep()) {
    if (interrupted()) {
      summary.interrupted = true;
      break;
    }
    simulation.step();
    ++summary.steps;
    if constexpr (std::is_same_v<decltype(each_step()), bool>) {
      if (!each_step()) {
        summary.interrupted = summary.stopped_by_caller = true;
        break;
      }
    } else {
      each_step();
    }
    if (options.progress && (summary.steps & 255) == 0) {
      const auto now = clock::now();
      if (now - last_print > std::chrono::seconds(1)) {
        last_print = now;
        const double wall = std::chrono::duration<double>(now - start).count();
        const double done = (simulation.time() - t_start) / duration;
        const double eta = done > 0 ? wall * (1 - done) / done : 0;
        std::fprintf(stderr, "\r%s: t = %.4f / %.4f s, %.0f steps/s, ETA %.0f s   ", options.label,
                     simulation.time() - t_start, duration, summary.steps / wall, eta);
        std::fflush(stderr);
      }
    }
  }
  summary.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  if (options.progress && summary.wall_seconds > 1.0) std::fprintf(stderr, "\n");
  if (summary.interrupted && !summary.stopped_by_caller) std::fprintf(stderr, "%s: stopped at t = %.4f s; results so far are kept\n", options.label, simulation.time());
  return summary;
}

/// run_until() for `duration` s from the simulation's current time.
template <class Simulation, class EachStep = void (*)()>
RunSummary run_for(Simulation& simulation, double duration, EachStep each_step = [] {}, RunOptions options = {}) {
  return run_until(simulation, simulation.time() + duration, std::move(each_step), options);
}

}  // namespace blockdem
