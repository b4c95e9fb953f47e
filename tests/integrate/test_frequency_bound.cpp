// The critical timestep (eq. 1): the block Gershgorin bound on omega_max against the eigenfrequencies of systems
// solved by hand or by a dense eigensolver, and against the integrator's own stability limit; rigid blocks, nodes
// of deformable blocks, contacts between them and trusses.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/model/deformable.hpp"
#include "fixtures.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_frequency_bound {

namespace {

using Sim = Simulation<damping::None, contact::Elastic>;

constexpr std::uint8_t vertical_only = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;

/// Steps until the largest block displacement from the start exceeds 1e6 times `initial` or `steps` are done;
/// returns that largest displacement over `initial`.
double growth(Sim& sim, double initial, long long steps = 20000) {
  const auto& b = sim.model().bodies;
  const auto x0 = b.position;
  double largest = 0;
  for (long long i = 0; i < steps && largest < 1e6 * initial; ++i) {
    try {
      sim.step();
    } catch (const RunawayError&) {
      break;  // beyond 100 m/s: the run guard stops every diverging run
    }
    for (std::size_t k = 0; k < b.size(); ++k) largest = std::max(largest, (b.position[k] - x0[k]).norm());
  }
  return largest / initial;
}

/// Two 1 m cubes of 2000 kg stacked on a fixed base, vertical translation only, each joint 1 m^2 of k_n = k_s:
/// masses m, springs k = k_n (base to 1, 1 to 2). omega^2 = (k / m) (3 +- sqrt 5) / 2.
struct Stack {
  model::Model model;
  double k = 2e9, m = 2000;
  Stack() {
    model.gravity = Vec3::Zero();
    model.add_block(geometry::make_box(Vec3(-2, -2, -0.5), Vec3(2, 2, 0)), 2000.0, "base", 0, model::Motion::fixed);
    for (int i = 0; i < 2; ++i) {
      const std::size_t b = model.add_block(geometry::make_box(Vec3(-0.5, -0.5, i), Vec3(0.5, 0.5, i + 1.0)), 2000.0, "cube", 1);
      model.bodies.fixity[b] = vertical_only;
    }
    model.bodies.velocity[2] = Vec3(0, 0, 1e-3);
  }
  double omega_max() const { return std::sqrt(k / m * (3 + std::sqrt(5.0)) / 2); }
};

}  // namespace

TEST_CASE("timestep: for two stacked blocks eq. 1's estimate per block is below omega_max, the bound above it") {
  Stack s;
  Sim sim(s.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(s.k, s.k); });
  // Per block: sqrt(2 k / m) (the lower block on its two joints). Bound: rows 2k/m + k/m and k/m + k/m.
  CHECK(sim.estimated_omega_max() == test::approx(std::sqrt(2 * s.k / s.m)).epsilon(1e-9));
  CHECK(sim.frequency_bound().omega_max() == test::approx(std::sqrt(3 * s.k / s.m)).epsilon(1e-9));
  CHECK(sim.bounded_frequency());
  CHECK(sim.critical_timestep() == test::approx(2 / std::sqrt(3 * s.k / s.m)).epsilon(1e-9));
  CHECK(sim.timestep() == test::approx(Sim::bound_safety_factor * sim.critical_timestep()).epsilon(1e-12));

  // The integrator's limit is 2 / omega_max (1.618 sqrt(k / m)): the estimate's timestep is beyond it.
  const double initial = 1e-3 / s.omega_max();
  auto run_at = [&](double dt) {
    Stack t;
    Sim run(t.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(t.k, t.k); });
    run.set_timestep(dt, TimestepCheck::unchecked);
    return growth(run, initial);
  };
  CHECK(run_at(0.99 * 2 / sim.estimated_omega_max()) > 1e3);
  CHECK(run_at(1.01 * 2 / s.omega_max()) > 1e3);
  CHECK(run_at(0.99 * 2 / s.omega_max()) < 10);
  CHECK(run_at(sim.critical_timestep()) < 10);
}

TEST_CASE("timestep: for one free block on its base the bound is omega_max, the integrator's limit to 2 %") {
  // Six degrees of freedom, translation and rocking coupled (the CPs lie below the centroid): the bound is the
  // largest eigenvalue of its 6 x 6 mass-normalised stiffness, so the scheme is stable just below and unstable just
  // above the critical timestep.
  auto run_at = [](double factor) {
    auto s = test::block_on_base(0.6, 0.4, 1.0);
    s.model.gravity = Vec3::Zero();
    auto& b = s.model.bodies;
    b.velocity[s.block] = Vec3(2e-4, -1e-4, 3e-4);
    b.angular_velocity[s.block] = Vec3(1e-4, 2e-4, -1.5e-4);
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Sim sim(s.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 0.4e9); }, contacts);
    sim.set_timestep(factor * sim.critical_timestep(), TimestepCheck::unchecked);
    return growth(sim, 1e-4 * sim.timestep(), 5000);
  };
  CHECK(run_at(0.98) < 1e3);
  CHECK(run_at(1.02) > 1e5);
}

TEST_CASE("timestep: partial density scaling by the bound brings every block's row to the target") {
  Stack s;
  Sim sim(s.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(s.k, s.k); });
  const double target = 2 * sim.timestep();
  const auto r = sim.scale_density_to(target);
  CHECK(sim.timestep() == target);
  CHECK(r.scaled_blocks == 2);
  // Both rows at most omega_t^2 with omega_t = 2 safety / target; each block's scaled with the other's real mass,
  // so the final bound lies below: the lower cube needs s with 2k/(m s) + k/(m sqrt s) = omega_t^2.
  const double omega_t = 2 * Sim::bound_safety_factor / target;
  CHECK(sim.frequency_bound().omega_max() <= omega_t);
  const double x = (std::sqrt(1 + 8 * omega_t * omega_t * s.m / s.k) - 1) / 4;  // 1 / sqrt(s): 2 x^2 + x = omega_t^2 m / k
  CHECK(s.model.bodies.mass[1] == test::approx(s.m / (x * x)).epsilon(1e-6));
  CHECK(std::abs(sim.density_scaling_mass(target, [](double) { return 1.0; })) < 1e-9 * s.m);  // nothing left to add
}

namespace {

/// A concrete-like deformable block 0.4 x 0.3 x 0.5 m (max edge 0.15 m) standing free in space, its bottom nodes
/// fixed: nothing but the elements.
struct Cantilever {
  model::Model model;
  std::size_t block = 0;
  Cantilever() {
    model.gravity = Vec3::Zero();
    block = model.add_block(geometry::make_box(Vec3(0, 0, 0), Vec3(0.4, 0.3, 0.5)), 2400.0, "block", 1);
    model.make_deformable(block, 0.15, model::IsotropicElastic(30e9, 0.2));
    auto& nd = model.deformable.nodes;
    for (std::size_t i = 0; i < nd.size(); ++i) nd.fixity[i] = nd.position[i].z() < 1e-9 ? 7 : 0;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> velocity(-1e-3, 1e-3);
    for (auto& v : nd.velocity) v = Vec3(velocity(random), velocity(random), velocity(random));
    for (std::size_t i = 0; i < nd.size(); ++i)
      if (nd.fixity[i]) nd.velocity[i].setZero();
  }

  /// omega_max of the free nodes' M^-1/2 K M^-1/2, K assembled here element by element (linear elasticity,
  /// lambda = K - 2G/3), by a dense eigensolver.
  double omega_max() const {
    const auto& nd = model.deformable.nodes;
    const auto& te = model.deformable.tetrahedra;
    const auto n = static_cast<Eigen::Index>(3 * nd.size());
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t t = 0; t < te.size(); ++t) {
      const auto& mat = model.deformable.materials[te.material[t]];
      const double mu = mat.shear(), lambda = mat.bulk() - 2 * mu / 3;
      const auto& g = te.gradient[t];
      for (std::size_t i = 0; i < 4; ++i)
        for (std::size_t j = 0; j < 4; ++j)
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
              k(3 * te.node[t][i] + a, 3 * te.node[t][j] + b) +=
                  te.volume[t] * (lambda * g[i][a] * g[j][b] + mu * g[i][b] * g[j][a] + (a == b ? mu * g[i].dot(g[j]) : 0.0));
    }
    for (Eigen::Index r = 0; r < n; ++r)
      for (Eigen::Index c = 0; c < n; ++c) {
        const auto i = static_cast<std::size_t>(r / 3), j = static_cast<std::size_t>(c / 3);
        const bool free = !nd.fixity[i] && !nd.fixity[j];
        k(r, c) = free ? k(r, c) / std::sqrt(nd.mass[i] * nd.mass[j]) : 0.0;  // fixed nodes: left out
      }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, Eigen::EigenvaluesOnly);
    return std::sqrt(solver.eigenvalues().maxCoeff());
  }
};

/// Steps until the largest node displacement exceeds 1e6 times `initial` or `steps` are done; returns that
/// largest displacement over `initial`.
template <class S>
double node_growth(S& sim, double initial, long long steps) {
  const auto& nd = sim.model().deformable.nodes;
  const auto x0 = nd.position;
  double largest = 0;
  for (long long i = 0; i < steps && largest < 1e6 * initial; ++i) {
    try {
      sim.step();
    } catch (const RunawayError&) {
      break;  // beyond 100 m/s: the run guard stops every diverging run
    }
    for (std::size_t k = 0; k < nd.size(); ++k) largest = std::max(largest, (nd.position[k] - x0[k]).norm());
  }
  return largest / initial;
}

}  // namespace

TEST_CASE("timestep: for a deformable block the bound lies above omega_max, which is the integrator's limit to 2 %") {
  // Reference: the dense eigensolution of the assembled lumped-mass system, and the integrator's own stability.
  Cantilever c;
  Sim sim(c.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e10, 1e10); });
  const double exact = c.omega_max(), bound = sim.frequency_bound().omega_max(), estimate = sim.estimated_omega_max();
  MESSAGE("deformable block, " << c.model.deformable.nodes.size() << " nodes: omega_max " << exact << " rad/s, bound "
                               << bound << " (" << bound / exact << "), eq. 2 estimate " << estimate << " ("
                               << estimate / exact << ")");
  CHECK(sim.bounded_frequency());
  CHECK(bound >= exact * (1 - 1e-9));
  CHECK(bound < 1.6 * exact);
  // The bound's timestep with its margin is longer than the estimate's with its own.
  CHECK(Sim::bound_safety_factor / bound > Sim::estimate_safety_factor / estimate);
  auto run_at = [&](double dt) {
    Cantilever d;
    Sim run(d.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e10, 1e10); });
    run.set_timestep(dt, TimestepCheck::unchecked);
    return node_growth(run, 1e-3 * dt, 3000);
  };
  CHECK(run_at(0.98 * 2 / exact) < 1e3);
  CHECK(run_at(1.02 * 2 / exact) > 1e5);
  CHECK(run_at(sim.critical_timestep()) < 1e3);
}

TEST_CASE("timestep: the stored norms of element blocks and node springs give each row's sums of a direct solution") {
  // Reference: Eigen's SVD of each scaled block M_i^-1/2 K_ij M_j^-1/2, with a node fixed on one axis only (its
  // block is solved, not scaled) beside free and fully fixed nodes (scaled by one number each).
  Cantilever c;
  auto& nd = c.model.deformable.nodes;
  std::size_t partly = 0;
  while (nd.fixity[partly] != 0) ++partly;
  nd.fixity[partly] = 2;  // y fixed
  const auto& te = c.model.deformable.tetrahedra;
  FrequencyBound stored(c.model), direct(c.model);
  std::vector<double> coupled(nd.size(), 0.0);
  const auto scale = [&](std::size_t n) {
    Vec3 s;
    for (int d = 0; d < 3; ++d) s[d] = (nd.fixity[n] & (1u << d)) ? 0.0 : 1.0 / std::sqrt(nd.mass[n]);
    return s;
  };
  for (std::size_t t = 0; t < te.size(); ++t) {
    const auto& mat = c.model.deformable.materials[te.material[t]];
    const auto norms = FrequencyBound::tetrahedron_pair_norms(te.gradient[t], te.volume[t], mat.bulk(), mat.shear());
    stored.tetrahedron(te.node[t], te.gradient[t], te.volume[t], mat.bulk(), mat.shear(), &norms);
    direct.tetrahedron(te.node[t], te.gradient[t], te.volume[t], mat.bulk(), mat.shear());
    for (const auto& [i, j] : FrequencyBound::tetrahedron_pairs) {
      const Mat3 k = FrequencyBound::tetrahedron_block(te.gradient[t], te.volume[t], mat.bulk(), mat.shear(), i, j);
      const double norm = Eigen::JacobiSVD<Mat3>(Mat3(scale(te.node[t][i]).asDiagonal() * k * scale(te.node[t][j]).asDiagonal())).singularValues()[0];
      coupled[te.node[t][i]] += norm;
      coupled[te.node[t][j]] += norm;
    }
  }
  // A contact spring between two free nodes and one from the partly fixed node (kn 1e10, ks 4e9 N/m along n).
  const Vec3 n = Vec3(1, 2, 2) / 3.0;
  const Mat3 d = 1e10 * n * n.transpose() + 4e9 * (Mat3::Identity() - n * n.transpose());
  std::size_t a = partly + 1, b = 0;
  while (nd.fixity[a] != 0) ++a;
  b = a + 1;
  while (nd.fixity[b] != 0) ++b;
  for (auto* bound : {&stored, &direct}) {
    bound->spring({FrequencyBound::node_point(a)}, {FrequencyBound::node_point(b, 0.5), FrequencyBound::node_point(partly, 0.5)}, d);
  }
  const double free_pair = 0.5 * 1e10 / std::sqrt(nd.mass[a] * nd.mass[b]);  // ||D|| = max(kn, ks)
  coupled[a] += free_pair + 0.5 * Eigen::JacobiSVD<Mat3>(Mat3(scale(a).asDiagonal() * d * scale(partly).asDiagonal())).singularValues()[0];
  coupled[b] += free_pair + 0.25 * Eigen::JacobiSVD<Mat3>(Mat3(scale(b).asDiagonal() * d * scale(partly).asDiagonal())).singularValues()[0];
  coupled[partly] += 0.5 * Eigen::JacobiSVD<Mat3>(Mat3(scale(a).asDiagonal() * d * scale(partly).asDiagonal())).singularValues()[0] +
                     0.25 * Eigen::JacobiSVD<Mat3>(Mat3(scale(b).asDiagonal() * d * scale(partly).asDiagonal())).singularValues()[0];
  double worst = 0;
  for (std::size_t i = 0; i < nd.size(); ++i) {
    CHECK(stored.node_row(i).own == direct.node_row(i).own);
    worst = std::max({worst, std::abs(stored.node_row(i).coupled - coupled[i]) / std::max(coupled[i], 1e-300),
                      std::abs(direct.node_row(i).coupled - coupled[i]) / std::max(coupled[i], 1e-300)});
  }
  MESSAGE(te.size() << " elements, " << nd.size() << " nodes: largest relative difference of a row's coupled sum " << worst);
  CHECK(worst < 1e-12);
  CHECK(stored.node_row(partly).coupled > 0);
  CHECK(stored.omega_max() == doctest::Approx(direct.omega_max()).epsilon(1e-13));
}

namespace {

/// Two deformable blocks, one on the other, on a free rigid block on a fixed base, and a steel tie from a node of
/// the top block to the rigid one: element, node-face (rigid and deformable) and rigid-rigid contacts, a truss.
struct Mixed {
  model::Model model;
  Mixed() {
    model.gravity = Vec3::Zero();
    model.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2400.0, "base", 0, model::Motion::fixed);
    const auto rigid = model.add_block(geometry::make_box(Vec3(-0.4, -0.3, 0), Vec3(0.4, 0.3, 0.2)), 2400.0, "rigid", 1);
    const auto lower = model.add_block(geometry::make_box(Vec3(-0.3, -0.2, 0.2), Vec3(0.3, 0.2, 0.5)), 2400.0, "lower", 1);
    const auto upper = model.add_block(geometry::make_box(Vec3(-0.2, -0.2, 0.5), Vec3(0.2, 0.2, 0.8)), 2400.0, "upper", 1);
    model.make_deformable(lower, 0.15, model::IsotropicElastic(20e9, 0.2));
    model.make_deformable(upper, 0.15, model::IsotropicElastic(20e9, 0.2));
    model.add_truss(model.block_end(rigid, Vec3(0.35, 0, 0.2)), model.node_end(model.nearest_node(upper, Vec3(0.2, 0, 0.8))), 5e-4,
                    200e9, 7800, 0.0, "tie");
    std::mt19937 random(11);
    std::uniform_real_distribution<double> velocity(-1e-3, 1e-3);
    for (auto& v : model.deformable.nodes.velocity) v = Vec3(velocity(random), velocity(random), velocity(random));
    model.bodies.velocity[rigid] = Vec3(velocity(random), velocity(random), velocity(random));
  }
};

}  // namespace

TEST_CASE("timestep: for mixed rigid and deformable blocks with a tie the bound's timestep is stable, twice it is not") {
  // The bound holds for the contacts between nodes, triangles and rigid faces and for a truss between a node and a
  // block: the integrator is stable at its critical timestep (no margin), and diverges at twice it (the bound is
  // not loose by a factor 2).
  Mixed s;
  auto properties = [](int, int) { return contact::Elastic::Parameters(2e10, 1e10); };
  Sim sim(s.model, damping::None{}, properties);
  const double critical = sim.critical_timestep();
  MESSAGE("mixed: " << s.model.deformable.nodes.size() << " nodes, " << sim.contact_points() << " CPs, bound dt " << critical
                    << " s, eq. 1-3 estimate " << 2 / sim.estimated_omega_max() << " s");
  CHECK(sim.bounded_frequency());
  CHECK(sim.contact_points() > 0);
  auto run_at = [&](double dt) {
    Mixed t;
    Sim run(t.model, damping::None{}, properties);
    run.set_timestep(dt, TimestepCheck::unchecked);
    return node_growth(run, 1e-3 * dt, 4000);
  };
  CHECK(run_at(critical) < 1e3);
  CHECK(run_at(2 * critical) > 1e5);
}

TEST_CASE("timestep: partial density scaling of nodes by the bound reaches the target, stable there") {
  Mixed s;
  auto properties = [](int, int) { return contact::Elastic::Parameters(2e10, 1e10); };
  Sim sim(s.model, damping::None{}, properties);
  const double target = 1.5 * sim.timestep();
  const auto r = sim.scale_density_to(target);
  MESSAGE("mixed, density scaled to 1.5 dt: +" << r.mass_increase_percent << " % mass, " << r.scaled_nodes << " nodes, "
                                            << r.scaled_blocks << " blocks");
  CHECK(sim.timestep() == target);
  CHECK(r.scaled_nodes > 0);
  CHECK(sim.frequency_bound().omega_max() <= 2 * Sim::bound_safety_factor / target);
  CHECK(std::abs(sim.density_scaling_mass(target, [](double) { return 1.0; })) < 1e-9 * r.real_mass);
  sim.set_timestep(sim.critical_timestep(), TimestepCheck::unchecked);
  CHECK(node_growth(sim, 1e-3 * target, 4000) < 1e3);
}

}  // namespace test_frequency_bound
