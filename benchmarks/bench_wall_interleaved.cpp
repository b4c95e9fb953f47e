// The cost of Maxwell<3> relative to MassProportional (and of None) per step on the wall of bench_wall, measured
// so that a noisy machine does not decide the answer: the three simulations live in one process and take turns,
// a few steps each, so that whatever slows the machine down slows all three alike; every step is timed on its
// own, and the report gives quantiles of the step times (the low ones are the least disturbed) and their ratios.
//
//   bench_wall_interleaved [--law elastic|mohr-coulomb|softening] [--rounds 50] [--steps-per-turn 8] [--threads 1]
//
// With --threads N > 1 every turn is run twice, on one thread and on N, and the report adds the speed-up of N
// threads over one at each quantile (results do not depend on the number of threads, so the runs stay alike).
//
// A ratio of two quantiles compares two distributions, each with its own share of disturbed steps. The report also
// pairs the turns: per round, the ratio of the median steps of two policies' turns (a few milliseconds apart, under the
// same conditions), and per turn the speed-up of N threads; then quantiles of those paired ratios. When the host
// slows everything down for a while, both turns of a pair are slow and their ratio keeps the cost of the code.
//
// On a virtual machine whose other tenants come and go, a whole benchmark run of one binary can be 30 % slower
// than the next; the ratio of two runs is then noise. Taking turns within one process keeps the ratio to about
// 1 %, run to run.

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "blockdem/integrate/simulation.hpp"
#include "wall_model.hpp"

namespace {

using namespace blockdem;
using namespace blockdem::benchmarks;

/// The q-quantile of step times (us).
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

/// One simulation of the wall and the times of its steps (us) on one thread and on several.
template <class Law, class Damping>
struct Contender {
  std::unique_ptr<model::Model> model = std::make_unique<model::Model>(make_wall());
  Simulation<Damping, Law> simulation{*model, make_damping<Damping>(), [](int, int) { return parameters<Law>(); }};
  std::vector<double> step_us, threaded_step_us;
  std::vector<double> turn_us, threaded_turn_us;  // the median step of each turn

  Contender() {
    for (int i = 0; i < 20; ++i) simulation.step();  // warm up, let it settle a little (as bench_wall)
  }
  /// Runs `steps` steps on one thread, then as many on `threads` if more than one; the first step of each is not
  /// kept (its data were pushed out of the caches by the others).
  void turn(int steps, int threads) {
    run(steps, 1, step_us, turn_us);
    if (threads > 1) run(steps, threads, threaded_step_us, threaded_turn_us);
  }

 private:
  void run(int steps, int threads, std::vector<double>& into, std::vector<double>& turns) {
    omp_set_num_threads(threads);
    const std::size_t before = into.size();
    for (int i = 0; i < steps; ++i) {
      const auto start = std::chrono::steady_clock::now();
      simulation.step();
      const auto stop = std::chrono::steady_clock::now();
      if (i > 0) into.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    }
    turns.push_back(quantile({into.begin() + static_cast<std::ptrdiff_t>(before), into.end()}, 0.5));
  }
};

/// Quantiles q25 / q50 / q75 of the paired ratios top[i] / bottom[i].
void report_paired(const char* what, const std::vector<double>& top, const std::vector<double>& bottom) {
  std::vector<double> r(top.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = top[i] / bottom[i];
  std::printf("  %-38s %.3f  %.3f  %.3f\n", what, quantile(r, 0.25), quantile(r, 0.5), quantile(r, 0.75));
}

/// The table of one thread count: step times, ns per CP-step and the Maxwell<3>/Mass ratio at three quantiles.
void report(const std::vector<double>& none, const std::vector<double>& mass, const std::vector<double>& maxwell, double points) {
  std::printf("quantile | us per step: None  Mass  Maxwell<3> | ns per CP-step: None  Mass  Maxwell<3> | Maxwell<3> / Mass\n");
  for (const double f : {0.1, 0.25, 0.5}) {
    const double n = quantile(none, f), m = quantile(mass, f), x = quantile(maxwell, f);
    std::printf("q%02.0f      | %8.1f %8.1f %8.1f | %6.1f %6.1f %6.1f | %.3f\n", 100 * f, n, m, x, 1e3 * n / points,
                1e3 * m / points, 1e3 * x / points, x / m);
  }
}

template <class Law>
void compare(const std::string& law, int rounds, int steps, int threads) {
  Contender<Law, damping::None> none;
  Contender<Law, damping::MassProportional> mass;
  Contender<Law, damping::Maxwell<3>> maxwell;
  const auto points = static_cast<double>(mass.simulation.contact_points());
  for (int r = 0; r < rounds; ++r) {
    none.turn(steps, threads);
    mass.turn(steps, threads);
    maxwell.turn(steps, threads);
  }
  std::printf("wall: %zu blocks, %.0f contact points, law %s, %d rounds of %d steps per policy\n", mass.model->bodies.size(),
              points, law.c_str(), rounds, steps);
  std::printf("1 thread\n");
  report(none.step_us, mass.step_us, maxwell.step_us, points);
  if (threads > 1) {
    std::printf("%d threads\n", threads);
    report(none.threaded_step_us, mass.threaded_step_us, maxwell.threaded_step_us, points);
    std::printf("speed-up of %d threads over 1 | None  Mass  Maxwell<3>\n", threads);
    for (const double f : {0.1, 0.25, 0.5}) {
      const auto up = [&](const auto& c) { return quantile(c.step_us, f) / quantile(c.threaded_step_us, f); };
      std::printf("q%02.0f                          | %5.2f %5.2f %5.2f\n", 100 * f, up(none), up(mass), up(maxwell));
    }
  }
  std::printf("paired (median steps of turns taken together), q25 / q50 / q75 over the %d rounds:\n", rounds);
  report_paired("Maxwell<3> / Mass, 1 thread", maxwell.turn_us, mass.turn_us);
  report_paired("Mass / None, 1 thread", mass.turn_us, none.turn_us);
  if (threads > 1) {
    report_paired(("Maxwell<3> / Mass, " + std::to_string(threads) + " threads").c_str(), maxwell.threaded_turn_us,
                  mass.threaded_turn_us);
    const auto speed_up = [&](const char* name, const auto& c) {
      report_paired(("speed-up of " + std::to_string(threads) + " threads, " + name).c_str(), c.turn_us, c.threaded_turn_us);
    };
    speed_up("None", none);
    speed_up("Mass", mass);
    speed_up("Maxwell<3>", maxwell);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Maxwell<3> against MassProportional and None on the bench_wall wall, taking turns in one process"};
  std::string law = "elastic";
  int rounds = 50, steps = 8, threads = 1;
  std::vector<std::string> laws;  // every shipped law, by its option name
  for_each_type<contact::ShippedLaws>([&](auto each) { laws.push_back(law_option<typename decltype(each)::type>()); });
  app.add_option("--law", law, "joint law")->check(CLI::IsMember(laws));
  app.add_option("--rounds", rounds, "turns per policy")->check(CLI::Range(1, 100000));
  app.add_option("--steps-per-turn", steps, "steps per turn (the first of each is not timed)")->check(CLI::Range(2, 100000));
  app.add_option("--threads", threads, "OpenMP threads besides one (each turn also run on this many)")->check(CLI::Range(1, 1024));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  for_each_type<contact::ShippedLaws>([&](auto each) {
    using Law = typename decltype(each)::type;
    if (law == law_option<Law>()) compare<Law>(law, rounds, steps, threads);
  });
}
