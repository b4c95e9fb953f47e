// The cross vault's explicit step (paper Sect. 5-6), rigid, mixed or deformable, under MassProportional, Maxwell<3>
// and None, measured as bench_wall_interleaved measures the wall: the simulations live in one process and take
// turns, a few steps each, on one thread and on N; every step is timed on its own and the report gives quantiles,
// steps per second and paired ratios. Each simulation is the study's (the vault's structure, its joint laws, its
// contact settings), settled under local damping for a fixed number of steps first, so that the joints carry the
// vault's weight.
//
//   bench_vault_step [--kinematics rigid|mixed|deformable] [--settle-steps 2000] [--rounds 10] [--steps-per-turn 10]
//                    [--threads 2] [--passes]
//
// With two threads or more, each round starts with the time a cache line takes between the two threads, and the
// report gives the two-thread step apart for the rounds when the host ran the two vCPUs on cores with one shared
// last-level cache and for those when it ran them on two.
//
// --passes adds, for the deformable part, the cost of each pass on its own (elements, node contacts, the node
// update, the forces on rigid blocks; the rest of the step by difference), per item and per step, with the bytes
// each pass moves and the flops it does per item, against this machine's bandwidth and peak measured here (a
// streaming triad over as many bytes as the deformable state, and independent FMA chains): the roofline table of
// benchmarks/README.md.

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "blockdem/analysis/study.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/damping/maxwell_fit.hpp"

namespace {

using namespace blockdem;
using namespace blockdem::analysis;
using clock_type = std::chrono::steady_clock;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

double microseconds(clock_type::time_point a, clock_type::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

/// The vault of the options with its joints loaded: settled `settle_steps` steps under local damping at static
/// masses (as the study settles, not to its tolerance), then continued under the policy at its default timestep.
template <class D>
struct Contender {
  std::unique_ptr<Structure> structure;
  std::unique_ptr<StudySimulation<D>> simulation;
  std::vector<double> step_us, threaded_step_us;
  std::vector<double> turn_us, threaded_turn_us;

  Contender(const VaultStudyOptions& o, D policy, long long settle_steps) : structure(std::make_unique<Structure>(vault_structure(o))) {
    using Settle = StudySimulation<damping::Local>;
    model::ContactSettings contacts = structure->contacts;
    contacts.kinds = o.contacts;
    structure->laws.fill(contacts);
    Settle settle(structure->model, damping::Local{}, analysis::detail::structure_properties<Settle>(*structure), contacts);
    settle.scale_masses_for_statics(settle.timestep());
    for (long long n = 0; n < settle_steps; ++n) settle.step();
    settle.restore_real_masses();
    simulation = std::make_unique<StudySimulation<D>>(settle, policy);
    for (int i = 0; i < 5; ++i) simulation->step();
  }

  void turn(int steps, int threads) {
    run(steps, 1, step_us, turn_us);
    if (threads > 1) run(steps, threads, threaded_step_us, threaded_turn_us);
  }

 private:
  void run(int steps, int threads, std::vector<double>& into, std::vector<double>& turns) {
    omp_set_num_threads(threads);
    const std::size_t before = into.size();
    for (int i = 0; i < steps; ++i) {
      const auto start = clock_type::now();
      simulation->step();
      const auto stop = clock_type::now();
      if (i > 0) into.push_back(microseconds(start, stop));  // the first step's data were pushed out by the others
    }
    turns.push_back(quantile({into.begin() + static_cast<std::ptrdiff_t>(before), into.end()}, 0.5));
  }
};

void report_paired(const std::string& what, const std::vector<double>& top, const std::vector<double>& bottom) {
  std::vector<double> r(top.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = top[i] / bottom[i];
  std::printf("  %-40s %.3f  %.3f  %.3f\n", what.c_str(), quantile(r, 0.25), quantile(r, 0.5), quantile(r, 0.75));
}

/// The time a cache line takes from one thread to the other and back (ns, half of a round trip of a counter two
/// threads pass each other): about 25 ns when the host runs the two vCPUs on cores that share a last-level cache,
/// about 180 ns when it runs them on two core complexes, as it does for tens of seconds at a time (docs/performance.md).
double cache_trip_ns() {
  std::atomic<long> turn{0};
  constexpr long trips = 20000;
  double ns = 0;
  omp_set_num_threads(2);
#pragma omp parallel
  {
    if (omp_get_num_threads() == 2) {
      const bool first = omp_get_thread_num() == 0;
      const auto start = clock_type::now();
      for (long k = 0; k < trips; ++k) {
        if (first) {
          turn.store(2 * k + 1, std::memory_order_release);
          while (turn.load(std::memory_order_acquire) != 2 * k + 2) {}
        } else {
          while (turn.load(std::memory_order_acquire) != 2 * k + 1) {}
          turn.store(2 * k + 2, std::memory_order_release);
        }
      }
      if (first) ns = 1e3 * microseconds(start, clock_type::now()) / (2.0 * trips);
    }
  }
  return ns;
}

/// The median of the turns of `turns` whose round had split caches (or not).
double median_where(const std::vector<double>& turns, const std::vector<bool>& split, bool which, int& count) {
  std::vector<double> v;
  for (std::size_t r = 0; r < turns.size() && r < split.size(); ++r)
    if (split[r] == which) v.push_back(turns[r]);
  count = static_cast<int>(v.size());
  return quantile(v, 0.5);
}

/// A streaming triad a = b + s c over three arrays of `bytes` in all (GB/s, the best of a few sweeps), on `threads`.
double triad_bandwidth(std::size_t bytes, int threads) {
  const std::size_t n = std::max<std::size_t>(bytes / 24, 1024);
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  omp_set_num_threads(threads);
  double best = 1e30;
  for (int sweep = 0; sweep < 30; ++sweep) {
    const auto start = clock_type::now();
    const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) a[static_cast<std::size_t>(i)] = b[static_cast<std::size_t>(i)] + 0.5 * c[static_cast<std::size_t>(i)];
    best = std::min(best, microseconds(start, clock_type::now()));
    std::swap(a, b);
  }
  return 24.0 * static_cast<double>(n) / best * 1e-3;
}

/// Peak double-precision flops of one thread (GFLOP/s): independent FMA chains, vectorised by the compiler.
double peak_gflops() {
  constexpr int chains = 64;
  alignas(64) double acc[chains];
  for (int i = 0; i < chains; ++i) acc[i] = 1.0 + 1e-9 * i;
  const double m = 0.999999999, s = 1e-12;
  constexpr long long rounds = 4'000'000;
  double best = 1e30;
  for (int trial = 0; trial < 3; ++trial) {
    const auto start = clock_type::now();
    for (long long r = 0; r < rounds; ++r) {
#pragma omp simd
      for (int i = 0; i < chains; ++i) acc[i] = acc[i] * m + s;
    }
    best = std::min(best, microseconds(start, clock_type::now()));
  }
  double sum = 0;
  for (double x : acc) sum += x;
  if (sum == 0) std::printf("(never)\n");
  return 2.0 * chains * static_cast<double>(rounds) / best * 1e-3;
}

/// The cost of each pass of the deformable step on its own, on copies of the model and of the state.
template <class D>
void passes(const char* name, Contender<D>& c, int threads, int repeats) {
  const auto& sim = *c.simulation;
  const auto& m0 = sim.model();
  if (m0.deformable.empty()) return;
  model::Model m = m0;
  auto state = sim.deformable_state();
  const double dt = sim.timestep(), w = sim.closure_inverse_omega_squared();
  const auto& damping = sim.damping();
  std::size_t node_points = 0;
  state.for_each_group([&](const auto& g) { node_points += g.size(); });
  const double tets = static_cast<double>(m.deformable.tetrahedra.size()), nodes = static_cast<double>(m.deformable.nodes.size());
  struct Pass {
    const char* what;
    double items;
    double bytes, flops;  // per item
    std::vector<double> us;
  };
  // Bytes per item: what each pass reads and writes of its arrays, from the sizes of their elements, counting a node's
  // position or velocity read through an index once per use (the caches may keep it; the bound is then lower).
  // Flops per item: counted by hand in the code of each pass (multiplications, additions, a square root or a division
  // as one).
  using State = std::remove_cvref_t<decltype(state)>;
  constexpr bool tensor = State::tensor_form;
  constexpr double vec = sizeof(Vec3);
  const double element_state_bytes = static_cast<double>(sizeof(typename State::ElementState)) /
                                     (tensor ? static_cast<double>(State::element_tile) : 1.0);
  // velocities 4 x 24, gradients 96, nodes 16, material 2, volume 8, stress read and written, branch states read and
  // written, forces 96 written
  const double element_bytes = 4 * vec + 4 * vec + 16 + 2 + 8 + 2 * 48 + 2 * element_state_bytes + 4 * vec;
  double contact_bytes = 0;  // summed over the points, then per point
  state.for_each_group([&](const auto& g) {
    using G = std::remove_cvref_t<decltype(g)>;
    double b = 4 + 2 + 8 + 2.0 * sizeof(typename G::History) + 3 * 8 + vec + 2 * 8;  // node, property, area, history,
                                                                                       // traction, force, slip work
    if constexpr (damping::PerSpringDamping<D>) b += 2.0 * sizeof(typename G::SpringState) + 2 * 8;
    if constexpr (G::FaceKinematics::deformable) b += 12 + 24 + 3 * vec + 4 * vec;  // triangle, weights, x, v
    else b += 3 * vec + 2 * vec + 4 + 72 + 2 * vec + vec;  // frame in the block, node v, block, rotation, v, w, moment
    contact_bytes += b * static_cast<double>(g.size());
  });
  contact_bytes /= static_cast<double>(std::max<std::size_t>(node_points, 1));
  const double element_entries = static_cast<double>(state.element_entry.size()) / nodes;
  const double contact_entries = static_cast<double>(state.node_entry.size()) / nodes;
  // per entry: the entry and the force (elements), the entry, its coefficient and the force (contacts); per node:
  // three list heads, force written, velocity and position read and written, three masses, fixity, four energies
  // (kinetic written, the others read and written), the position at the last detection
  const double node_bytes = element_entries * (4 + vec) + contact_entries * (4 + 8 + vec) + 3 * 4 + vec + 4 * vec + 3 * 8 + 1 +
                            8 + 2 * 3 * 8 + vec;
  std::vector<Pass> p{
      {"elements", tets, element_bytes, tensor ? 260.0 : 200.0, {}},
      {"node contacts", static_cast<double>(node_points), contact_bytes, damping::PerSpringDamping<D> ? 180.0 : 150.0, {}},
      {"node update", nodes, node_bytes, 6 * (element_entries + contact_entries) + 40, {}},
      {"forces on rigid blocks", static_cast<double>(m.bodies.size()), 0, 0, {}},
  };
  omp_set_num_threads(threads);
  for (int r = 0; r < repeats; ++r) {
    auto t0 = clock_type::now();
    node_contact_passes(state, m, damping, dt, w);
    auto t1 = clock_type::now();
    element_pass(state, m, damping, dt);
    auto t2 = clock_type::now();
    gather_rigid(state, m, dt);
    auto t3 = clock_type::now();
    node_pass(state, m, damping, dt, dt, true, 1e9);
    auto t4 = clock_type::now();
    p[1].us.push_back(microseconds(t0, t1));
    p[0].us.push_back(microseconds(t1, t2));
    p[3].us.push_back(microseconds(t2, t3));
    p[2].us.push_back(microseconds(t3, t4));
  }
  // The whole step: the median of the turns on as many threads (the passes run on copies of the state, which the
  // step would push out of the caches if it ran between them).
  const double step = quantile(threads > 1 ? c.threaded_step_us : c.step_us, 0.5);
  std::printf("%s, %d thread%s: step %.0f us (the turns' median), passes the median of %d\n", name, threads, threads > 1 ? "s" : "", step,
              repeats);
  std::printf("  %-24s %10s %9s %8s %10s %10s %8s %8s\n", "pass", "items", "us/step", "share", "ns/item", "bytes/item",
              "GB/s", "flop/B");
  double sum = 0;
  for (const auto& x : p) {
    const double us = quantile(x.us, 0.5);
    sum += us;
    const double ns = 1e3 * us / x.items;
    std::printf("  %-24s %10.0f %9.0f %7.1f%% %10.1f %10.0f %8.1f %8.2f\n", x.what, x.items, us, 100 * us / step, ns, x.bytes,
                x.bytes > 0 ? x.bytes / ns : 0.0, x.bytes > 0 ? x.flops / x.bytes : 0.0);
  }
  std::printf("  %-24s %10s %9.0f %7.1f%%   (rigid contacts, block pass, re-detection checks, guard)\n", "rest of the step", "",
              step - sum, 100 * (step - sum) / step);
}

template <class D>
void table_row(const char* name, const Contender<D>& c, int threads) {
  for (int t : {1, threads}) {
    const auto& v = t == 1 ? c.step_us : c.threaded_step_us;
    if (v.empty()) continue;
    std::printf("  %-12s %d thread%s  q10 %8.0f  q25 %8.0f  q50 %8.0f  q75 %8.0f us   %7.0f steps/s (median)\n", name, t,
                t > 1 ? "s" : " ", quantile(v, 0.1), quantile(v, 0.25), quantile(v, 0.5), quantile(v, 0.75), 1e6 / quantile(v, 0.5));
    if (threads == 1) break;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"the cross vault's step, rigid, mixed or deformable, MassProportional against Maxwell<3> and None, taking turns"};
  std::string kinematics = "deformable";
  long long settle_steps = 2000;
  int rounds = 10, steps = 10, threads = 2;
  bool with_passes = false;
  app.add_option("--kinematics", kinematics, "rigid, mixed or deformable")->check(CLI::IsMember({"rigid", "mixed", "deformable"}));
  app.add_option("--settle-steps", settle_steps, "steps of settling before the measurement")->check(CLI::Range(0LL, 10'000'000LL));
  app.add_option("--rounds", rounds, "turns per policy")->check(CLI::Range(1, 100000));
  app.add_option("--steps-per-turn", steps, "steps per turn (the first of each is not timed)")->check(CLI::Range(2, 100000));
  app.add_option("--threads", threads, "OpenMP threads besides one (each turn also run on this many)")->check(CLI::Range(1, 1024));
  app.add_flag("--passes", with_passes, "also the cost of each pass of the deformable step, with its roofline");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  VaultStudyOptions o;
  o.kinematics = kinematics == "rigid" ? VaultKinematics::rigid : kinematics == "mixed" ? VaultKinematics::mixed : VaultKinematics::deformable;
  const auto start = clock_type::now();
  Contender<damping::MassProportional> mass(o, damping::MassProportional::from_damping_ratio(0.04, 7.5), settle_steps);
  Contender<damping::Maxwell<3>> maxwell(o, damping::to_policy<3>(damping::fit_maxwell(damping::MaxwellFitOptions{})), settle_steps);
  Contender<damping::None> none(o, damping::None{}, settle_steps);
  const auto& m = mass.simulation->model();
  std::printf("cross vault, %s: %zu blocks (%zu deformable), %zu nodes, %zu tetrahedra, %zu contact points; settled %lld steps in "
              "%.1f s (three times)\n",
              kinematics.c_str(), m.bodies.size(), m.deformable.blocks.size(), m.deformable.nodes.size(), m.deformable.tetrahedra.size(),
              mass.simulation->contact_points(), settle_steps, 1e-6 * microseconds(start, clock_type::now()));
  std::printf("timestep: MassProportional %.4g s, Maxwell<3> %.4g s, None %.4g s\n", mass.simulation->timestep(),
              maxwell.simulation->timestep(), none.simulation->timestep());
  std::vector<bool> split_caches;  // per round: the two vCPUs on two last-level caches (cache_trip_ns over 80 ns)
  std::vector<double> trips;
  for (int r = 0; r < rounds; ++r) {
    if (threads > 1) {
      trips.push_back(cache_trip_ns());
      split_caches.push_back(trips.back() > 80.0);
    }
    mass.turn(steps, threads);
    maxwell.turn(steps, threads);
    none.turn(steps, threads);
  }
  std::printf("step times over %d rounds of %d steps:\n", rounds, steps);
  table_row("Mass", mass, threads);
  table_row("Maxwell<3>", maxwell, threads);
  table_row("None", none, threads);
  std::printf("paired (median steps of turns taken together), q25 / q50 / q75:\n");
  report_paired("Maxwell<3> / Mass, 1 thread", maxwell.turn_us, mass.turn_us);
  report_paired("Mass / None, 1 thread", mass.turn_us, none.turn_us);
  if (threads > 1) {
    const std::string n = std::to_string(threads);
    report_paired("Maxwell<3> / Mass, " + n + " threads", maxwell.threaded_turn_us, mass.threaded_turn_us);
    report_paired("speed-up of " + n + " threads, Mass", mass.turn_us, mass.threaded_turn_us);
    report_paired("speed-up of " + n + " threads, Maxwell<3>", maxwell.turn_us, maxwell.threaded_turn_us);
    // The host's placement of the two vCPUs, measured before each round: the two-thread step on each.
    std::printf("the two vCPUs, per round: one shared last-level cache (cache line trip %.0f ns at the median) or two (over 80 ns):\n",
                quantile(trips, 0.5));
    for (bool split : {false, true}) {
      int count = 0;
      const double mass_us = median_where(mass.threaded_turn_us, split_caches, split, count);
      int maxwell_count = 0;
      const double maxwell_us = median_where(maxwell.threaded_turn_us, split_caches, split, maxwell_count);
      if (count > 0)
        std::printf("  %-20s %3d rounds: %d threads, Mass %.0f us, Maxwell<3> %.0f us per step (medians of the turns)\n",
                    split ? "two caches" : "one cache", count, threads, mass_us, maxwell_us);
    }
  }
  if (with_passes && !m.deformable.empty()) {
    // About what one step of the deformable vault reads and writes with Maxwell<3> (elements 700 bytes, node contacts
    // 500, nodes 300): the triad runs over as much.
    const std::size_t state_bytes = m.deformable.tetrahedra.size() * 700 + mass.simulation->contact_points() * 500 +
                                    m.deformable.nodes.size() * 300;
    std::printf("this machine: triad %.1f GB/s on 1 thread, %.1f GB/s on %d over %.1f MB (the deformable state's size); "
                "peak %.1f GFLOP/s per thread\n",
                triad_bandwidth(state_bytes, 1), triad_bandwidth(state_bytes, threads), threads, 1e-6 * static_cast<double>(state_bytes),
                peak_gflops());
    for (int t : {1, threads}) {
      passes("Maxwell<3>", maxwell, t, 30);
      passes("Mass", mass, t, 30);
      if (threads == 1) break;
    }
  }
}
