// Cost of one explicit step on a dry-stack wall of 2000+ rigid blocks in running bond, for every combination of
// joint law and damping policy, on one thread and on all threads, beside a hand-fused reference loop (Elastic,
// no damping) written without templates: the generic integrator should cost no more than the hand-written one.
//
// Counters: ns per contact-point-step (cp_step_ns) and per block-step (block_step_ns).

#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <memory>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"

namespace {

using namespace blockdem;

model::Model make_wall() {
  model::Model m;
  // 40 courses of 50 units (0.24 x 0.12 x 0.055 m): 2020 blocks.
  for (const auto& b : geometry::running_bond_wall(40, 50, 0.24, 0.12, 0.055))
    m.add_block(b.shape, 1800, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  return m;
}

contact::Elastic::Parameters elastic() { return {1e10, 4e9}; }
contact::MohrCoulomb::Parameters mohr_coulomb() { return {1e10, 4e9, 1e5, 2e5, 0.6}; }
/// The paper's Table 1 through eq. 4-7 (k_n = 3.9e10 Pa/m: a smaller timestep than the other laws, same step cost).
contact::ElastoSoftening::Parameters softening() { return contact::ElastoSoftening::Parameters::from_material(); }

template <class Law>
typename Law::Parameters parameters() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) return elastic();
  else if constexpr (std::is_same_v<Law, contact::ElastoSoftening>) return softening();
  else return mohr_coulomb();
}

damping::Maxwell<3> maxwell3() {
  damping::MaxwellFitOptions o;
  return damping::to_policy<3>(damping::fit_maxwell(o));
}

template <class Damping>
Damping make_damping() {
  if constexpr (std::is_same_v<Damping, damping::None>) return {};
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.04, 7.5);
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40);
  else return maxwell3();
}

template <class Law, class Damping>
void step(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  auto model = std::make_unique<model::Model>(make_wall());
  Simulation<Damping, Law> sim(*model, make_damping<Damping>(), [](int, int) { return parameters<Law>(); });
  for (int i = 0; i < 20; ++i) sim.step();  // warm up, let it settle a little
  for (auto _ : state) sim.step();
  // Rates per item, inverted: seconds per CP-step; the table in README.md lists them in ns.
  state.counters["cp_step_ns"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(sim.contact_points()) * 1e-9,
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["block_step_ns"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(model->bodies.size()) * 1e-9,
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["contact_points"] = static_cast<double>(sim.contact_points());
  state.counters["blocks"] = static_cast<double>(model->bodies.size());
}

#define BLOCKDEM_WALL_BENCHMARK(Law, Damping) \
  BENCHMARK(step<Law, Damping>)->Name("wall/" #Law "/" #Damping)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond)

BLOCKDEM_WALL_BENCHMARK(contact::Elastic, damping::None);
BLOCKDEM_WALL_BENCHMARK(contact::Elastic, damping::MassProportional);
BLOCKDEM_WALL_BENCHMARK(contact::Elastic, damping::Rayleigh);
BLOCKDEM_WALL_BENCHMARK(contact::Elastic, damping::Maxwell<3>);
BLOCKDEM_WALL_BENCHMARK(contact::MohrCoulomb, damping::None);
BLOCKDEM_WALL_BENCHMARK(contact::MohrCoulomb, damping::MassProportional);
BLOCKDEM_WALL_BENCHMARK(contact::MohrCoulomb, damping::Rayleigh);
BLOCKDEM_WALL_BENCHMARK(contact::MohrCoulomb, damping::Maxwell<3>);
BLOCKDEM_WALL_BENCHMARK(contact::ElastoSoftening, damping::None);
BLOCKDEM_WALL_BENCHMARK(contact::ElastoSoftening, damping::MassProportional);
BLOCKDEM_WALL_BENCHMARK(contact::ElastoSoftening, damping::Maxwell<3>);

// ---- the hand-fused reference: Elastic joints, no damping, rigid blocks, one function, no templates ----

struct Reference {
  // Blocks
  std::vector<Vec3> x, v, w, f, m;
  std::vector<Quaternion> q;
  std::vector<Mat3> r;
  std::vector<double> mass;
  std::vector<Vec3> inertia;
  std::vector<char> free;
  // Contact points
  std::vector<std::uint32_t> a, b;
  std::vector<Vec3> arm_a, arm_b, n_a, t_a;
  std::vector<double> area, gap, s1, s2;
  std::vector<Vec3> force;
  std::vector<std::uint32_t> first, entry;
  double kn = 1e10, ks = 4e9, dt = 0;
  Vec3 g = Vec3(0, 0, -9.81);

  void step(bool increment) {
    const double inc = increment ? dt : 0.0;
    const auto ncp = static_cast<std::ptrdiff_t>(a.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t kk = 0; kk < ncp; ++kk) {
      const auto k = static_cast<std::size_t>(kk);
      const auto ia = a[k], ib = b[k];
      const Vec3 ra = r[ia] * arm_a[k], rb = r[ib] * arm_b[k];
      const Vec3 n = r[ia] * n_a[k], t1 = r[ia] * t_a[k], t2 = n.cross(t1);
      const Vec3 ha = (-0.5 * inc) * w[ia], hb = (-0.5 * inc) * w[ib];
      const Vec3 ma = ra + ha.cross(ra), mb = rb + hb.cross(rb);
      const Vec3 nm = n + ha.cross(n), t1m = t1 + ha.cross(t1), t2m = t2 + ha.cross(t2);
      const Vec3 du = ((v[ib] + w[ib].cross(mb)) - (v[ia] + w[ia].cross(ma))) * inc;
      gap[k] += du.dot(nm);
      s1[k] -= ks * du.dot(t1m);
      s2[k] -= ks * du.dot(t2m);
      force[k] = area[k] * (-kn * gap[k] * n + s1[k] * t1 + s2[k] * t2);
    }
    const auto nb = static_cast<std::ptrdiff_t>(x.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t ii = 0; ii < nb; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (!free[i]) continue;
      Vec3 fi = mass[i] * g, mb_sum = Vec3::Zero();
      const Mat3 rt = r[i].transpose();
      for (auto e = first[i]; e < first[i + 1]; ++e) {
        const auto k = entry[e] >> 1;
        const Vec3 fk = (entry[e] & 1u) ? Vec3(force[k]) : Vec3(-force[k]);
        fi += fk;
        mb_sum += ((entry[e] & 1u) ? arm_b[k] : arm_a[k]).cross(rt * fk);
      }
      const Vec3 mi = r[i] * mb_sum;
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
  ref.a = g.body_a; ref.b = g.body_b; ref.arm_a = g.arm_a; ref.arm_b = g.arm_b; ref.n_a = g.normal_a; ref.t_a = g.tangent_a;
  ref.area = g.area;
  for (const auto& h : g.history) { ref.gap.push_back(h.gap); ref.s1.push_back(h.shear[0]); ref.s2.push_back(h.shear[1]); }
  ref.force.assign(g.size(), Vec3::Zero());
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
