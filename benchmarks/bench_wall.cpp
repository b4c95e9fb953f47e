// Cost of one explicit step on a dry-stack wall of 2000+ rigid blocks in running bond, for every combination of
// joint law and damping policy, on one thread and on all threads, beside a hand-fused reference loop (Elastic,
// no damping) written without templates: the generic integrator should cost no more than the hand-written one.
//
// Counters: ns per contact-point-step (cp_step_ns) and per block-step (block_step_ns).

#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "blockdem/integrate/simulation.hpp"
#include "wall_model.hpp"

namespace {

using namespace blockdem;
using namespace blockdem::benchmarks;

template <class Law, class Damping>
void step(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  auto model = std::make_unique<model::Model>(make_wall());
  Simulation<Damping, Law> sim(*model, make_damping<Damping>(), [](int, int) { return parameters<Law>(); });
  for (int i = 0; i < 20; ++i) sim.step();  // warm up, let it settle a little
  for (auto _ : state) sim.step();
  // Rates per item, inverted: seconds per CP-step; the table in docs/performance.md lists them in ns.
  state.counters["cp_step_ns"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(sim.contact_points()) * 1e-9,
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["block_step_ns"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(model->bodies.size()) * 1e-9,
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["contact_points"] = static_cast<double>(sim.contact_points());
  state.counters["blocks"] = static_cast<double>(model->bodies.size());
  // Contact detections run during the whole benchmark (the first one included): a redetection in the timed loop
  // would count in the step's time.
  state.counters["detections"] = sim.detections();
}

/// The rows of the table: every shipped law with each policy the table has for it (in_wall_table), named
/// "wall/contact::Elastic/damping::None" and so on.
[[maybe_unused]] const bool wall_benchmarks = [] {
  for_each_type<contact::ShippedLaws>([](auto law) {
    using Law = typename decltype(law)::type;
    for_each_type<damping::ShippedPolicies>([](auto policy) {
      using Damping = typename decltype(policy)::type;
      if constexpr (in_wall_table<Law, Damping>()) {
        const std::string name = "wall/" + short_name<Law>() + "/" + short_name<Damping>();
        benchmark::RegisterBenchmark(name.c_str(), step<Law, Damping>)
            ->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
      }
    });
  });
  return true;
}();

// ---- the hand-fused reference: Elastic joints, no damping, rigid blocks, one function, no templates ----

struct Reference {
  // Blocks
  std::vector<Vec3> x, v, w;
  std::vector<Quaternion> q;
  std::vector<Mat3> r;
  std::vector<double> mass;
  std::vector<Vec3> inertia;
  std::vector<char> free;
  // Contacts (block pairs): frame fixed in A, resultants
  std::vector<std::uint32_t> a, b, first_point;
  std::vector<Vec3> o_a, n_a, t_a, force, moment;  // moment: [2c] on A, [2c + 1] on B
  // Contact points
  std::vector<double> s1, s2, area, gap, tau1, tau2;
  std::vector<std::uint32_t> first, entry;
  double kn = 1e10, ks = 4e9, dt = 0;
  Vec3 g = Vec3(0, 0, -9.81);

  void step(bool increment) {
    const double inc = increment ? dt : 0.0, h = 0.5 * inc;
    const auto nc = static_cast<std::ptrdiff_t>(a.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t cc = 0; cc < nc; ++cc) {
      const auto c = static_cast<std::size_t>(cc);
      const auto ia = a[c], ib = b[c];
      const Vec3 n = r[ia] * n_a[c], t1 = r[ia] * t_a[c], t2 = n.cross(t1);
      const Vec3 arm_a = r[ia] * o_a[c], arm_b = x[ia] + arm_a - x[ib];
      const Vec3 dv = v[ib] - v[ia], wa = w[ia], ww = w[ib] - wa, wa_arm = wa.cross(arm_a);
      const Vec3 u = dv + w[ib].cross(arm_b + h * (dv - wa_arm)) - wa.cross(arm_a - h * wa_arm);
      const Vec3 d0 = inc * u + h * wa.cross(inc * u);
      const Vec3 e1 = inc * ww.cross(t1 - h * wa.cross(t1)), e2 = inc * ww.cross(t2 - h * wa.cross(t2));
      const Vec3 d1 = e1 + h * wa.cross(e1), d2 = e2 + h * wa.cross(e2);
      const double d0n = d0.dot(n), d01 = d0.dot(t1), d02 = d0.dot(t2);
      const double d1n = d1.dot(n), d11 = d1.dot(t1), d12 = d1.dot(t2);
      const double d2n = d2.dot(n), d21 = d2.dot(t1), d22 = d2.dot(t2);
      double fn = 0, f1 = 0, f2 = 0, mn = 0, m1 = 0, m2 = 0;
      for (auto k = first_point[c]; k < first_point[c + 1]; ++k) {
        const double x1 = s1[k], x2 = s2[k];
        gap[k] += d0n + x1 * d1n + x2 * d2n;
        tau1[k] -= ks * (d01 + x1 * d11 + x2 * d21);
        tau2[k] -= ks * (d02 + x1 * d12 + x2 * d22);
        const double an = -kn * gap[k] * area[k], a1 = tau1[k] * area[k], a2 = tau2[k] * area[k];
        fn += an; f1 += a1; f2 += a2;
        mn += x1 * a2 - x2 * a1; m1 += x2 * an; m2 -= x1 * an;
      }
      const Vec3 f = fn * n + f1 * t1 + f2 * t2, mo = mn * n + m1 * t1 + m2 * t2;
      force[c] = f;
      moment[2 * c] = -(arm_a.cross(f) + mo);
      moment[2 * c + 1] = arm_b.cross(f) + mo;
    }
    const auto nb = static_cast<std::ptrdiff_t>(x.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t ii = 0; ii < nb; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (!free[i]) continue;
      Vec3 fi = mass[i] * g, mi = Vec3::Zero();
      for (auto e = first[i]; e < first[i + 1]; ++e) {
        const double sign = static_cast<double>(entry[e] & 1u) * 2.0 - 1.0;
        fi += sign * force[entry[e] >> 1];
        mi += moment[entry[e]];
      }
      v[i] += dt * fi / mass[i];
      const Vec3 wb_old = r[i].transpose() * w[i];
      const Vec3 mb = r[i].transpose() * mi;
      Vec3 wb = wb_old;
      for (int pass = 0; pass < 3; ++pass) {
        const Vec3 wm = 0.5 * (wb_old + wb);
        wb = wb_old + dt * (mb - wm.cross(inertia[i].cwiseProduct(wm))).cwiseQuotient(inertia[i]);
      }
      w[i] = r[i] * wb;
      x[i] += dt * v[i];
      const double angle = w[i].norm() * dt;
      if (angle > 0) {
        q[i] = (Quaternion(Eigen::AngleAxisd(angle, w[i] / w[i].norm())) * q[i]).normalized();
        r[i] = q[i].toRotationMatrix();
      }
    }
  }
};

void reference(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  auto model = make_wall();
  // Take the contact set from the library so that both loops see the same points.
  Simulation<damping::None, contact::Elastic> sim(model, damping::None{}, [](int, int) { return elastic(); });
  const auto& g = sim.group<contact::Elastic>();
  const auto& bo = model.bodies;
  Reference ref;
  ref.x = bo.position; ref.v = bo.velocity; ref.w = bo.angular_velocity; ref.q = bo.orientation; ref.r = bo.rotation;
  ref.mass = bo.mass; ref.inertia = bo.principal_inertia;
  for (auto mo : bo.motion) ref.free.push_back(mo == model::Motion::free);
  ref.a = g.body_a; ref.b = g.body_b; ref.first_point = g.first_point;
  ref.o_a = g.origin_a; ref.n_a = g.normal_a; ref.t_a = g.tangent_a;
  ref.force = g.force; ref.moment = g.moment;
  ref.s1 = g.s1; ref.s2 = g.s2; ref.area = g.area;
  for (const auto& h : g.history) { ref.gap.push_back(h.gap); ref.tau1.push_back(h.shear[0]); ref.tau2.push_back(h.shear[1]); }
  ref.first = g.first; ref.entry = g.entry; ref.dt = sim.timestep();
  bool increment = false;
  for (int i = 0; i < 20; ++i) { ref.step(increment); increment = true; }
  for (auto _ : state) ref.step(true);
  state.counters["cp_step_ns"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(g.size()) * 1e-9,
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["block_step_ns"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(bo.size()) * 1e-9,
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(reference)->Name("wall/hand-fused reference (Elastic, None)")->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
