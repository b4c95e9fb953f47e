// Random models through the library's API, not its files: small assemblies of random convex blocks and boxes on a
// fixed or moving base, built from a seeded random stream (SplitMix64: the same models on every platform), with joint
// parameters drawn within their documented ranges, every damping policy, rigid, deformable and mixed kinematics, with
// and without partial density scaling, steel ties and base motion; each stepped a few hundred steps. Each model must
// build (or throw the documented InvalidArgument for the parameters deliberately put out of range), keep every
// position, velocity, force and stress finite, never trip the run guard, and close its energy balance.
//
// The fixed list of models: rows 0-41 cover every pair of (kinematics, damping policy, density scaling, ties, base
// motion) and every combination of the three switches with each kinematics; rows 42-47 are chosen cases, the first
// of them the rigid-only model with density scaling whose first step once read past the gather lists. A failing model
// is named by its row and seed; BLOCKDEM_FUZZ_ONLY=<row> runs that row alone.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/laws.hpp"
#include "blockdem/core/random.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/policies.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/motion/base_motion.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_model_fuzz {

namespace {

using Elastic = contact::Elastic;
using MohrCoulomb = contact::MohrCoulomb;
using Softening = contact::ElastoSoftening;
// The three laws in the vault study's order (analysis::VaultSimulation): the same simulation types as the vault tests,
// compiled once where this file shares their translation unit (tests/CMakeLists.txt).
template <class Damping>
using Sim = Simulation<Damping, Softening, MohrCoulomb, Elastic>;
using Properties = std::variant<Softening::Parameters, MohrCoulomb::Parameters, Elastic::Parameters>;

// ---- the random stream ----

struct Rng {
  SplitMix64 stream;
  double uniform(double a, double b) { return a + (b - a) * stream.uniform(); }
  double uniform_symmetric() { return stream.uniform_symmetric(); }
  double log_uniform(double a, double b) { return a * std::pow(b / a, stream.uniform()); }
  int integer(int a, int b) { return a + static_cast<int>(stream.next() % static_cast<std::uint64_t>(b - a + 1)); }
  bool chance(double p) { return stream.uniform() < p; }
  double angle_deg(double a, double b) { return uniform(a, b) * pi / 180.0; }
};

// ---- the rows: what each model is ----

enum class Kinematics { rigid, deformable, mixed };
enum class Policy { none, local, mass_proportional, stiffness_proportional, rayleigh, maxwell3, maxwell2 };
constexpr int policy_count = 7;

const char* name(Kinematics k) {
  switch (k) {
    case Kinematics::rigid: return "rigid";
    case Kinematics::deformable: return "deformable";
    default: return "mixed";
  }
}
const char* name(Policy p) {
  switch (p) {
    case Policy::none: return "None";
    case Policy::local: return "Local";
    case Policy::mass_proportional: return "MassProportional";
    case Policy::stiffness_proportional: return "StiffnessProportional";
    case Policy::rayleigh: return "Rayleigh";
    case Policy::maxwell3: return "Maxwell<3>";
    default: return "Maxwell<2>";
  }
}

struct Row {
  int index = 0;
  std::uint64_t seed = 0;
  Kinematics kinematics = Kinematics::rigid;
  Policy policy = Policy::none;
  bool density_scaling = false;
  bool ties = false;
  bool base_motion = false;
};

/// Rows 0-41: (kinematics, policy) in full twice; density scaling = the repetition, ties and base motion flipped by
/// bits of the policy and the kinematics, so that every pair of the five factors, and every combination of the three
/// switches with each kinematics, occurs. Rows 42-47: chosen cases.
std::vector<Row> rows() {
  std::vector<Row> r;
  for (int i = 0; i < 42; ++i) {
    const int k = i % 3, p = (i / 3) % policy_count, rep = i / 21;
    Row row;
    row.index = i;
    row.kinematics = static_cast<Kinematics>(k);
    row.policy = static_cast<Policy>(p);
    row.density_scaling = rep == 1;
    row.ties = (rep ^ (p & 1)) == 1;
    row.base_motion = (rep ^ ((p >> 1) & 1) ^ (k == 1 ? 1 : 0)) == 1;
    r.push_back(row);
  }
  auto add = [&](Kinematics k, Policy p, bool scaling, bool ties, bool base) {
    Row row;
    row.index = static_cast<int>(r.size());
    row.kinematics = k;
    row.policy = p;
    row.density_scaling = scaling;
    row.ties = ties;
    row.base_motion = base;
    r.push_back(row);
  };
  add(Kinematics::rigid, Policy::none, true, false, false);  // the rigid-only model with density scaling
  add(Kinematics::rigid, Policy::local, true, false, false);
  add(Kinematics::rigid, Policy::maxwell3, true, false, true);
  add(Kinematics::mixed, Policy::stiffness_proportional, true, true, true);
  add(Kinematics::deformable, Policy::maxwell2, true, true, true);
  add(Kinematics::rigid, Policy::rayleigh, false, true, false);  // rigid blocks and ties only: the mixed step
  for (auto& row : r) row.seed = 0x5EED0000ULL + 7919ULL * static_cast<std::uint64_t>(row.index);
  return r;
}

// ---- joint properties within their documented ranges ----

Properties random_elastic(Rng& rng) {
  const double kn = rng.log_uniform(1e8, 3e10);
  return Elastic::Parameters(kn, kn * rng.uniform(0.1, 1.0));
}

Properties random_mohr_coulomb(Rng& rng) {
  const double kn = rng.log_uniform(1e8, 3e10);
  const double ft = rng.chance(0.4) ? 0.0 : rng.log_uniform(1e2, 3e5);
  const double c = rng.chance(0.4) ? 0.0 : rng.log_uniform(1e2, 3e5);
  const double phi = rng.chance(0.1) ? 0.0 : rng.angle_deg(10, 45);
  return MohrCoulomb::Parameters(kn, kn * rng.uniform(0.1, 1.0), ft, c, phi, ft * rng.uniform(0, 0.5), c * rng.uniform(0, 0.5),
                                 rng.chance(0.5) ? -1.0 : phi * rng.uniform(0.6, 1.0));
}

Properties random_softening(Rng& rng) {
  if (rng.chance(0.3)) {  // from the material, eq. 4-7
    contact::MasonryJointProperties m;
    m.mortar_modulus = rng.log_uniform(100e6, 600e6);
    m.unit_modulus = m.mortar_modulus * rng.uniform(4, 20);
    m.mortar_thickness = rng.uniform(0.008, 0.02);
    m.poisson_ratio = rng.uniform(0.1, 0.3);
    m.tensile_strength = rng.log_uniform(1e4, 5e5);
    m.compressive_strength = rng.uniform(2e6, 15e6);
    // Within the documented bounds: G_f^I (eq. 4) above f_t^2 / (2 k_n), G_c (eq. 6) above 5 f_c^2 / (6 k_n).
    const double kn = contact::joint_stiffness_from_eq7(m.unit_modulus, m.mortar_modulus, m.mortar_thickness, m.poisson_ratio).normal;
    while (contact::fracture_energy_tension_eq4(m.tensile_strength) < 1.2 * m.tensile_strength * m.tensile_strength / (2 * kn))
      m.tensile_strength *= 0.7;
    while (contact::fracture_energy_compression_eq6(m.compressive_strength) <
           1.2 * 5 * m.compressive_strength * m.compressive_strength / (6 * kn))
      m.compressive_strength *= 0.7;
    m.compressive_strength = std::max(m.compressive_strength, 2 * m.tensile_strength);
    m.cohesion = m.tensile_strength * rng.uniform(0.5, 2);
    m.friction_angle = rng.angle_deg(20, 45);
    return Softening::Parameters::from_material(m, rng.chance(0.3) ? 0.0 : rng.uniform(1, 16), rng.uniform(0.2, 1.0));
  }
  const double kn = rng.log_uniform(1e9, 3e10);
  const contact::JointStiffness k{kn, kn * rng.uniform(0.2, 0.5)};
  Softening::Strengths s;
  s.tensile = rng.log_uniform(1e3, 5e5);
  s.cohesion = s.tensile * rng.uniform(0.5, 2);
  s.friction_angle = rng.angle_deg(15, 45);
  s.compressive = std::max(s.tensile * rng.uniform(5, 30), rng.uniform(1e6, 15e6));
  s.residual_tensile = rng.chance(0.5) ? 0.0 : s.tensile * rng.uniform(0, 0.2);
  s.residual_cohesion = rng.chance(0.5) ? 0.0 : s.cohesion * rng.uniform(0, 0.3);
  s.residual_friction_angle = rng.chance(0.5) ? -1.0 : s.friction_angle * rng.uniform(0.7, 1.0);
  // Above the elastic energies at the peaks (the documented lower bounds), and at least eq. 4-6.
  Softening::FractureEnergies g;
  g.tension = std::max(contact::fracture_energy_tension_eq4(s.tensile), s.tensile * s.tensile / (2 * kn)) * rng.uniform(1.2, 3);
  g.shear = g.tension * rng.uniform(2, 20);
  g.compression = std::max(15e3, 5 * s.compressive * s.compressive / (6 * kn)) * rng.uniform(1.2, 3);
  return Softening::Parameters(k, s, g, rng.chance(0.3) ? 0.0 : rng.uniform(1, 16), rng.uniform(0.2, 1.0));
}

const char* law_name(const Properties& p) {
  return std::visit([](const auto& v) -> const char* {
    using T = std::remove_cvref_t<decltype(v)>;
    if constexpr (std::is_same_v<T, Elastic::Parameters>) return "elastic";
    else if constexpr (std::is_same_v<T, MohrCoulomb::Parameters>) return "Mohr-Coulomb";
    else return "softening";
  }, p);
}

/// The joint properties of every pair of tags 0..3 (symmetric), from one law for all or a law per pair.
struct PropertyTable {
  std::map<std::pair<int, int>, Properties> table;
  std::string description;

  static PropertyTable random(Rng& rng) {
    PropertyTable t;
    const int mode = rng.integer(0, 3);  // 0 elastic, 1 Mohr-Coulomb, 2 softening, 3 a law per pair
    std::map<std::string, int> used;
    for (int a = 0; a <= 3; ++a)
      for (int b = a; b <= 3; ++b) {
        const int law = mode == 3 ? rng.integer(0, 2) : mode;
        Properties p = law == 0 ? random_elastic(rng) : law == 1 ? random_mohr_coulomb(rng) : random_softening(rng);
        ++used[law_name(p)];
        t.table.emplace(std::make_pair(a, b), std::move(p));
      }
    for (const auto& [law, count] : used) t.description += (t.description.empty() ? "" : "/") + law;
    return t;
  }
  Properties operator()(int a, int b) const { return table.at({std::min(a, b), std::max(a, b)}); }
};

// ---- geometry ----

/// A convex polygon of n vertices (3..7) on an ellipse with semi-axes (a, b), turned by `turn`, about (cx, cy), at z.
std::vector<Vec3> random_polygon(Rng& rng, double cx, double cy, double z, double a, double b) {
  const int n = rng.integer(3, 7);
  const double turn = rng.uniform(0, two_pi);
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    // Evenly spaced angles, each moved by at most a quarter spacing: edges never shrink to nothing.
    const double t = two_pi * (i + 0.25 * rng.uniform_symmetric()) / n;
    const double x = a * std::cos(t), y = b * std::sin(t);
    p.emplace_back(cx + x * std::cos(turn) - y * std::sin(turn), cy + x * std::sin(turn) + y * std::cos(turn), z);
  }
  return p;
}

/// A box [lo, hi] whose top face is the plane z = hi.z + sx (x - cx) + sy (y - cy) (a wedge-topped block).
geometry::ConvexPolyhedron slanted_box(const Vec3& lo, const Vec3& hi, double sx, double sy) {
  const double cx = 0.5 * (lo.x() + hi.x()), cy = 0.5 * (lo.y() + hi.y());
  auto top = [&](double x, double y) { return Vec3(x, y, hi.z() + sx * (x - cx) + sy * (y - cy)); };
  return geometry::make_hexahedron({Vec3(lo.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()),
                                    Vec3(lo.x(), hi.y(), lo.z()), top(lo.x(), lo.y()), top(hi.x(), lo.y()), top(hi.x(), hi.y()),
                                    top(lo.x(), hi.y())});
}

struct Built {
  model::Model model;
  std::size_t base = 0;
  std::vector<std::size_t> free_blocks;
  std::vector<std::size_t> on_base;  // free blocks standing on the base (for the interpenetration probe)
  std::vector<Vec3> top_centre;      // per block: the centre of its top face (m)
  std::vector<bool> flat_top;        // per block: whether that face is horizontal
  model::ContactSettings settings;
  std::size_t deformable = 0, tetrahedra = 0, ties = 0;
  bool dropped = false;  // a block starts in the air
  std::string description;
};

/// The base, then up to three groups along x: a column of random prisms (its top block possibly wedge-topped), a row
/// of boxes side by side with a lintel, or a box dropped onto the base. Groups 0.9 m apart, no wider than 0.8 m.
Built build(const Row& row, Rng& rng) {
  Built s;
  auto& m = s.model;
  model::ContactSettings& c = s.settings;
  c.tolerance = rng.log_uniform(5e-4, 4e-3);
  if (rng.chance(0.3)) c.max_contact_point_area = rng.uniform(0.004, 0.02);
  if (rng.chance(0.3)) c.max_normal_angle = rng.uniform(0.2, 0.6);
  if (rng.chance(0.3)) c.redetection_check_interval = rng.integer(1, 3);  // (1 again below if a block is in the air)
  if (rng.chance(0.2)) c.redetection_distance = rng.uniform(0.2, 1.0) * c.tolerance;
  const double tol = c.tolerance;
  // Joints closed to within 10 um, open or overlapping: a contact point found open on a joint with tensile strength
  // (elastic, bonded) starts in tension k_n gap, found overlapping in compression; either is released at the first step.
  auto gap = [&] { return rng.uniform(-1, 1) * std::min(0.05 * tol, 1e-5); };
  s.base = m.add_block(geometry::make_box(Vec3(-1.6, -1.0, -0.3), Vec3(1.6, 1.0, 0)), 2400, "base", 0,
                       row.base_motion ? model::Motion::base : model::Motion::fixed);
  std::ostringstream d;
  auto add = [&](const geometry::ConvexPolyhedron& shape, const std::string& label, bool on_base) {
    const auto i = m.add_block(shape, rng.uniform(1500, 2600), label, rng.integer(1, 3));
    s.free_blocks.push_back(i);
    if (on_base) s.on_base.push_back(i);
    return i;
  };
  auto record_top = [&](std::size_t i, const Vec3& centre, bool flat = true) {
    s.flat_top.resize(m.bodies.size(), false);
    s.top_centre.resize(m.bodies.size(), Vec3::Zero());
    s.flat_top[i] = flat;
    s.top_centre[i] = centre;
  };
  const int groups = rng.integer(1, 3);
  for (int gi = 0; gi < groups; ++gi) {
    const double gx = -0.9 + 0.9 * gi, gy = rng.uniform(-0.1, 0.1);
    const int kind = rng.integer(0, 9);
    if (kind < 5) {  // a column of 1-3 random prisms
      const int n = rng.integer(1, 3);
      double z = 0, cx = gx, cy = gy, a = rng.uniform(0.1, 0.25), b = rng.uniform(0.1, 0.25);
      d << " column " << n << ":";
      for (int k = 0; k < n; ++k) {
        const double h = rng.uniform(0.08, 0.4);
        const double bottom = z + (z == 0 && k == 0 ? std::max(0.0, gap()) : gap());  // not into the base's top
        const std::string label = "g" + std::to_string(gi) + " b" + std::to_string(k);
        std::size_t i;
        bool flat = true;
        if (k == n - 1 && rng.chance(0.3)) {  // a wedge-topped box on top
          const double hx = 0.7 * std::min(a, b), hy = 0.7 * std::min(a, b);
          const double sx = rng.uniform(-0.3, 0.3), sy = rng.uniform(-0.3, 0.3);
          i = add(slanted_box(Vec3(cx - hx, cy - hy, bottom), Vec3(cx + hx, cy + hy, bottom + h), sx, sy), label, k == 0);
          d << " wedge";
          flat = false;
        } else {
          i = add(geometry::make_prism(random_polygon(rng, cx, cy, bottom, a, b), Vec3(0, 0, h)), label, k == 0);
          d << " prism";
        }
        record_top(i, Vec3(cx, cy, bottom + h), flat);
        z = bottom + h;
        // The next one off centre by up to 0.3 of this one's smaller semi-axis, its own size.
        cx += 0.3 * std::min(a, b) * rng.uniform_symmetric();
        cy += 0.3 * std::min(a, b) * rng.uniform_symmetric();
        a = rng.uniform(0.1, 0.25);
        b = rng.uniform(0.1, 0.25);
      }
    } else if (kind < 8) {  // boxes side by side, touching, and a lintel across them
      const int n = rng.integer(2, 3);
      const double width = rng.uniform(0.1, 0.25), depth = rng.uniform(0.15, 0.4), h = rng.uniform(0.15, 0.4);
      double x = gx - 0.5 * n * width;
      std::vector<std::size_t> ids;
      for (int k = 0; k < n; ++k) {
        const double lo = x + (k == 0 ? 0.0 : gap());
        ids.push_back(add(geometry::make_box(Vec3(lo, gy - 0.5 * depth, 0), Vec3(lo + width, gy + 0.5 * depth, h)),
                          "g" + std::to_string(gi) + " box" + std::to_string(k), true));
        record_top(ids.back(), Vec3(lo + 0.5 * width, gy, h));
        x = lo + width;
      }
      const double bottom = h + gap(), lh = rng.uniform(0.06, 0.15);
      const auto lintel = add(geometry::make_box(Vec3(gx - 0.45 * n * width, gy - 0.4 * depth, bottom),
                                                 Vec3(gx + 0.45 * n * width, gy + 0.4 * depth, bottom + lh)),
                              "g" + std::to_string(gi) + " lintel", false);
      record_top(lintel, Vec3(gx, gy, bottom + lh));
      d << " row " << n << " + lintel";
    } else {  // a box dropped onto the base from 1.5-3 tolerances
      const double w = rng.uniform(0.1, 0.3), h = rng.uniform(0.1, 0.3), z = rng.uniform(1.5, 2) * tol;
      const auto i = add(geometry::make_box(Vec3(gx - 0.5 * w, gy - 0.5 * w, z), Vec3(gx + 0.5 * w, gy + 0.5 * w, z + h)),
                         "g" + std::to_string(gi) + " dropped", false);
      m.bodies.velocity[i] = Vec3(0, 0, -rng.uniform(0.02, 0.1));
      s.dropped = true;
      c.redetection_check_interval = 1;  // found before it lands, not up to a few steps' fall deep
      record_top(i, Vec3(gx, gy, z + h));
      d << " dropped box";
    }
  }
  // Motion: small random velocities and spins, now and then a fixity; gravity tilted (a lateral load) half the time.
  for (const auto i : s.free_blocks) {
    m.bodies.velocity[i] += 0.02 * Vec3(rng.uniform_symmetric(), rng.uniform_symmetric(), rng.uniform_symmetric());
    m.bodies.angular_velocity[i] = 0.05 * Vec3(rng.uniform_symmetric(), rng.uniform_symmetric(), rng.uniform_symmetric());
    if (rng.chance(0.1)) m.bodies.fixity[i] = rng.chance(0.5) ? model::Fixity::all_rotations : model::Fixity::translation_y;
  }
  if (rng.chance(0.5)) {
    const double r = rng.uniform(0, 0.3), t = rng.uniform(0, two_pi);
    m.gravity = 9.81 * Vec3(r * std::cos(t), r * std::sin(t), -1).normalized();
  }
  // Deformable blocks: all free blocks, or a random part of them with at least one rigid and one deformable.
  if (row.kinematics != Kinematics::rigid) {
    std::vector<std::size_t> chosen;
    if (row.kinematics == Kinematics::deformable) {
      chosen = s.free_blocks;
    } else {
      for (const auto i : s.free_blocks)
        if (rng.chance(0.5)) chosen.push_back(i);
      if (chosen.empty()) chosen.push_back(s.free_blocks[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.free_blocks.size()) - 1))]);
      if (chosen.size() == s.free_blocks.size()) {
        if (chosen.size() == 1) {  // one block only: a second, rigid one on top of it (or beside it, on the base)
          const bool flat = s.flat_top[chosen[0]];
          const Vec3 t = flat ? s.top_centre[chosen[0]] : Vec3(1.4, 0.7, 0.0);
          const auto i = add(geometry::make_box(t + Vec3(-0.05, -0.05, flat ? gap() : 0.0), t + Vec3(0.05, 0.05, 0.1)), "cap", !flat);
          record_top(i, t + Vec3(0, 0, 0.1));
          d << (flat ? " cap" : " box beside");
        } else {
          chosen.pop_back();
        }
      }
    }
    for (const auto i : chosen) {
      const double size = m.bodies.world_shape(i).diameter();
      const model::IsotropicElastic material(rng.log_uniform(0.5e9, 30e9), rng.uniform(0.0, 0.4));
      s.tetrahedra += m.make_deformable(i, size * rng.uniform(0.45, 0.9), material);
      ++s.deformable;
    }
  }
  // Steel ties: from the base to a block's top, or between the tops of two blocks.
  if (row.ties) {
    const int n = rng.integer(1, 2);
    auto end_at = [&](std::size_t i, const Vec3& x) {
      return m.deformable.is_deformable(i) ? m.node_end(m.nearest_node(i, x)) : m.block_end(i, x);
    };
    for (int k = 0; k < n; ++k) {
      const auto a = s.free_blocks[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.free_blocks.size()) - 1))];
      const auto b = s.free_blocks[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.free_blocks.size()) - 1))];
      const double area = rng.log_uniform(2e-5, 5e-4), young = rng.uniform(5e10, 2.1e11);
      // Pretension up to half the weight of the block it holds (a tie keeps a block in place, it does not throw it).
      const double pretension = rng.chance(0.5) ? 0.0 : rng.uniform(0, 0.5) * 9.81 * m.bodies.mass[b];
      model::TrussEnd end_b = end_at(b, s.top_centre[b]);
      model::TrussEnd end_a = a != b ? end_at(a, s.top_centre[a])
                                     : m.block_end(s.base, Vec3(s.top_centre[b].x() + rng.uniform(0.3, 0.5), s.top_centre[b].y(), -0.1));
      if ((m.end_position(end_a) - m.end_position(end_b)).norm() < 0.05)  // one block's top to itself: to the base
        end_a = m.block_end(s.base, Vec3(s.top_centre[b].x() - 0.4, s.top_centre[b].y(), -0.1));
      m.add_truss(end_a, end_b, area, young, 7850, pretension, "tie " + std::to_string(k));
      ++s.ties;
    }
  }
  s.description = d.str();
  return s;
}

// ---- damping policies within their documented ranges ----

template <int N>
damping::Maxwell<N> random_maxwell(Rng& rng) {
  if (rng.chance(0.3)) {  // fitted to zeta over a band (eq. 21-25)
    damping::MaxwellFitOptions o;
    o.damping_ratio = rng.uniform(0.01, 0.08);
    o.lower_hz = rng.uniform(0.5, 3);
    o.upper_hz = o.lower_hz * rng.uniform(10, 60);
    o.branches = N;
    o.points = 100;
    return damping::to_policy<N>(damping::fit_maxwell(o));
  }
  std::array<damping::MaxwellBranch, static_cast<std::size_t>(N)> b;
  for (auto& x : b) x = damping::MaxwellBranch::from_peak(rng.uniform(0.005, 0.05), two_pi * rng.log_uniform(1, 1000));
  return damping::Maxwell<N>(b);
}

damping::Rayleigh random_rayleigh(Rng& rng) {
  const double f1 = rng.uniform(0.5, 5), f2 = f1 * rng.uniform(3, 40), z2 = rng.uniform(0.01, 0.08);
  // zeta_1 / zeta_2 in [f1 / f2, f2 / f1] keeps both coefficients >= 0 (no negative damping anywhere).
  const double ratio = std::clamp(rng.log_uniform(0.5, 2), f1 / f2, f2 / f1);
  return damping::Rayleigh::from_two_frequencies(ratio * z2, f1, z2, f2);
}

// ---- checks ----

bool finite(const Vec3& v) { return v.allFinite(); }

/// The first value of the state that is not finite, named; empty if all are.
template <class S>
std::string first_not_finite(const S& sim) {
  const auto& m = sim.model();
  const auto& b = m.bodies;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (!finite(b.position[i]) || !b.orientation[i].coeffs().allFinite() || !b.rotation[i].allFinite() ||
        !finite(b.velocity[i]) || !finite(b.angular_velocity[i]) || !finite(b.force[i]) || !finite(b.moment[i]) ||
        !std::isfinite(b.mass[i]) || !finite(b.principal_inertia[i]))
      return "block '" + b.name[i] + "'";
  const auto& nd = m.deformable.nodes;
  for (std::size_t i = 0; i < nd.size(); ++i)
    if (!finite(nd.position[i]) || !finite(nd.velocity[i]) || !finite(nd.force[i]) || !std::isfinite(nd.mass[i]))
      return "node " + std::to_string(i);
  const auto& te = m.deformable.tetrahedra;
  for (std::size_t t = 0; t < te.size(); ++t)
    for (double x : te.stress[t])
      if (!std::isfinite(x)) return "tetrahedron " + std::to_string(t);
  std::string contact;
  sim.visit_contacts([&](const ContactView& v) {
    if (contact.empty() && (!finite(v.position) || !finite(v.normal) || !finite(v.force) || !std::isfinite(v.gap) ||
                            !std::isfinite(v.normal_stress) || !std::isfinite(v.shear_stress) || !std::isfinite(v.damage)))
      contact = "contact point between '" + b.name[v.block_a] + "' and '" + b.name[v.block_b] + "'";
  });
  if (!contact.empty()) return contact;
  const auto e = sim.energy();
  for (double x : {e.kinetic, e.elastic, e.gravity_work, e.base_work, e.viscous, e.slip, e.contact_update, e.balance_error})
    if (!std::isfinite(x)) return "energy report";
  if (!(sim.timestep() > 0) || !std::isfinite(sim.timestep())) return "timestep";
  return {};
}

/// The balance must close within this fraction of its largest term (EnergyReport::balance_error). The scheme
/// conserves its energy exactly for linear springs at any timestep, and every joint law books what it dissipates as
/// the scheme's own work on its springs (the trapezoid of the stresses at both samples) less their stored energy,
/// a normal spring whose path bends within a step (a joint that opens, closes, breaks, cracks or crushes) corrected
/// by the closure impulse (docs/energy.md). What is left: the timestep hold's mass raises at the velocities of the
/// moment, impacts found late (a block that moves past the contact tolerance between two detections, at up to three
/// times the default timestep under density scaling) and elastic contact points that come and go at the tolerance.
/// Of 833 rigid models of this generator with other seeds (BLOCKDEM_FUZZ_SEEDS=1000, docs/energy.md), the dynamic
/// run closes to 2e-6 in the median, 2.7 % at the 99th percentile, 19 above 1 % and 4 above 10 %; all those above
/// 1 % have a block dropped, ties or density scaling, and the four above 10 % all three, or 276 detections in 300
/// steps. The fixed rows below close within 2.5 % (row 12, Rayleigh), hence 5 %. Deformable blocks meet their
/// supports node by node, with the nodes' small masses: 0.7 % at most in 223 runs with other seeds (mixed models:
/// 3 % in all but one of 223), hence 2 % and 5 %. The bookkeeping errors this test found were 2 % to several times
/// the energy (a run's first step, the base's work, the ties' energy, Mohr-Coulomb's tension failure; regression
/// tests at the end of this file). Local damping's own boundary term is added (local_damping_boundary).
double balance_tolerance(Kinematics k) {
  switch (k) {
    case Kinematics::rigid: return 0.05;
    case Kinematics::mixed: return 0.05;
    default: return 0.02;
  }
}
constexpr double local_balance_tolerance = 0.1;

struct Outcome {
  std::string text;
  double balance_error = 0;          // the worst of the runs (settling under local damping and the dynamic run)
  double dynamic_balance_error = 0;  // the dynamic run's
  bool stopped = false;
  double start_boundary = 0;  // J, local damping's boundary term after the first step of the last run()
};

/// Local damping's work over a step, which the balance books at the mid-step velocity while the kinetic energy is
/// the product of the half-step velocities: the balance of a run under local damping is off by this term of its
/// first and of its last step, 1/2 c |F_i| |v_i| dt summed over the degrees of freedom (J; the last one vanishes as
/// the model comes to rest). Twice that, from the forces and velocities after the step.
template <class S>
double local_damping_boundary(const S& sim) {
  if constexpr (std::is_same_v<std::remove_cvref_t<decltype(sim.damping())>, damping::Local>) {
    const auto& m = sim.model();
    const auto& b = m.bodies;
    double sum = 0;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.motion[i] == model::Motion::free && !m.deformable.is_deformable(i))
        sum += b.force[i].norm() * b.velocity[i].norm() + b.moment[i].norm() * b.angular_velocity[i].norm();
    const auto& nd = m.deformable.nodes;
    for (std::size_t i = 0; i < nd.size(); ++i) sum += nd.force[i].norm() * nd.velocity[i].norm();
    return sim.damping().coefficient * sim.timestep() * sum;
  } else {
    return 0.0;
  }
}

/// Steps `steps` times; fails (with the run guard's message) if the guard stops the run.
template <class S>
bool run(S& sim, int steps, Outcome& out) {
  for (int i = 0; i < steps; ++i) {
    try {
      sim.step();
      if (i == 0) out.start_boundary = local_damping_boundary(sim);
    } catch (const RunawayError& e) {
      FAIL_CHECK("the run guard stopped the run: " << std::string(e.what()));
      out.stopped = true;
      return false;
    }
  }
  return true;
}

/// Checks after a run: every value finite, the balance closed within `tolerance`, and what is stored or dissipated
/// not negative: the joints' and elements' elastic energy is not, the ties' may be down to -P^2 / (2 k) each (a
/// pretensioned tie that shortens gives up P times its shortening); slip is dissipation; viscous work is, but for
/// local damping, whose force takes the sign of the velocity of the half step before and does positive work in a
/// step where the velocity turns (Local's own caveat, damping/local.hpp).
template <class S>
void check_state(const S& sim, const std::string& phase, double tolerance, Outcome& out) {
  const std::string bad = first_not_finite(sim);
  CHECK_MESSAGE(bad.empty(), "not finite: " << bad);
  const auto e = sim.energy();
  std::ostringstream t;
  t << phase << ": " << sim.steps() << " steps of " << sim.timestep() << " s, " << sim.contact_points() << " CPs, "
    << sim.detections() << " detections; energy kinetic " << e.kinetic << ", elastic " << e.elastic << ", gravity work "
    << e.gravity_work << ", base work " << e.base_work << ", viscous " << e.viscous << ", slip " << e.slip
    << ", contact update " << e.contact_update << " J, balance error " << e.balance_error;
  const TimestepHold& hold = sim.timestep_hold();
  if (hold.reductions > 0) t << "; timestep lowered " << hold.reductions << " times, to " << hold.smallest_dt << " s at least";
  if (hold.raises > 0) t << "; masses raised " << hold.raises << " times (+" << hold.added_mass << " kg, +" << hold.kinetic_energy << " J)";
  out.text += (out.text.empty() ? "" : "\n  ") + t.str();
  INFO(t.str());
  const double scale = std::max({std::abs(e.gravity_work) + std::abs(e.base_work), e.kinetic + e.elastic + e.viscous + e.slip, 1e-12});
  // (balance_error divides by a scale at least this one, so the bound holds whenever |change| <= tolerance scale + B.)
  const double boundary = (out.start_boundary + local_damping_boundary(sim)) / scale;
  INFO("local damping's boundary term " << boundary << " of the balance's scale");
  CHECK(e.balance_error < tolerance + boundary);
  out.balance_error = std::max(out.balance_error, e.balance_error);
  double pretension = 0;
  for (const auto& tie : sim.model().deformable.trusses) pretension += tie.pretension * tie.pretension / (2 * tie.axial_stiffness());
  CHECK(e.elastic >= -pretension - 1e-9 * scale);
  CHECK(e.slip >= -tolerance * scale);  // (a joint law books work less stored energy: a step that reverses the shear
                                        // past a collapsed limit, as a joint opens, books a little negative slip)
  if (!std::is_same_v<std::remove_cvref_t<decltype(sim.damping())>, damping::Local>) CHECK(e.viscous >= -1e-6 * scale);
}

// ---- parameters out of their ranges: each must throw InvalidArgument ----

/// One probe of a parameter put out of its documented range, by index (0..probe_count - 1).
constexpr int probe_count = 14;
void probe(int which, Rng& rng, const Built& s) {
  INFO("out-of-range probe " << which);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double kn = rng.log_uniform(1e8, 1e11);
  switch (which) {
    case 0: {
      const double bad[] = {0.0, -kn, nan, inf};
      CHECK_THROWS_AS(Elastic::Parameters(bad[rng.integer(0, 3)], kn), InvalidArgument);
      CHECK_THROWS_AS(Elastic::Parameters(kn, bad[rng.integer(0, 3)]), InvalidArgument);
      break;
    }
    case 1:
      CHECK_THROWS_AS(MohrCoulomb::Parameters(kn, kn, 0, 0, rng.angle_deg(90, 180)), InvalidArgument);
      CHECK_THROWS_AS(MohrCoulomb::Parameters(kn, kn, 1e4, 0, 0.5, 1e4 * rng.uniform(1.01, 3)), InvalidArgument);
      CHECK_THROWS_AS(MohrCoulomb::Parameters(kn, kn, 0, -rng.uniform(1, 1e5), 0.5), InvalidArgument);
      break;
    case 2: {
      Softening::Strengths st;
      st.tensile = 1e5;
      st.cohesion = 1e5;
      st.friction_angle = 0.6;
      st.compressive = st.tensile * rng.uniform(0.1, 1.0);  // not above the tensile strength
      CHECK_THROWS_AS(Softening::Parameters({1e10, 4e9}, st, {100, 1000, 1e5}), InvalidArgument);
      st.compressive = 5e6;
      // G_f^I below the elastic energy at the peak, f_t^2 / (2 k_n) = 0.5 J/m^2.
      CHECK_THROWS_AS(Softening::Parameters({1e10, 4e9}, st, {rng.uniform(0.01, 0.5), 1000, 1e5}), InvalidArgument);
      CHECK_THROWS_AS(Softening::Parameters({1e10, 4e9}, st, {100, 1000, 1e5}, 9.0, rng.chance(0.5) ? 0.0 : rng.uniform(1.01, 2)),
                      InvalidArgument);
      CHECK_THROWS_AS(Softening::Parameters({1e10, 4e9}, st, {100, 1000, 1e5}, -rng.uniform(0.1, 9)), InvalidArgument);
      break;
    }
    case 3:
      CHECK_THROWS_AS(model::IsotropicElastic(1e9, rng.uniform(0.5, 1.0)), InvalidArgument);
      CHECK_THROWS_AS(model::IsotropicElastic(1e9, -rng.uniform(1.0, 2.0)), InvalidArgument);
      CHECK_THROWS_AS(model::IsotropicElastic(-rng.log_uniform(1, 1e10), 0.2), InvalidArgument);
      break;
    case 4: {
      model::Model m = s.model;
      const auto i = s.free_blocks.front();
      if (!m.deformable.is_deformable(i))
        CHECK_THROWS_AS(m.make_deformable(i, rng.chance(0.5) ? 0.0 : -rng.uniform(0.01, 1), model::IsotropicElastic(1e9, 0.2)),
                        InvalidArgument);
      CHECK_THROWS_AS(m.make_deformable(s.base, 0.2, model::IsotropicElastic(1e9, 0.2)), InvalidArgument);  // not free
      CHECK_THROWS_AS(m.make_deformable(m.bodies.size() + 3, 0.2, model::IsotropicElastic(1e9, 0.2)), InvalidArgument);
      break;
    }
    case 5: {
      model::Model m = s.model;
      const auto i = s.free_blocks.back();
      const auto a = m.block_end(s.base, Vec3(0, 0, -0.1));
      const auto b = m.block_end(i, m.bodies.position[i]);
      CHECK_THROWS_AS(m.add_truss(a, b, rng.chance(0.5) ? 0.0 : -1e-4, 2e11, 7850), InvalidArgument);
      CHECK_THROWS_AS(m.add_truss(a, b, 1e-4, 2e11, 7850, -rng.uniform(1, 1e3)), InvalidArgument);
      CHECK_THROWS_AS(m.add_truss(a, a, 1e-4, 2e11, 7850), InvalidArgument);  // coincident ends
      CHECK(m.deformable.trusses.size() == s.model.deformable.trusses.size());
      break;
    }
    case 6: {
      model::Model m = s.model;
      const auto box = geometry::make_box(Vec3(5, 5, 5), Vec3(5.2, 5.2, 5.2));
      CHECK_THROWS_AS(m.add_block(box, rng.chance(0.5) ? 0.0 : -rng.uniform(1, 3000), "bad density"), InvalidArgument);
      auto dented = box;
      dented.vertices[6] -= Vec3(0.05, 0.05, 0.05);  // a corner pushed inwards: faces not planar, not convex
      CHECK_THROWS_AS(m.add_block(dented, 2000, "dented"), InvalidArgument);
      auto inside_out = box;
      for (auto& f : inside_out.faces) std::reverse(f.begin(), f.end());
      CHECK_THROWS_AS(m.add_block(inside_out, 2000, "inside out"), InvalidArgument);
      break;
    }
    case 7: {
      model::Model m = s.model;
      model::ContactSettings c = s.settings;
      switch (rng.integer(0, 3)) {
        case 0: c.tolerance = rng.chance(0.5) ? 0.0 : -1e-3; break;
        case 1: c.max_normal_angle = rng.uniform(1.5, 3); break;
        case 2: c.redetection_check_interval = -rng.integer(0, 5); break;
        default: c.max_contact_point_area = -rng.uniform(0.001, 0.1); break;
      }
      CHECK_THROWS_AS(Sim<damping::None>(m, damping::None{}, [](int, int) { return Properties(Elastic::Parameters(1e9, 1e9)); }, c),
                      InvalidArgument);
      break;
    }
    case 8: {  // a property function that builds a joint out of range: the constructor passes the throw on
      model::Model m = s.model;
      const int bad_tag = rng.integer(1, 3);
      const auto props = [bad_tag](int a, int b) -> Properties {
        if (a == bad_tag || b == bad_tag) return MohrCoulomb::Parameters(1e9, 1e9, 0, 0, 2.0);  // 115 degrees
        return Elastic::Parameters(1e9, 1e9);
      };
      bool touches = false;  // does a block with that tag touch something at the start? (else no joint is built)
      for (const auto& c : model::detect_contacts(m.bodies, s.settings))
        touches = touches || m.bodies.joint_tag[c.a] == bad_tag || m.bodies.joint_tag[c.b] == bad_tag;
      if (touches) CHECK_THROWS_AS(Sim<damping::None>(m, damping::None{}, props, s.settings), InvalidArgument);
      CHECK_THROWS_AS(Sim<damping::None>(m, damping::None{}, {}, s.settings), InvalidArgument);  // no property function
      break;
    }
    case 9: {  // one block pushed into the base by 2-5 tolerances
      if (s.on_base.empty()) break;
      model::Model m = s.model;
      const auto i = s.on_base[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.on_base.size()) - 1))];
      if (m.deformable.is_deformable(i)) break;  // (nodes keep their positions: move a rigid block)
      m.bodies.position[i].z() -= rng.uniform(2, 5) * s.settings.tolerance;
      CHECK_THROWS_WITH_AS(Sim<damping::None>(m, damping::None{}, [](int, int) { return Properties(Elastic::Parameters(1e9, 1e9)); },
                                              s.settings),
                           doctest::Contains("interpenetrate"), InvalidArgument);
      break;
    }
    case 10: {
      motion::SineVelocity sine{0.1, 0.1, 1, Vec3::UnitX(), 0};
      switch (rng.integer(0, 3)) {
        case 0: sine.period = rng.chance(0.5) ? 0.0 : -rng.uniform(0.01, 1); break;
        case 1: sine.cycles = -rng.integer(0, 3); break;
        case 2: sine.direction = Vec3::Zero(); break;
        default: sine.amplitude = inf; break;
      }
      CHECK_THROWS_AS(motion::BaseMotion{sine}, InvalidArgument);
      CHECK_THROWS_AS(motion::BaseMotion::constant(Vec3(nan, 0, 0)), InvalidArgument);
      break;
    }
    case 11: {
      motion::Record r;
      r.dt = 0.01;
      r.acceleration = {0.0, 1.0, 0.5};
      switch (rng.integer(0, 2)) {
        case 0: r.dt = rng.chance(0.5) ? 0.0 : -0.01; break;
        case 1: r.acceleration.resize(static_cast<std::size_t>(rng.integer(0, 1))); break;
        default: r.acceleration[1] = nan; break;
      }
      CHECK_THROWS_AS(motion::BaseMotion(r, {}, Vec3::UnitX()), InvalidArgument);
      break;
    }
    case 12: {
      const double f1 = rng.uniform(1, 10);
      CHECK_THROWS_AS(damping::Rayleigh::from_two_frequencies(0.05, f1, 0.05, f1 * rng.uniform(0.1, 1.0)), InvalidArgument);
      CHECK_THROWS_AS(damping::Rayleigh::from_two_frequencies(-0.01, 1, 0.05, 10), InvalidArgument);
      CHECK_THROWS_AS(damping::MaxwellBranch::from_peak(rng.chance(0.5) ? 0.0 : -0.02, 10), InvalidArgument);
      damping::MaxwellFitOptions o;
      o.damping_ratio = rng.uniform(0.5, 2);
      CHECK_THROWS_AS(damping::fit_maxwell(o), InvalidArgument);
      o = {};
      o.branches = rng.chance(0.5) ? 0 : rng.integer(9, 20);
      CHECK_THROWS_AS(damping::fit_maxwell(o), InvalidArgument);
      break;
    }
    default: {
      CHECK_THROWS_AS(contact::fracture_energy_compression_eq6(rng.uniform(151e6, 1e9)), InvalidArgument);  // f_c > 150 MPa
      CHECK_THROWS_AS(contact::fracture_energy_tension_eq4(rng.chance(0.5) ? 0.0 : -rng.uniform(1, 1e6)), InvalidArgument);
      CHECK_THROWS_AS(contact::joint_stiffness_from_eq7(1e9, rng.uniform(1e9, 2e9), 0.01, 0.2), InvalidArgument);  // E_b <= E_m
      break;
    }
  }
}

// ---- the run ----

constexpr int settle_steps = 150;
constexpr int dynamic_steps = 300;

/// A sine velocity of the table along a random, mostly horizontal direction, now and then with a short random
/// acceleration record along another and a constant drift; from about t0 on.
motion::BaseMotion random_base_motion(Rng& rng, double t0, std::ostringstream& d) {
  auto direction = [&] {
    const double t = rng.uniform(0, two_pi);
    return Vec3(std::cos(t), std::sin(t), rng.uniform(-0.3, 0.3));
  };
  motion::SineVelocity sine;
  sine.period = rng.uniform(0.05, 0.3);
  sine.amplitude = rng.uniform(1, 8) * sine.period / two_pi;  // peak acceleration 1-8 m/s^2
  sine.cycles = rng.integer(1, 3);
  sine.direction = direction();
  sine.start = t0 + rng.uniform(0, 0.005);
  motion::BaseMotion m(sine);
  d << "; base: sine " << sine.amplitude << " m/s, " << sine.period << " s x " << sine.cycles;
  if (rng.chance(0.4)) {
    motion::Record r;
    r.dt = rng.uniform(0.001, 0.005);
    r.acceleration.resize(static_cast<std::size_t>(rng.integer(5, 40)));
    const double peak = rng.uniform(1, 6);
    for (auto& a : r.acceleration) a = peak * rng.uniform_symmetric();
    m += motion::BaseMotion(r, {}, direction(), t0 + rng.uniform(0, 0.01));
    d << " + record of " << r.size() << " samples, " << peak << " m/s2";
  }
  if (rng.chance(0.2)) {
    const Vec3 v = rng.uniform(0.005, 0.02) * direction();
    m += motion::BaseMotion::constant(v);
    d << " + drift " << v.norm() << " m/s";
  }
  return m;
}

/// Out-of-range calls on a built simulation are refused and leave it as it was; then the dynamic run (density
/// scaling, a smaller timestep, base motion as the row says), and its checks.
template <class S>
void dynamic_run(S& sim, const Row& row, Built& s, Rng& rng, Outcome& out) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double dt0 = sim.timestep();
  const double critical = sim.critical_timestep();
  if (std::isfinite(critical)) CHECK_THROWS_AS(sim.set_timestep(critical * rng.uniform(1.05, 3)), InvalidArgument);
  const double bad_dt[] = {0.0, -1e-5, nan, inf};
  CHECK_THROWS_AS(sim.set_timestep(bad_dt[rng.integer(0, 3)]), InvalidArgument);
  CHECK_THROWS_AS(sim.scale_density_to(bad_dt[rng.integer(0, 3)]), InvalidArgument);
  CHECK_THROWS_AS(sim.scale_density_to(2 * dt0, rng.chance(0.5) ? 0.0 : rng.uniform(1.01, 3)), InvalidArgument);
  RunGuard bad_speed, bad_interval;
  bad_speed.max_speed = rng.chance(0.5) ? 0.0 : nan;
  bad_interval.check_interval = rng.chance(0.5) ? 0 : 2000000;
  CHECK_THROWS_AS(sim.set_run_guard(bad_speed), InvalidArgument);
  CHECK_THROWS_AS(sim.set_run_guard(bad_interval), InvalidArgument);
  CHECK(sim.timestep() == dt0);
  RunGuard guard;
  guard.check_interval = rng.integer(1, 32);
  sim.set_run_guard(guard);
  std::ostringstream d;
  if (row.density_scaling) {
    const double target = dt0 * rng.uniform(1.3, 3);
    const auto r = sim.scale_density_to(target);
    CHECK(r.dt == target);
    CHECK(sim.timestep() == target);
    CHECK(sim.mixed());
    CHECK(r.mass_increase_percent >= 0);
    d << "density scaling " << dt0 << " -> " << target << " s: +" << r.mass_increase_percent << " % mass, " << r.scaled_blocks
      << " blocks and " << r.scaled_nodes << " nodes scaled";
  } else if (rng.chance(0.3)) {
    sim.set_timestep(dt0 * rng.uniform(0.5, 1.0));
    d << "timestep " << dt0 << " -> " << sim.timestep() << " s";
  }
  if (row.base_motion) s.model.base_motion = random_base_motion(rng, sim.time(), d);
  out.text += (out.text.empty() ? "" : "\n  ") + d.str();
  if (!run(sim, dynamic_steps, out)) return;
  CHECK(sim.steps() >= dynamic_steps);
  constexpr bool local = std::is_same_v<std::remove_cvref_t<decltype(sim.damping())>, damping::Local>;
  check_state(sim, "dynamic run", local ? local_balance_tolerance : balance_tolerance(row.kinematics), out);
  out.dynamic_balance_error = sim.energy().balance_error;
}

/// The model under `policy`; for a viscous or undamped policy, now and then settled first under local damping (with
/// static mass scaling half the time, which the continuation refuses until the real masses are back) and continued.
template <class Damping>
void run_model(const Row& row, Built& s, const PropertyTable& table, Damping policy, Rng& rng, Outcome& out) {
  const typename Sim<Damping>::PropertyFunction properties = [table](int a, int b) { return table(a, b); };
  if (!std::is_same_v<Damping, damping::Local> && rng.chance(0.4)) {
    Sim<damping::Local> settling(s.model, damping::Local{rng.uniform(0.6, 0.9)}, properties, s.settings);
    // Static mass scaling with the safety factor 0.35: the estimate it follows is exact for a block on its own but
    // up to a factor 2 low for a chain of them (Simulation::estimate_safety_factor), and local damping holds only
    // for omega dt < 2 / sqrt(1 + c) = 1.49; with the default 0.5 a stack can reach omega dt = 2 and diverge (row 21
    // does, at 1.5 times per step). Not on a model with a block in the air: the timestep is not held under static
    // masses, and the block that lands on its new contacts reached omega dt = 14 (row 39).
    const bool statics = !s.dropped && rng.chance(0.5);
    if (statics) settling.scale_masses_for_statics(settling.timestep() * rng.uniform(0.7, 1.5), 0.35);
    out.text += std::string("settled ") + std::to_string(settle_steps) + " steps under local damping" +
                (statics ? " with static mass scaling" : "");
    if (!run(settling, settle_steps, out)) return;
    check_state(settling, "settling", local_balance_tolerance, out);
    if (statics) {
      CHECK_THROWS_AS(Sim<Damping>(settling, policy), InvalidArgument);
      settling.restore_real_masses();
    }
    Sim<Damping> sim(settling, policy);
    CHECK(sim.time() == settling.time());
    dynamic_run(sim, row, s, rng, out);
  } else {
    Sim<Damping> sim(s.model, policy, properties, s.settings);
    dynamic_run(sim, row, s, rng, out);
  }
}

void run_row(const Row& row, Built& s, const PropertyTable& table, Rng& rng, Outcome& out) {
  switch (row.policy) {
    case Policy::none: return run_model(row, s, table, damping::None{}, rng, out);
    case Policy::local: return run_model(row, s, table, damping::Local{rng.uniform(0.5, 0.9)}, rng, out);
    case Policy::mass_proportional:
      return run_model(row, s, table, damping::MassProportional::from_damping_ratio(rng.uniform(0.01, 0.1), rng.uniform(1, 20)), rng, out);
    case Policy::stiffness_proportional:
      return run_model(row, s, table, damping::StiffnessProportional::from_damping_ratio(rng.uniform(0.01, 0.1), rng.uniform(5, 100)),
                       rng, out);
    case Policy::rayleigh: return run_model(row, s, table, random_rayleigh(rng), rng, out);
    case Policy::maxwell3: return run_model(row, s, table, random_maxwell<3>(rng), rng, out);
    case Policy::maxwell2: return run_model(row, s, table, random_maxwell<2>(rng), rng, out);
  }
}

}  // namespace

/// The benchmark's models (BLOCKDEM_FUZZ_SEEDS=<n>, benchmarks/README.md): n rigid models, the configurations of
/// the fixed list's rigid rows in turn, each with a seed of its own, so that the fixed rows are a sample of them.
std::vector<Row> seeded_rows(int n) {
  std::vector<Row> rigid;
  for (const Row& row : rows())
    if (row.kinematics == Kinematics::rigid) rigid.push_back(row);
  std::vector<Row> r;
  for (int i = 0; i < n; ++i) {
    Row row = rigid[static_cast<std::size_t>(i) % rigid.size()];
    row.index = 1000 + i;
    row.seed = 0xF022000000ULL + 104729ULL * static_cast<std::uint64_t>(i);
    r.push_back(row);
  }
  return r;
}

/// The integer in the environment variable `name`, or `unset` without one; anything but an integer in [lo, hi]
/// fails the test, naming the variable, the range and the text.
int environment_integer(const char* name, int lo, int hi, int unset) {
  const char* text = std::getenv(name);
  if (!text) return unset;
  const char* end = text + std::strlen(text);
  int value = 0;
  const auto [stop, error] = std::from_chars(text, end, value);
  if (error != std::errc{} || stop != end || value < lo || value > hi)
    FAIL(std::string(name) << " must be an integer in [" << lo << ", " << hi << "], got '" << std::string(text) << "'");
  return value;
}

TEST_CASE("model fuzz: random models build or refuse bad input, stay finite and close their energy balance") {
  const int only = environment_integer("BLOCKDEM_FUZZ_ONLY", 0, std::numeric_limits<int>::max(), -1);
  const int seeds = environment_integer("BLOCKDEM_FUZZ_SEEDS", 1, 1000000, 0);
  const auto all = seeds > 0 ? seeded_rows(seeds) : rows();
  std::vector<double> balances;  // of the dynamic runs of the rigid models without local damping (their own tolerance)
  const auto start = std::chrono::steady_clock::now();
  int models = 0;
  double worst = 0;
  std::map<std::string, int> cells;  // kinematics x policy x scaling x ties x base motion
  for (const Row& row : all) {
    if (only >= 0 && only != row.index) continue;
    std::ostringstream head;
    head << "row " << row.index << " (seed 0x" << std::hex << row.seed << std::dec << "): " << name(row.kinematics) << ", "
         << name(row.policy) << (row.density_scaling ? ", density scaling" : "") << (row.ties ? ", ties" : "")
         << (row.base_motion ? ", base motion" : "");
    INFO(head.str());
    Rng rng{SplitMix64(row.seed)};
    Outcome out;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      Built s = build(row, rng);
      const PropertyTable table = PropertyTable::random(rng);
      std::ostringstream what;
      what << s.model.bodies.size() - 1 << " free blocks:" << s.description << "; " << s.deformable << " deformable ("
           << s.tetrahedra << " tetrahedra, " << s.model.deformable.nodes.size() << " nodes), " << s.ties << " ties; laws "
           << table.description << "; tolerance " << 1e3 * s.settings.tolerance << " mm";
      INFO(what.str());
      probe(9, rng, s);  // interpenetration, on every model
      for (int k = 0; k < 2; ++k) probe(rng.integer(0, probe_count - 1), rng, s);
      run_row(row, s, table, rng, out);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      MESSAGE(head.str() << "; " << what.str() << "\n  " << out.text << "\n  (" << seconds << " s)");
    } catch (const std::exception& e) {
      FAIL_CHECK("unexpected exception: " << std::string(e.what()) << "\n  " << out.text);
    }
    worst = std::max(worst, out.balance_error);
    if (row.kinematics == Kinematics::rigid && row.policy != Policy::local) balances.push_back(out.dynamic_balance_error);
    ++models;
    ++cells[std::string(name(row.kinematics)) + " " + name(row.policy) + (row.density_scaling ? " S" : " -") +
            (row.ties ? "T" : "-") + (row.base_motion ? "B" : "-")];
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE(models << " random models (" << cells.size() << " distinct cells of kinematics x policy x scaling x ties x base motion) in "
                 << seconds << " s; worst energy balance error " << worst
                 << " (tolerance 5 % rigid and mixed, 2 % deformable; under local damping 10 % and its boundary term)");
  if (!balances.empty()) {
    std::sort(balances.begin(), balances.end());
    const auto at = [&](double q) { return balances[static_cast<std::size_t>(q * static_cast<double>(balances.size() - 1))]; };
    MESSAGE(balances.size() << " rigid models without local damping, their dynamic runs: energy balance error median " << at(0.5) << ", 99th percentile "
                            << at(0.99) << ", worst " << balances.back() << "; "
                            << std::count_if(balances.begin(), balances.end(), [](double b) { return b > 0.01; }) << " above 1 %");
  }
  if (!only) CHECK(models == static_cast<int>(all.size()));
}

// ---- the bookkeeping errors the models above found, each on the smallest model that shows it ----

namespace {
/// A 1 x 1 x 1 m block of 2000 kg on a larger fixed (or base) block whose top is z = 0, its bottom `lift` above it.
model::Model block_above_base(double lift, model::Motion base = model::Motion::fixed) {
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-2, -2, -0.5), Vec3(2, 2, 0)), 2000, "base", 0, base);
  m.add_block(geometry::make_box(Vec3(-0.5, -0.5, lift), Vec3(0.5, 0.5, 1 + lift)), 2000, "block", 1);
  return m;
}
}  // namespace

TEST_CASE("energy: dissipation of a run's first step is part of the balance's reference") {
  // A bonded Mohr-Coulomb joint found open by 0.5 mm (within the 1 mm tolerance) starts in tension k_n g = 5e5 Pa,
  // beyond f_t = 1e3 Pa: it breaks at the first step, with no motion, releasing f_t g - f_t^2 / (2 k_n) per m^2 (no
  // gravity, nothing else happens). The reference was kinetic + elastic of the first step only: 100 % error.
  auto m = block_above_base(5e-4);
  m.gravity = Vec3::Zero();
  const MohrCoulomb::Parameters joint(1e9, 1e9, 1e3, 0, 0.5);
  Sim<damping::None> sim(m, damping::None{}, [&](int, int) { return Properties(joint); });
  for (int i = 0; i < 10; ++i) sim.step();
  const auto e = sim.energy();
  CHECK(e.slip == doctest::Approx(1e3 * 5e-4 - 0.5 * 1e3 * 1e3 / 1e9).epsilon(1e-9));  // 1 m^2
  CHECK(e.balance_error < 1e-12);
}

TEST_CASE("energy: Mohr-Coulomb books the energy a tension failure releases and stores the residual tension's") {
  // Opened past the cut-off and closed again in steps of 1 um: the work done on the normal spring (trapezoid rule)
  // equals what it stores plus what it dissipated, but for the step in which it fails, whose trapezoid differs from
  // the path by at most f_t du / 2 = 0.005 J/m^2. Before: the elastic energy lost at the failure (0.05 J/m^2) was
  // booked nowhere, nor the energy of an opening at the residual tension, which closing gives back (0.49 J/m^2).
  for (const double residual : {0.0, 5e3}) {
    CAPTURE(residual);
    const MohrCoulomb::Parameters p(1e9, 1e9, 1e4, 0, 0.5, residual);
    MohrCoulomb::History h;
    double work = 0, dissipated = 0, worst = 0;
    const auto move = [&](double du) {
      const double before = h.normal;
      dissipated += MohrCoulomb::update(p, h, du, {0, 0}).dissipated;
      work -= 0.5 * (before + h.normal) * du;  // compression positive: opening against tension is work done on it
      worst = std::max(worst, std::abs(work - MohrCoulomb::stored_energy(p, h) - dissipated));
    };
    for (int i = 0; i < 100; ++i) move(1e-6);  // to 0.1 mm, ten times the elastic limit
    CHECK(MohrCoulomb::stored_energy(p, h) == doctest::Approx(residual * 1e-4 - 0.5 * residual * residual / 1e9));
    const double at_failure = dissipated;
    for (int i = 0; i < 100; ++i) move(-1e-6);
    CHECK(dissipated > 0);
    CHECK(dissipated == at_failure);  // once, at the failure: the residual tension's opening and closing store
    CHECK(MohrCoulomb::stored_energy(p, h) == doctest::Approx(0.0));
    CHECK(worst <= 0.5 * 1e4 * 1e-6 * (1 + 1e-9));
  }
}

TEST_CASE("energy: the base's work is the mean of the forces at both ends of a move (leapfrog energy, 2.5 g sine)") {
  // A block on elastic joints on a shaking table, no gravity, rotations fixed: linear springs and a prescribed base,
  // so the leapfrog's energy balance is exact. With the force at the end of the move alone the base's work was off by
  // dt/2 times the integral of F.a: the balance error was about 1.
  auto m = block_above_base(0, model::Motion::base);
  m.gravity = Vec3::Zero();
  m.bodies.fixity[1] = model::Fixity::all_rotations;
  Sim<damping::None> sim(m, damping::None{}, [](int, int) { return Properties(Elastic::Parameters(1e9, 5e8)); });
  m.base_motion = motion::BaseMotion(motion::SineVelocity{0.2, 0.05, 3, Vec3(1, 0.3, 0), 0.0});  // 25 m/s^2
  double worst = 0;
  while (sim.time() < 0.2) {
    sim.step();
    worst = std::max(worst, sim.energy().balance_error);
  }
  CHECK(std::abs(sim.energy().base_work) > 0);
  CHECK(worst < 1e-9);
}

TEST_CASE("energy: a tie's energy is that of the positions its force was computed at") {
  // A block in the air, no gravity, rotations fixed, held by a steel tie from the base: the tie's energy was taken
  // at the positions after the step, one step ahead of its force and of every other term (balance error 0.97).
  auto m = block_above_base(0.05);
  m.gravity = Vec3::Zero();
  m.bodies.fixity[1] = model::Fixity::all_rotations;
  m.bodies.velocity[1] = Vec3(0.01, 0.005, 0);
  m.add_truss(m.block_end(0, Vec3(0.4, 0, -0.1)), m.block_end(1, Vec3(0, 0, 1.05)), 1e-4, 2e11, 7850, 0.0, "tie");
  Sim<damping::None> sim(m, damping::None{}, [](int, int) { return Properties(Elastic::Parameters(1e9, 5e8)); });
  REQUIRE(sim.contact_points() == 0);
  double worst = 0;
  for (int i = 0; i < 1000; ++i) {
    sim.step();
    worst = std::max(worst, sim.energy().balance_error);
  }
  CHECK(sim.energy().elastic > 0);
  CHECK(worst < 1e-4);  // the tie turns as the block moves sideways: second order in the timestep
}

TEST_CASE("energy: a step taken with another timestep books the change of the kinetic energy measure") {
  // A block bouncing and sliding on an elastic (glued, linear) joint under gravity, rotations fixed: the leapfrog's
  // energy 1/2 m v(n-1/2).v(n+1/2) + U(x_n) is conserved exactly at a constant timestep. Changing the timestep
  // between steps changes that measure by its impulse part times 1 - dt_old / dt_new (energy.hpp,
  // half_step_kinetic); booked (contact_update), the balance closes to rounding (2e-15). Without it the balance was
  // 0.99 off here (row 1831 of the 1,000-seed fuzz: 12.5 %).
  auto m = block_above_base(0);
  m.bodies.fixity[1] = model::Fixity::all_rotations;
  m.bodies.velocity[1] = Vec3(0.02, -0.01, -0.05);
  Sim<damping::None> sim(m, damping::None{}, [](int, int) { return Properties(Elastic::Parameters(1e9, 4e8)); });
  const double dt = sim.timestep();
  double worst = 0;
  for (const double factor : {1.0, 0.5, 0.8, 0.3, 1.0}) {
    sim.set_timestep(factor * dt);
    for (int i = 0; i < 37; ++i) {
      sim.step();
      worst = std::max(worst, sim.energy().balance_error);
    }
  }
  const auto e = sim.energy();
  MESSAGE("kinetic " << e.kinetic << " J, elastic " << e.elastic << " J, timestep changes booked " << e.contact_update
                     << " J; worst balance error " << worst);
  CHECK(std::abs(e.contact_update) > 1e-3 * (e.kinetic + e.elastic));  // the term matters
  CHECK(worst < 1e-12);
}

TEST_CASE("energy: a softening joint that cracks and slips in a dynamic run closes its books") {
  // A block on a bonded elasto-softening joint (Table 1 masonry) thrown up and sideways, no gravity, undamped: the
  // joint cracks through in tension and slips, the block flies off. Its laws book the scheme's own work (the
  // trapezoid of the stresses at both samples less the change of stored energy) and send the trapezoid error of
  // each step where the normal path bends (the peak, the softening branch) to the closure impulse: the balance
  // closes to 1.0e-6. Booked as the envelope's and the return's integrals along the path it closed to 8.3e-3 here
  // (fuzz row 1306: 18 %).
  auto m = block_above_base(0);
  m.gravity = Vec3::Zero();
  m.bodies.velocity[1] = Vec3(0.2, 0.1, 0.3);
  m.bodies.angular_velocity[1] = Vec3(0.2, -0.1, 0.05);
  Sim<damping::None> sim(m, damping::None{}, [](int, int) { return Properties(Softening::Parameters::from_material()); });
  const double kinetic0 = 0.5 * 2000 * (0.2 * 0.2 + 0.1 * 0.1 + 0.3 * 0.3);
  double worst = 0, damage = 0;
  for (int i = 0; i < 3000; ++i) {
    sim.step();
    worst = std::max(worst, sim.energy().balance_error);
    sim.visit_contacts([&](const auto& c) { damage = std::max(damage, c.damage); });
  }
  const auto e = sim.energy();
  MESSAGE("dissipated " << e.slip << " J of " << kinetic0 << " J; largest damage " << damage << "; " << sim.contact_points()
                        << " CPs left; worst balance error " << worst);
  CHECK(damage > 0.99);  // cracked through
  CHECK(e.slip > 1.0);   // J: at least the tension fracture energy of part of the 1 m^2 joint
  CHECK(worst < 1e-5);
}

}  // namespace test_model_fuzz
