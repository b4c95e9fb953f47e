// Deformable blocks: meshing, constant-strain tetrahedra, damping inside the elements, density scaling, mixed
// rigid/deformable models and trusses.

#include <doctest/doctest.h>

#include "../approx.hpp"
#include "../integrate/fixtures.hpp"
#include "../threads.hpp"

#include <cmath>
#include <numeric>
#include <string>
#include <variant>
#include <vector>


#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/tetrahedral_mesh.hpp"
#include "blockdem/integrate/node_contact_assignment.hpp"
#include "blockdem/integrate/simulation.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_deformable {

static_assert(kinematics::Kinematics<kinematics::Rigid>);
static_assert(kinematics::Kinematics<kinematics::Deformable>);
static_assert(!kinematics::Kinematics<double>);
static_assert(DeformableState<damping::Maxwell<3>, contact::Elastic>::tensor_form);
static_assert(!DeformableState<damping::MassProportional, contact::Elastic>::tensor_form);

TEST_CASE("deformable mesh: a box meshed with a maximum edge, conforming, volume exact") {
  const auto box = geometry::make_box(Vec3(0, 0, 0), Vec3(1.0, 0.5, 0.3));
  const auto mesh = geometry::mesh_convex_polyhedron(box, 0.25, "box");
  CHECK(mesh.longest_edge() <= 0.25 * (1 + 1e-9));
  double volume = 0;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    CHECK(mesh.volume(t) > 0);
    volume += mesh.volume(t);
  }
  CHECK(volume == test::approx(0.15));
  // Boundary area = surface area, every boundary triangle on a face of the box.
  double area = 0;
  for (std::size_t k = 0; k < mesh.boundary.size(); ++k) {
    const auto& t = mesh.boundary[k];
    area += 0.5 * (mesh.nodes[t[1]] - mesh.nodes[t[0]]).cross(mesh.nodes[t[2]] - mesh.nodes[t[0]]).norm();
    CHECK(mesh.boundary_face[k] >= 0);
  }
  CHECK(area == test::approx(2 * (0.5 + 0.3 + 0.15)));
}

namespace {

using ElasticSim = Simulation<damping::None, contact::Elastic>;
auto elastic_joint = [](int, int) { return contact::Elastic::Parameters(1e10, 1e10); };

/// A free deformable box [lo, hi] alone in space (no contacts, no gravity).
model::Model lone_box(const Vec3& lo, const Vec3& hi, double max_edge, double young, double poisson, double rho = 2000) {
  model::Model m;
  m.gravity = Vec3::Zero();
  const auto i = m.add_block(geometry::make_box(lo, hi), rho, "box");
  m.make_deformable(i, max_edge, model::IsotropicElastic(young, poisson));
  return m;
}

/// Tip displacement history of a bar [0, a] x [0, a] x [0, L] fixed at z = 0, released with the velocity of its
/// first axial mode, v_z = v0 sin(pi z / 2L).
template <class Damping>
std::pair<std::vector<double>, std::vector<double>> axial_bar(Damping damping, double young, double length, double a,
                                                              double max_edge, double periods, double rho = 2000) {
  auto m = lone_box(Vec3::Zero(), Vec3(a, a, length), max_edge, young, 0.0, rho);
  auto& nd = m.deformable.nodes;
  std::size_t tip = 0;
  for (std::size_t i = 0; i < nd.size(); ++i) {
    const double z = nd.position[i].z();
    if (z < 1e-12) nd.fixity[i] = 7;
    else nd.velocity[i] = Vec3(0, 0, 1e-3 * std::sin(pi * z / (2 * length)));
    if (z > nd.position[tip].z() - 1e-12 && nd.position[i].x() < 1e-12 && nd.position[i].y() < 1e-12) tip = i;
  }
  Simulation<Damping, contact::Elastic> sim(m, damping, elastic_joint);
  const double f = std::sqrt(young / rho) / (4 * length);
  std::vector<double> t, u;
  const double z0 = nd.position[tip].z();
  while (sim.time() < periods / f) {
    sim.step();
    t.push_back(sim.time());
    u.push_back(nd.position[tip].z() - z0);
  }
  return {t, u};
}

}  // namespace

TEST_CASE("deformable patch test: a uniform strain field is reproduced exactly (linear displacement on the boundary)") {
  // Reference: the patch test of Irons and Razzaque (1972), which constant-strain elements pass exactly.
  auto m = lone_box(Vec3(0, 0, 0), Vec3(1.0, 0.8, 0.6), 0.3, 30e9, 0.2);
  ElasticSim sim(m, damping::None{}, elastic_joint);
  const double dt = sim.timestep();
  Mat3 a;
  a << 1.0, 0.3, -0.2, 0.5, -0.7, 0.4, 0.1, 0.6, 0.9;
  a *= 1e-4;
  auto& nd = m.deformable.nodes;
  const auto x0 = nd.position;
  // One step with v = A X / dt moves every node by u = A X; the element strains come from that move.
  for (std::size_t i = 0; i < nd.size(); ++i) nd.velocity[i] = a * x0[i] / dt;
  sim.step();         // moves
  sim.synchronize();  // the strain of that move into the elements
  for (std::size_t i = 0; i < nd.size(); ++i) nd.velocity[i].setZero();
  // The boundary nodes are held at X + A X; the interior ones are free.
  std::vector<bool> boundary(nd.size(), false);
  for (const auto& t : m.deformable.blocks[0].boundary)
    for (auto n : t) boundary[n] = true;
  std::size_t interior = 0;
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if (boundary[i]) nd.fixity[i] = 7;
    else ++interior;
  }
  REQUIRE(interior > 0);
  for (int s = 0; s < 200; ++s) sim.step();
  const Mat3 e = 0.5 * (a + a.transpose());
  const model::IsotropicElastic mat(30e9, 0.2);
  const Mat3 sigma = mat.bulk() * e.trace() * Mat3::Identity() + 2 * mat.shear() * (e - e.trace() / 3 * Mat3::Identity());
  const double scale = sigma.norm();
  double worst_stress = 0, worst_position = 0;
  const auto& te = m.deformable.tetrahedra;
  for (std::size_t t = 0; t < te.size(); ++t) {
    const auto& s = te.stress[t];
    Mat3 st;
    st << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    worst_stress = std::max(worst_stress, (st - sigma).norm() / scale);
  }
  for (std::size_t i = 0; i < nd.size(); ++i)
    worst_position = std::max(worst_position, (nd.position[i] - x0[i] - a * x0[i]).norm() / (a * x0[i]).norm());
  MESSAGE("patch test: " << te.size() << " tetrahedra, " << interior << " interior nodes; stress residual " << worst_stress
                         << ", interior displacement residual " << worst_position << " (relative)");
  CHECK(worst_stress < 1e-12);
  CHECK(worst_position < 1e-12);
}

TEST_CASE("deformable bar fixed at one end: first axial frequency c / (4L) within 1 % (fine mesh)") {
  // Reference: f_1 = c / (4L), c = sqrt(E / rho), for a rod fixed at one end and free at the other (nu = 0).
  const double young = 1e9, length = 1.0;
  const auto [t, u] = axial_bar(damping::None{}, young, length, 0.05, 0.025 * std::sqrt(3.0), 6.0);
  const auto decay = test::measure_decay(t, u, 1);
  const double expected = std::sqrt(young / 2000) / (4 * length);
  MESSAGE("bar: f = " << decay.frequency_hz << " Hz, c/(4L) = " << expected << " Hz, error "
                      << 100 * (decay.frequency_hz / expected - 1) << " %");
  CHECK(decay.frequency_hz == test::approx(expected).epsilon(0.01));
  CHECK(decay.damping_ratio < 1e-3);
}

TEST_CASE("deformable Maxwell branches in the elements: damping ratio from the decay matches zeta(f) within 5 %") {
  // Reference: zeta(omega) = Im(M_T) / (2 Re(M_T)) of the branches (eq. 19), at the measured frequency.
  const damping::Maxwell<1> policy({damping::MaxwellBranch::from_peak(0.05, two_pi * 60.0)});
  for (const double f : {15.0, 30.0, 60.0, 120.0, 240.0}) {
    const double young = 2000 * 16 * f * f;  // c / (4L) = f with L = 1 m
    const auto [t, u] = axial_bar(policy, young, 1.0, 0.1, 0.1 * std::sqrt(3.0), 8.0);
    const auto decay = test::measure_decay(t, u, 1);
    const double expected = policy.damping_ratio(two_pi * decay.frequency_hz);
    MESSAGE("E = " << young << " Pa: f = " << decay.frequency_hz << " Hz, zeta measured " << decay.damping_ratio
                   << ", zeta(f) " << expected << ", error " << 100 * (decay.damping_ratio / expected - 1) << " %");
    CHECK(decay.damping_ratio == test::approx(expected).epsilon(0.05));
  }
}

namespace {

/// A block width x depth x height on a fixed rigid base (top at z = 0), rigid or deformable.
struct Twin {
  model::Model model;
  std::size_t block = 0;
};
Twin block_on_base(bool deformable, double width, double depth, double height, double max_edge = 0.1, double young = 100e9) {
  Twin s;
  s.model.add_block(geometry::make_box(Vec3(-2 * width, -2 * depth, -0.5), Vec3(2 * width, 2 * depth, 0)), 2000, "base", 0,
                    model::Motion::fixed);
  s.block = s.model.add_block(geometry::make_box(Vec3(-0.5 * width, -0.5 * depth, 0), Vec3(0.5 * width, 0.5 * depth, height)),
                              2000, "block", 1);
  if (deformable) s.model.make_deformable(s.block, max_edge, model::IsotropicElastic(young, 0.2));
  return s;
}

/// Lateral load as a tilt of gravity by atan(ratio), ramped in quasi-statically under local damping; returns the
/// block's horizontal sliding displacement (m) and its rotation (rad, from the vertical displacements of its base
/// corners, or its orientation if rigid).
std::pair<double, double> tilted(bool deformable, double ratio, double friction_deg) {
  auto s = block_on_base(deformable, 0.2, 0.2, 0.4, 0.1, 20e9);  // stiff: 20 GPa
  const contact::MohrCoulomb::Parameters joint(1e10, 1e10, 0, 0, friction_deg * pi / 180);
  Simulation<damping::Local, contact::MohrCoulomb> sim(s.model, damping::Local{}, [&](int, int) { return joint; });
  sim.solve_to_equilibrium(1e-6, 20000);
  const auto& nd = s.model.deformable.nodes;
  const auto x0 = nd.position;
  const Vec3 p0 = s.model.bodies.position[s.block];
  const Quaternion q0 = s.model.bodies.orientation[s.block];
  const double ramp = 0.3, hold = 0.4, t0 = sim.time();  // s
  while (sim.time() - t0 < ramp + hold) {
    const double r = ratio * std::min(1.0, (sim.time() - t0) / ramp);
    s.model.gravity = 9.81 / std::sqrt(1 + r * r) * Vec3(r, 0, -1);
    sim.step();
  }
  if (!deformable) {
    const double rotation = 2.0 * (s.model.bodies.orientation[s.block] * q0.conjugate()).vec().y();
    return {s.model.bodies.position[s.block].x() - p0.x() - rotation * 0.2, std::abs(rotation)};
  }
  // Deformable: the base corners at x = -w/2 and +w/2, y = -d/2.
  double heel = 0, toe = 0, slide = 0;
  int count = 0;
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if (x0[i].z() > 1e-9 || x0[i].y() > -0.1 + 1e-9) continue;
    if (x0[i].x() < -0.1 + 1e-9) heel = nd.position[i].z() - x0[i].z();
    if (x0[i].x() > 0.1 - 1e-9) toe = nd.position[i].z() - x0[i].z();
    slide += nd.position[i].x() - x0[i].x();
    ++count;
  }
  return {slide / count, std::abs(heel - toe) / 0.2};
}

}  // namespace

TEST_CASE("deformable twin: a stiff deformable block and its rigid twin slide and uplift at the same thresholds (2 %)") {
  // Reference: sliding when tan(theta) > mu (here mu = tan 20 deg, the block slender enough not to tip); uplift when
  // a / g > b / h = 0.5 (mu = tan 45 deg, no sliding).
  for (const bool deformable : {false, true}) {
    const double mu = std::tan(20 * pi / 180);
    const auto below = tilted(deformable, 0.98 * mu, 20);
    const auto above = tilted(deformable, 1.02 * mu, 20);
    MESSAGE(std::string(deformable ? "deformable" : "rigid") << ": slip at 0.98 mu " << below.first << " m, at 1.02 mu " << above.first << " m");
    CHECK(std::abs(below.first) < 1e-4);
    CHECK(std::abs(above.first) > 1e-3);
    const auto stands = tilted(deformable, 0.98 * 0.5, 45);
    const auto tips = tilted(deformable, 1.02 * 0.5, 45);
    MESSAGE(std::string(deformable ? "deformable" : "rigid") << ": rotation at 0.98 b/h " << stands.second << " rad, at 1.02 b/h " << tips.second << " rad");
    CHECK(stands.second < 1e-3);
    CHECK(tips.second > 2e-3);
  }
}

TEST_CASE("deformable joint next to a face at a small angle: no node contact point off the joint") {
  // A block whose flat top (x < 0.5) carries a box, and whose top falls away beyond it at 10 degrees (a chamfer,
  // within the normal angle of the joint; as the webs of the vault meet at its groins). When the joint's overlap
  // reaches past the edge (here given so, to x = 0.8: in the vault, a sliver), the chamfer's triangles project onto
  // it, and their nodes, up to 0.3 tan 10 deg = 5.3 cm below the box, came in as contact points that far off the
  // joint. Every node contact point starts within twice the contact tolerance of the other block's face.
  const double drop = 0.5 * std::tan(10 * pi / 180);
  const Vec3 y(0, 1, 0);
  auto at = [](double x, double z) { return Vec3(x, 0, z); };
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-0.2, -0.2, -0.2), Vec3(1.2, 1.2, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto lower = m.add_block(geometry::make_prism({at(0, 0), at(1, 0), at(1, 0.5 - drop), at(0.5, 0.5), at(0, 0.5)}, y), 2000, "lower");
  const auto upper = m.add_block(geometry::make_box(Vec3(0, 0, 0.5), Vec3(1, 1, 0.8)), 2000, "upper");
  m.make_deformable(lower, 0.2, model::IsotropicElastic(1e9, 0.2));  // the finer mesh: the node side
  m.make_deformable(upper, 0.4, model::IsotropicElastic(1e9, 0.2));
  DeformableState<damping::None, contact::Elastic> state;
  state.setup(m);
  std::vector<model::ContactCandidate> joint;
  for (const double x : {0.0, 0.8})
    for (const double yy : {0.0, 1.0}) joint.push_back({lower, upper, Vec3(x, yy, 0.5), Vec3(0, 0, 1), Vec3(1, 0, 0), 0.2, 0.0});
  const model::ContactSettings settings;
  const contact::Elastic::Parameters parameters{1e9, 1e9};
  NodeContactAssignment<damping::None, contact::Elastic> assignment;
  assignment.assign(state, m, joint, [&](int, int) { return std::variant<contact::Elastic::Parameters>(parameters); }, settings, false);
  std::size_t points = 0, off = 0;
  double worst = 0;
  state.for_each_group([&](const auto& g) {
    for (std::size_t k = 0; k < g.size(); ++k) {
      ++points;
      worst = std::max(worst, std::abs(g.history[k].gap));
      if (m.deformable.nodes.position[g.node[k]][0] > 0.5 + 1e-9) ++off;
    }
  });
  MESSAGE(points << " node contact points, " << off << " on the chamfer, largest |gap| " << worst << " m");
  CHECK(points > 10);
  CHECK(off == 0);
  CHECK(worst <= 2 * settings.tolerance);
}

TEST_CASE("deformable density scaling: the target timestep is reached, the mass increase is the sum of the added masses") {
  // Reference: paper Sect. 3.2 (dsf = m_scaled / m_real; only nodes whose own limit is below the target are scaled).
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto fine = m.add_block(geometry::make_box(Vec3(-0.5, -0.2, 0), Vec3(0, 0.2, 0.4)), 2000, "fine", 1);
  const auto coarse = m.add_block(geometry::make_box(Vec3(0, -0.2, 0), Vec3(0.5, 0.2, 0.4)), 2000, "coarse", 1);
  const auto rigid = m.add_block(geometry::make_box(Vec3(-0.5, -0.2, 0.4), Vec3(0.5, 0.2, 0.5)), 7800, "rigid", 1);
  m.make_deformable(fine, 0.06, model::IsotropicElastic(30e9, 0.2));
  m.make_deformable(coarse, 0.25, model::IsotropicElastic(30e9, 0.2));
  Simulation<damping::None, contact::Elastic> sim(m, damping::None{}, [](int, int) { return contact::Elastic::Parameters(5e10, 2e10); });
  const double real_nodes = std::accumulate(m.deformable.nodes.real_mass.begin(), m.deformable.nodes.real_mass.end(), 0.0);
  const double real_rigid = m.bodies.mass[rigid];
  const double unscaled = sim.timestep();
  const double target = 1.5 * unscaled;
  const auto r = sim.scale_density_to(target);
  double added = 0;
  std::size_t scaled = 0;
  for (std::size_t i = 0; i < m.deformable.nodes.size(); ++i) {
    added += m.deformable.nodes.mass[i] - m.deformable.nodes.real_mass[i];
    if (m.deformable.nodes.density_scaling_factor(i) > 1) ++scaled;
  }
  added += m.bodies.mass[rigid] - real_rigid;
  MESSAGE("density scaling: dt " << unscaled << " -> " << r.dt << " s (critical " << r.dt_critical_unscaled << " -> "
                                 << r.dt_critical << " s), +" << r.mass_increase_percent << " % mass, " << r.scaled_nodes
                                 << " of " << m.deformable.nodes.size() << " nodes and " << r.scaled_blocks
                                 << " rigid blocks scaled, max dsf " << r.max_density_scaling_factor);
  CHECK(r.dt == target);
  CHECK(sim.timestep() == target);
  CHECK(decltype(sim)::bound_safety_factor * r.dt_critical >= target * (1 - 1e-9));
  CHECK(r.dt_critical_unscaled == test::approx(unscaled / decltype(sim)::bound_safety_factor));
  CHECK(r.added_mass == test::approx(added).epsilon(1e-12));
  CHECK(r.mass_increase_percent == test::approx(100 * added / (real_nodes + real_rigid)).epsilon(1e-12));
  CHECK(scaled == r.scaled_nodes);
  // Confined to the finely meshed block: the coarse one keeps its real masses.
  std::size_t scaled_coarse = 0, fine_nodes = 0;
  for (std::size_t i = 0; i < m.deformable.nodes.size(); ++i) {
    if (m.deformable.nodes.block[i] == coarse && m.deformable.nodes.density_scaling_factor(i) > 1) ++scaled_coarse;
    if (m.deformable.nodes.block[i] == fine) ++fine_nodes;
  }
  MESSAGE("fine block: " << fine_nodes << " nodes; coarse block nodes scaled: " << scaled_coarse);
  CHECK(scaled_coarse == 0);
  CHECK(scaled > 0);
  CHECK(scaled < m.deformable.nodes.size());
  // The weights stay real: at rest under gravity, the base carries the real weight.
  for (int k = 0; k < 3000; ++k) sim.step();
  CHECK(std::abs(sim.energy().balance_error) < 1e-2);
}

TEST_CASE("deformable static mass scaling: the same equilibrium as unscaled, restore gives back the real node masses") {
  // Reference: the unscaled settle of the same model (statics do not depend on the masses; node weights stay real).
  // Unbalanced-force ratio 1e-5: 3440 steps unscaled, 3180 scaled: the slowest mode is the deformable block's
  // bouncing on its joint (whole-block mass on the joint stiffness, ~1/50 of the node frequencies), which node-by-node
  // scaling cannot raise; the gain is the rigid blocks' and is small here.
  struct Settled {
    long long steps = 0;
    std::vector<Vec3> nodes, blocks;
  };
  const auto settle = [](bool scaled) {
    model::Model m = test::deformable_block_with_rigid_ones();
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Simulation<damping::Local, contact::Elastic> sim(m, damping::Local{}, [](int, int) { return contact::Elastic::Parameters(1e9, 4e8); },
                                                     contacts);
    const auto node_mass = m.deformable.nodes.mass;
    const auto block_mass = m.bodies.mass;
    const auto block_inertia = m.bodies.principal_inertia;
    Settled r;
    // Both at the timestep of eq. 1-3's estimate with its margin (the one static masses run at): the bound's larger
    // one for the unscaled run would compare two timesteps, not two mass distributions.
    const double estimate_dt = sim.estimate_safety_factor * 2 / sim.estimated_omega_max();
    if (!scaled) sim.set_timestep(estimate_dt);
    if (scaled) {
      const auto scaling = sim.scale_masses_for_statics(estimate_dt);
      CHECK(scaling.scaled_nodes == m.deformable.nodes.size());
      CHECK(scaling.scaled_blocks == 2);
      CHECK(scaling.mass_increase_percent < 0);  // the timestep was set by the elements: all lighter
    }
    CHECK(sim.solve_to_equilibrium(1e-5, 100000));
    r.steps = sim.steps();
    CHECK(sim.solve_to_equilibrium(1e-9, 100000));
    r.nodes = m.deformable.nodes.position;
    r.blocks = m.bodies.position;
    sim.restore_real_masses();
    CHECK(m.deformable.nodes.mass == node_mass);
    CHECK(m.bodies.mass == block_mass);
    CHECK(m.bodies.principal_inertia == block_inertia);
    for (std::size_t i = 0; i < node_mass.size(); ++i) CHECK(sim.deformable_state().node_inverse_mass[i] == 1.0 / node_mass[i]);
    CHECK(sim.timestep() == sim.default_timestep());
    return r;
  };
  const auto unscaled = settle(false);
  const auto scaled = settle(true);
  MESSAGE("settling a deformable block and two rigid ones to 1e-5: " << unscaled.steps << " steps unscaled, " << scaled.steps
                                                                      << " with static mass scaling");
  CHECK(scaled.steps <= unscaled.steps);
  const double sink = 1.177e-5;  // m, of the small block: its weight on its joint plus the deformable block's
  for (std::size_t i = 0; i < unscaled.nodes.size(); ++i) CHECK((scaled.nodes[i] - unscaled.nodes[i]).norm() <= 1e-6 * sink);
  for (std::size_t i = 0; i < unscaled.blocks.size(); ++i) CHECK((scaled.blocks[i] - unscaled.blocks[i]).norm() <= 1e-6 * sink);
}

TEST_CASE("deformable energy: kinetic + elastic (contacts, elements) + dissipated - work stays balanced (Maxwell<3>)") {
  // Reference: the conservation law of the central-difference scheme; damping work booked as dissipated.
  auto s = block_on_base(true, 0.3, 0.2, 0.3, 0.1);
  s.model.gravity = Vec3(3.0, 0, -9.81);
  const damping::Maxwell<3> policy({damping::MaxwellBranch::from_peak(0.02, two_pi * 10), damping::MaxwellBranch::from_peak(0.02, two_pi * 100),
                                    damping::MaxwellBranch::from_peak(0.02, two_pi * 1000)});
  Simulation<damping::Maxwell<3>, contact::MohrCoulomb> sim(s.model, policy, [](int, int) {
    return contact::MohrCoulomb::Parameters(1e10, 1e10, 0, 0, 0.3);
  });
  double worst = 0;
  for (int k = 0; k < 4000; ++k) {
    sim.step();
    if (k % 500 == 499) worst = std::max(worst, sim.energy().balance_error);
  }
  const auto e = sim.energy();
  MESSAGE("energy: kinetic " << e.kinetic << ", elastic " << e.elastic << ", viscous " << e.viscous << ", slip " << e.slip
                             << ", gravity work " << e.gravity_work << ", worst balance error " << worst);
  CHECK(e.slip > 0);
  CHECK(e.viscous > 0);
  CHECK(worst < 5e-3);
}

TEST_CASE("deformable threads: one and two threads give bitwise identical results") {
  auto run = [] {
    model::Model m;
    m.gravity = Vec3(2.0, 0, -9.81);
    m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
    const auto a = m.add_block(geometry::make_box(Vec3(-0.5, -0.25, 0), Vec3(0.5, 0.25, 0.5)), 2000, "a", 1);
    const auto b = m.add_block(geometry::make_box(Vec3(-0.5, -0.25, 0.5), Vec3(0.5, 0.25, 0.7)), 2000, "b", 1);
    m.add_block(geometry::make_box(Vec3(-0.5, -0.25, 0.7), Vec3(0.5, 0.25, 0.8)), 2000, "c", 1);
    m.make_deformable(a, 0.1, model::IsotropicElastic(10e9, 0.2));
    m.make_deformable(b, 0.12, model::IsotropicElastic(10e9, 0.2));
    Simulation<damping::Maxwell<1>, contact::MohrCoulomb> sim(m, damping::Maxwell<1>({damping::MaxwellBranch::from_peak(0.05, 300.0)}),
                                                              [](int, int) { return contact::MohrCoulomb::Parameters(1e10, 1e10, 0, 0, 0.4); });
    for (int k = 0; k < 200; ++k) sim.step();
    auto out = m.deformable.nodes.position;
    out.insert(out.end(), m.bodies.position.begin(), m.bodies.position.end());
    return out;
  };
  CHECK(test::differences_between_one_and_two_threads(run) == 0);
}

TEST_CASE("deformable threads: Maxwell<3> element tiles over several chunks give bitwise identical results and energy") {
  // More elements than the parallel threshold and than two viscous chunks, and a last, partial tile.
  using State = DeformableState<damping::Maxwell<3>, contact::MohrCoulomb>;
  std::size_t tetrahedra = 0;
  auto run = [&] {
    model::Model m;
    m.gravity = Vec3(2.0, 0, -9.81);
    m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
    const auto a = m.add_block(geometry::make_box(Vec3(-0.5, -0.25, 0), Vec3(0.5, 0.25, 0.5)), 2000, "a", 1);
    m.make_deformable(a, 0.06, model::IsotropicElastic(10e9, 0.2));
    tetrahedra = m.deformable.tetrahedra.size();
    const damping::Maxwell<3> policy({damping::MaxwellBranch::from_peak(0.05, 30.0), damping::MaxwellBranch::from_peak(0.05, 300.0),
                                      damping::MaxwellBranch::from_peak(0.05, 3000.0)});
    Simulation<damping::Maxwell<3>, contact::MohrCoulomb> sim(m, policy,
                                                              [](int, int) { return contact::MohrCoulomb::Parameters(1e10, 1e10, 0, 0, 0.4); });
    for (int k = 0; k < 100; ++k) sim.step();
    auto out = m.deformable.nodes.position;
    const auto e = sim.energy();
    out.push_back(Vec3(e.viscous, e.elastic, e.kinetic));
    return out;
  };
  CHECK(test::differences_between_one_and_two_threads(run) == 0);
  MESSAGE(tetrahedra << " tetrahedra");
  CHECK(State::element_tiles(tetrahedra) > 2);
  CHECK(tetrahedra % State::element_tile != 0);
}

TEST_CASE("deformable truss: a block hanging from a tie stretches it by W L / (E A)") {
  // The tie in the timestep bound: test_frequency_bound.cpp.
  // Reference: Hooke's law for an axial bar, delta = N L / (E A).
  model::Model m;
  const auto support = m.add_block(geometry::make_box(Vec3(-0.5, -0.5, 2), Vec3(0.5, 0.5, 2.2)), 2000, "support", 0, model::Motion::fixed);
  const auto block = m.add_block(geometry::make_box(Vec3(-0.1, -0.1, 0), Vec3(0.1, 0.1, 0.2)), 2000, "block", 1);
  m.make_deformable(block, 0.1, model::IsotropicElastic(30e9, 0.2));
  const double area = 8e-4, young = 200e9;  // steel: 2.4 um of stretch, all of the top node's displacement
  const auto top = m.nearest_node(block, Vec3(0, 0, 0.2));
  m.add_truss(m.block_end(support, Vec3(0, 0, 2)), m.node_end(top), area, young, 7800, 0.0, "tie");
  m.deformable.nodes.fixity.assign(m.deformable.nodes.size(), 0);
  // Keep the block from swinging: only vertical motion.
  for (auto& f : m.deformable.nodes.fixity) f = 3;
  Simulation<damping::Local, contact::Elastic> sim(m, damping::Local{}, elastic_joint);
  // The default ratio 1e-5 after about 7,400 steps (320,000 with a tie 100 times softer, whose bounce local damping
  // takes many periods to stop); the stretch then within 1e-5 of Hooke's (8e-6 measured).
  REQUIRE(sim.solve_to_equilibrium(1e-5, 100000));
  const double weight = 9.81 * (2000 * 0.008 + 0.5 * 7800 * area * 1.8);
  const double stretch = m.end_position(m.deformable.trusses[0].end[1]).z() - 0.2;
  const double expected = -weight * 1.8 / (young * area);
  MESSAGE("truss: stretch " << stretch << " m, W L / (E A) = " << expected << " m");
  CHECK(stretch == test::approx(expected).epsilon(1e-4));
  CHECK_THROWS_AS(m.add_truss(m.node_end(top), m.node_end(top), area, young, 7800), InvalidArgument);
  CHECK_THROWS_AS(m.add_truss(m.block_end(support, Vec3(0, 0, 2)), m.node_end(top), 0.0, young, 7800), InvalidArgument);
}

TEST_CASE("deformable bad input: degenerate tetrahedron, E <= 0, nu outside (-1, 0.5), max edge <= 0") {
  geometry::TetMesh flat;
  flat.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1e-9)};
  flat.tetrahedra = {{0, 1, 2, 3}};
  CHECK_THROWS_WITH_AS(geometry::check_mesh_quality(flat, "flat"), doctest::Contains("tetrahedron 0 is degenerate"), InvalidArgument);
  CHECK_THROWS_WITH_AS(model::IsotropicElastic(0.0, 0.2), doctest::Contains("Young's modulus must be > 0"), InvalidArgument);
  CHECK_THROWS_WITH_AS(model::IsotropicElastic(-1e9, 0.2), doctest::Contains("Young's modulus must be > 0"), InvalidArgument);
  CHECK_THROWS_WITH_AS(model::IsotropicElastic(1e9, 0.5), doctest::Contains("Poisson's ratio must be in (-1, 0.5)"), InvalidArgument);
  CHECK_THROWS_WITH_AS(model::IsotropicElastic(1e9, -1.0), doctest::Contains("Poisson's ratio"), InvalidArgument);
  const auto box = geometry::make_box(Vec3::Zero(), Vec3(1, 1, 1));
  CHECK_THROWS_WITH_AS(geometry::mesh_convex_polyhedron(box, 0.0, "b"), doctest::Contains("maximum edge length must be > 0 m"), InvalidArgument);
  CHECK_THROWS_AS(geometry::mesh_convex_polyhedron(box, -0.1, "b"), InvalidArgument);
  model::Model m;
  const auto i = m.add_block(box, 2000, "b");
  CHECK_THROWS_WITH_AS(m.make_deformable(i, 0.0, model::IsotropicElastic(1e9, 0.2)), doctest::Contains("block 'b'"), InvalidArgument);
}

TEST_CASE("deformable mesh: a general convex polyhedron (not a hexahedron) is fanned and refined, conforming") {
  // A triangular prism whose triangles are larger than the maximum edge: the fan path.
  const auto prism = geometry::make_prism({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, Vec3(0, 0, 0.5));
  const auto mesh = geometry::mesh_convex_polyhedron(prism, 0.3, "prism");
  double volume = 0;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) volume += mesh.volume(t);
  CHECK(volume == test::approx(0.25));
  CHECK(mesh.longest_edge() <= 0.3 * (1 + 1e-9));
  double area = 0;
  for (const auto& t : mesh.boundary)
    area += 0.5 * (mesh.nodes[t[1]] - mesh.nodes[t[0]]).cross(mesh.nodes[t[2]] - mesh.nodes[t[0]]).norm();
  CHECK(area == test::approx(2 * 0.5 + 0.5 * (1 + 1 + std::sqrt(2.0))));
}

TEST_CASE("deformable mesh: a long thin triangular prism (an infill wedge of the vault) is meshed in layers, none flat") {
  // The top infill piece of the cross vault at its groin: a skew wedge 0.39 m long with a 0.029 x 0.046 m section,
  // where a fan from the centroid refined to 0.25 m gave a tetrahedron of quality 0.0009.
  geometry::ConvexPolyhedron wedge;
  wedge.vertices = {Vec3(1.362947, 1.75, 1.754456), Vec3(1.362947, 1.75, 1.8),     Vec3(1.362947, 1.362947, 1.8),
                    Vec3(1.362947, 1.362947, 1.754456), Vec3(1.334061, 1.75, 1.8), Vec3(1.334061, 1.334061, 1.8)};
  wedge.faces = {{0, 1, 2, 3}, {1, 4, 5, 2}, {4, 0, 3, 5}, {4, 1, 0}, {5, 3, 2}};
  const auto mesh = geometry::mesh_convex_polyhedron(wedge, 0.25, "wedge");
  CHECK(mesh.tetrahedra.size() == 6);  // two layers of three
  double volume = 0, worst = 1;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    const auto& e = mesh.tetrahedra[t];
    worst = std::min(worst, geometry::tetrahedron_quality(mesh.nodes[e[0]], mesh.nodes[e[1]], mesh.nodes[e[2]], mesh.nodes[e[3]]));
    volume += mesh.volume(t);
  }
  CHECK(worst > 0.02);
  double exact = 0;  // the polyhedron's volume from its faces (divergence theorem)
  for (const auto& f : wedge.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
      exact += wedge.vertices[static_cast<std::size_t>(f[0])].dot(
                   wedge.vertices[static_cast<std::size_t>(f[i])].cross(wedge.vertices[static_cast<std::size_t>(f[i + 1])])) / 6.0;
  CHECK(volume == test::approx(std::abs(exact)).epsilon(1e-9));
  CHECK(mesh.longest_edge() <= 0.25 * (1 + 1e-9));
  double area = 0, surface = 0;
  for (std::size_t k = 0; k < mesh.boundary.size(); ++k) {
    const auto& t = mesh.boundary[k];
    area += 0.5 * (mesh.nodes[t[1]] - mesh.nodes[t[0]]).cross(mesh.nodes[t[2]] - mesh.nodes[t[0]]).norm();
    CHECK(mesh.boundary_face[k] >= 0);
  }
  for (std::size_t f = 0; f < wedge.faces.size(); ++f) surface += wedge.face_area(f);
  CHECK(area == test::approx(surface).epsilon(1e-9));
}

TEST_CASE("deformable reversibility: a deformable block bouncing on a rigid base retraces its motion when reversed") {
  // Reference: the central-difference scheme is time reversible; the constant-strain increments are linear in the
  // nodal velocities and the elastic joint is path independent, so reversal is exact up to rounding.
  auto s = block_on_base(true, 0.3, 0.2, 0.2, 0.1, 20e9);
  s.model.gravity = Vec3(1.0, 0.5, -9.81);
  for (auto& v : s.model.deformable.nodes.velocity) v = Vec3(0.05, 0, -0.1);
  model::ContactSettings contacts;
  contacts.tolerance = 0.01;  // no re-detection during the run: this test is about the scheme
  Simulation<damping::None, contact::Elastic> sim(s.model, damping::None{}, elastic_joint, contacts);
  const auto x0 = s.model.deformable.nodes.position;
  const int n = 3000;
  double moved = 0;  // largest excursion of a node
  for (int k = 0; k < n; ++k) {
    sim.step();
    for (std::size_t i = 0; i < x0.size(); ++i) moved = std::max(moved, (s.model.deformable.nodes.position[i] - x0[i]).norm());
  }
  sim.reverse();
  for (int k = 0; k < n; ++k) sim.step();
  double error = 0;
  for (std::size_t i = 0; i < x0.size(); ++i) error = std::max(error, (s.model.deformable.nodes.position[i] - x0[i]).norm());
  MESSAGE("reversibility: moved " << moved << " m, back within " << error << " m");
  CHECK(moved > 1e-5);
  CHECK(error / moved < 1e-9);
  CHECK(sim.detections() == 1);
}

}  // namespace test_deformable
