#pragma once
// The timestep (paper eq. 1-3, 11, 20) and partial density scaling (Sect. 3.2): the upper bound on omega_max for
// the present contacts, elements, trusses and masses (FrequencyBound), eq. 1-3's per-node and per-block estimate,
// and the masses that bring every free node and rigid block to a target timestep. Simulation keeps the state and
// calls these; they read the model and the contact groups and change nothing.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "blockdem/core/rotation.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/integrate/block_pass.hpp"
#include "blockdem/integrate/contact_frame.hpp"
#include "blockdem/integrate/frequency_bound.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

enum class TimestepCheck { checked, unchecked };

/// What partial density scaling did (paper Sect. 3.2: only nodes and rigid blocks whose own limit is below the
/// target are made heavier; dsf = m_scaled / m_real per node), or static mass scaling (every node and block set to
/// the mass of the target: some lighter, so added_mass may be negative).
struct DensityScaling {
  double target_dt = 0;              // s, the timestep asked for (the one the simulation now runs with)
  double dt_critical_unscaled = 0;   // s, critical timestep before this scaling
  double dt_critical = 0;            // s, critical timestep after scaling
  double dt = 0;                     // s, the timestep set
  double real_mass = 0;              // kg, free nodes and free rigid blocks before scaling
  double added_mass = 0;             // kg, scaled minus real (negative if static scaling made the model lighter)
  double mass_increase_percent = 0;  // 100 added / real
  std::size_t scaled_nodes = 0, scaled_blocks = 0;  // whose mass (blocks: or inertia) this scaling changed
  // m_scaled / m_real over the free nodes and free rigid blocks (blocks: also I_min,scaled / I_min,real)
  double max_density_scaling_factor = 1;
  double min_density_scaling_factor = 1;
};

/// What holding the timestep against contacts that appear during a dynamic run did (Simulation::hold_timestep()):
/// re-detection may add contact points whose stiffness lowers the critical timestep below the one the run was set
/// up with. A density-scaled run keeps its timestep and raises the masses of the rows that now exceed the target,
/// by the rule of the first scaling (partial density scaling kept up to date); a run without density scaling keeps
/// its margin below the critical timestep by lowering the timestep. Counts are cumulative over the simulation.
struct TimestepHold {
  long long checks = 0;           // re-detections after which the bound was checked
  long long raises = 0;           // of them, those after which some mass was raised
  long long raised_nodes = 0;     // nodes raised, counted once per raise
  long long raised_blocks = 0;    // rigid blocks raised (mass and inertia by one factor), counted once per raise
  double added_mass = 0;          // kg, mass added by the raises
  double kinetic_energy = 0;      // J, kinetic energy the raises added at the velocities of the moment
  long long reductions = 0;       // timestep lowered (runs without density scaling)
  double smallest_dt = 0;         // s, the smallest timestep after a reduction (0: none)
};

/// How scale_masses() sets masses: raise only those whose own limit is below the target (partial density
/// scaling), or set every one to the mass of the target (static mass scaling).
enum class MassRule { raise_only, exact };

/// The masses that scale_masses() sets (free nodes; rigid blocks: mass and principal inertia).
struct MassPlan {
  std::vector<double> node_mass, block_mass;
  std::vector<Vec3> block_inertia;
  /// FrequencyBound's omega_max (rad/s) for the masses before the plan, when the plan was made from it (partial
  /// density scaling under bounded frequency; 0 otherwise): what omega_max() gives while no mass changes.
  double omega_max = 0;
};

/// The real (unscaled) masses and principal inertias of the rigid blocks.
struct RealMasses {
  const std::vector<double>* mass = nullptr;
  const std::vector<Vec3>* inertia = nullptr;
};

/// omega_t (rad/s) with safety 2 f(omega_t) / omega_t = target_dt (f: the policy's eq. 11 or eq. 20 factor), by
/// bisection in log omega; returned squared and lowered by a relative 1e-9 so that the masses it gives are on the
/// safe side of the target.
template <class Factor>
double target_omega_squared(double target_dt, double safety_factor, Factor timestep_factor, double margin) {
  auto limit = [&](double omega) { return safety_factor * 2.0 / omega * timestep_factor(omega); };
  double lo = 1e-12, hi = 1e15;
  for (int it = 0; it < 200; ++it) {
    const double mid = std::sqrt(lo * hi);
    (limit(mid) > target_dt ? lo : hi) = mid;
  }
  return lo * lo / margin;
}

/// The upper bound on omega_max for the present contacts, elements, trusses and masses.
template <class Groups, class Deformable>
FrequencyBound frequency_bound(const model::Model& m, const Groups& groups, const Deformable* deformable) {
  const auto& b = m.bodies;
  FrequencyBound bound(m);
  for_each_in(groups, [&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t c = 0; c < g.contacts(); ++c) {
      const auto& p = g.properties[g.property[c]];
      const double kn = L::normal_stiffness(p), ks = L::shear_stiffness(p);
      const ContactFrame fr = contact_frame(b, g, c);
      const Mat3 nn = fr.n * fr.n.transpose();
      const Mat3 per_area = kn * nn + ks * (Mat3::Identity() - nn);
      bound.connect(g.body_a[c], g.body_b[c], [&](auto&& spring) {
        for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) {
          const Vec3 x = fr.point(g.s1[k], g.s2[k]);
          spring(x, x, Mat3(g.area[k] * per_area));
        }
      });
    }
  });
  for (const auto& t : m.deformable.trusses) {
    const auto point = [&](const model::TrussEnd& e) {
      return e.node >= 0 ? FrequencyBound::node_point(static_cast<std::size_t>(e.node))
                         : FrequencyBound::block_point(e.block, b.position[e.block] + rotate(b.rotation[e.block], e.body_point));
    };
    const Vec3 e = (m.end_position(t.end[1]) - m.end_position(t.end[0])).normalized();
    bound.spring({point(t.end[0])}, {point(t.end[1])}, Mat3(t.axial_stiffness() * e * e.transpose()));
  }
  if (deformable) deformable->add_to(m, bound);
  return bound;
}

/// Eq. 1-3's estimate of omega_max (rad/s): per node and per rigid block on its own (see critical_timestep()).
template <class Groups, class Deformable>
double estimated_omega_max(const model::Model& m, const Groups& groups, const Deformable* deformable) {
  const auto& b = m.bodies;
  std::vector<double> k_translation, k_rotation, k_node;
  stiffnesses(m, groups, deformable, k_translation, k_rotation, k_node);
  double omega_max = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.motion[i] != model::Motion::free) continue;
    if ((b.fixity[i] & 7) != 7) omega_max = std::max(omega_max, std::sqrt(k_translation[i] / b.mass[i]));
    if ((b.fixity[i] & model::Fixity::all_rotations) != model::Fixity::all_rotations)
      omega_max = std::max(omega_max, std::sqrt(k_rotation[i] / b.principal_inertia[i].minCoeff()));
  }
  const auto& nd = m.deformable.nodes;
  for (std::size_t i = 0; i < k_node.size(); ++i)
    if ((nd.fixity[i] & 7) != 7) omega_max = std::max(omega_max, std::sqrt(k_node[i] / nd.mass[i]));  // eq. 1-3
  return omega_max;
}

/// Stiffness (N/m) on each rigid block (translation; rotation k r^2 in N m) and on each node: contacts, elements
/// (eq. 2) and trusses.
template <class Groups, class Deformable>
void stiffnesses(const model::Model& m, const Groups& groups, const Deformable* deformable, std::vector<double>& k_translation,
                 std::vector<double>& k_rotation, std::vector<double>& k_node) {
  const auto& b = m.bodies;
  k_translation.assign(b.size(), 0.0);
  k_rotation.assign(b.size(), 0.0);
  for_each_in(groups, [&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t c = 0; c < g.contacts(); ++c) {
      const auto& p = g.properties[g.property[c]];
      const double k_spring = std::max(L::normal_stiffness(p), L::shear_stiffness(p));
      const std::size_t a = g.body_a[c], bb = g.body_b[c];
      const ContactFrame fr = contact_frame(b, g, c);
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) {
        const double stiffness = k_spring * g.area[k];
        const Vec3 x = fr.point(g.s1[k], g.s2[k]);
        k_translation[a] += stiffness;
        k_translation[bb] += stiffness;
        k_rotation[a] += stiffness * (x - b.position[a]).squaredNorm();
        k_rotation[bb] += stiffness * (x - b.position[bb]).squaredNorm();
      }
    }
  });
  k_node.clear();
  if (deformable) deformable->add_stiffness(m, k_node, k_translation, k_rotation);
}

template <class Groups, class Deformable, class Factor>
MassPlan plan_masses(const model::Model& m, const Groups& groups, const Deformable* deformable, const RealMasses& real,
                     bool bounded_frequency, double target_dt, double safety_factor, MassRule rule, Factor timestep_factor,
                     const FrequencyBound* given_bound = nullptr) {
  const auto& b = m.bodies;
  const auto& nd = m.deformable.nodes;
  const double margin = 1.0 + 1e-9;
  const double omega2 = target_omega_squared(target_dt, safety_factor, timestep_factor, margin);
  MassPlan plan{nd.mass, b.mass, b.principal_inertia};
  const bool bounded = rule == MassRule::raise_only && bounded_frequency;
  std::vector<double> kt, kr, kn;
  if (!bounded) stiffnesses(m, groups, deformable, kt, kr, kn);
  // The bound of the present masses: the caller's (one bound for many targets), else formed here.
  std::optional<FrequencyBound> formed;
  if (bounded && !given_bound) formed.emplace(frequency_bound(m, groups, deformable));
  const FrequencyBound* bound = given_bound ? given_bound : (formed ? &*formed : nullptr);
  // mass (and inertia) times s: own / s + coupled / sqrt(s) <= omega_t^2, solved for x = 1 / sqrt(s)
  const auto bounded_factor = [&](const FrequencyBound::Row& row) {
    if (row.omega_squared() <= omega2) return 1.0;
    const double x = row.own > 0 ? (std::sqrt(row.coupled * row.coupled + 4 * row.own * omega2) - row.coupled) / (2 * row.own)
                                 : omega2 / row.coupled;
    return 1.0 / (x * x) * margin;
  };
  double largest = 0;  // omega_max^2 of the bound, from the rows the plan computes anyway (their eigenproblems)
  for (std::size_t i = 0; i < nd.size(); ++i) {
    const FrequencyBound::Row row = bounded ? bound->node_row(i) : FrequencyBound::Row{};
    largest = std::max(largest, row.omega_squared());
    if ((nd.fixity[i] & 7) == 7) continue;
    if (bounded) {
      plan.node_mass[i] *= bounded_factor(row);
      continue;
    }
    const double required = kn[i] / omega2;
    plan.node_mass[i] = rule == MassRule::raise_only ? std::max(nd.mass[i], required) : (kn[i] > 0 ? required : nd.real_mass[i]);
  }
  const auto& real_mass = *real.mass;
  const auto& real_inertia = *real.inertia;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const FrequencyBound::Row row = bounded ? bound->row(i) : FrequencyBound::Row{};
    largest = std::max(largest, row.omega_squared());
    if (b.motion[i] != model::Motion::free || m.deformable.is_deformable(i)) continue;
    const bool translates = (b.fixity[i] & 7) != 7;
    const bool turns = (b.fixity[i] & model::Fixity::all_rotations) != model::Fixity::all_rotations;
    double& mass = plan.block_mass[i];
    Vec3& inertia = plan.block_inertia[i];
    if (bounded) {
      const double factor = bounded_factor(row);
      mass *= factor;
      inertia *= factor;
    } else if (rule == MassRule::raise_only) {
      double factor = 1.0;
      if (translates) factor = std::max(factor, kt[i] / (omega2 * mass));
      if (turns) factor = std::max(factor, kr[i] / (omega2 * inertia.minCoeff()));
      mass *= factor;
      inertia *= factor;
    } else {
      mass = translates && kt[i] > 0 ? kt[i] / omega2 : real_mass[i];
      inertia = turns && kr[i] > 0 ? Vec3(real_inertia[i] * (kr[i] / omega2 / real_inertia[i].minCoeff())) : real_inertia[i];
    }
  }
  plan.omega_max = std::sqrt(largest);
  return plan;
}

/// Gives the free nodes and rigid blocks the masses of `plan` (those that differ, with their inverses) and reports
/// in `r` what was scaled, the mass added over the real masses and the range of the scaling factors.
inline void apply_mass_plan(model::Model& m, const MassPlan& plan, const RealMasses& real, std::vector<double>& node_inverse_mass,
                            BlockState& blocks, DensityScaling& r) {
  auto& b = m.bodies;
  auto& nd = m.deformable.nodes;
  const auto factor_range = [&](double factor) {
    r.max_density_scaling_factor = std::max(r.max_density_scaling_factor, factor);
    r.min_density_scaling_factor = std::min(r.min_density_scaling_factor, factor);
  };
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if ((nd.fixity[i] & 7) == 7) continue;
    if (plan.node_mass[i] != nd.mass[i]) {
      nd.mass[i] = plan.node_mass[i];
      node_inverse_mass[i] = 1.0 / nd.mass[i];
      ++r.scaled_nodes;
    }
    r.real_mass += nd.real_mass[i];
    r.added_mass += nd.mass[i] - nd.real_mass[i];
    factor_range(nd.density_scaling_factor(i));
  }
  const auto& real_mass = *real.mass;
  const auto& real_inertia = *real.inertia;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.motion[i] != model::Motion::free || m.deformable.is_deformable(i)) continue;
    if (plan.block_mass[i] != b.mass[i] || plan.block_inertia[i] != b.principal_inertia[i]) {
      b.mass[i] = plan.block_mass[i];
      b.principal_inertia[i] = plan.block_inertia[i];
      blocks.inverse_mass[i] = 1.0 / b.mass[i];
      blocks.inverse_inertia[i] = b.principal_inertia[i].cwiseInverse();
      ++r.scaled_blocks;
    }
    r.real_mass += real_mass[i];
    r.added_mass += b.mass[i] - real_mass[i];
    factor_range(b.mass[i] / real_mass[i]);
    factor_range(b.principal_inertia[i].minCoeff() / real_inertia[i].minCoeff());
  }
  r.mass_increase_percent = r.real_mass > 0 ? 100.0 * r.added_mass / r.real_mass : 0.0;
}

/// What raise_masses() did: nodes and rigid blocks raised, mass added (kg), kinetic energy added (J) at their
/// present velocities.
struct MassRaise {
  long long nodes = 0, blocks = 0;
  double added = 0, kinetic = 0;
};

/// Raises the masses that `plan` makes heavier (mass and inertia of a rigid block by one factor), at the present
/// velocities (the holding of the timestep against new contacts: TimestepHold).
inline MassRaise raise_masses(model::Model& m, const MassPlan& plan, std::vector<double>& node_inverse_mass, BlockState& blocks) {
  auto& b = m.bodies;
  auto& nd = m.deformable.nodes;
  MassRaise r;
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if (!(plan.node_mass[i] > nd.mass[i])) continue;
    const double dm = plan.node_mass[i] - nd.mass[i];
    r.added += dm;
    r.kinetic += 0.5 * dm * nd.velocity[i].squaredNorm();
    nd.mass[i] = plan.node_mass[i];
    node_inverse_mass[i] = 1.0 / nd.mass[i];
    ++r.nodes;
  }
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!(plan.block_mass[i] > b.mass[i])) continue;
    const double f = plan.block_mass[i] / b.mass[i];
    const Vec3 w = b.rotation[i].transpose() * b.angular_velocity[i];
    r.added += plan.block_mass[i] - b.mass[i];
    r.kinetic += (f - 1) * 0.5 * (b.mass[i] * b.velocity[i].squaredNorm() + w.cwiseProduct(w).dot(b.principal_inertia[i]));
    b.mass[i] = plan.block_mass[i];
    b.principal_inertia[i] = plan.block_inertia[i];
    blocks.inverse_mass[i] = 1.0 / b.mass[i];
    blocks.inverse_inertia[i] = b.principal_inertia[i].cwiseInverse();
    ++r.blocks;
  }
  return r;
}

}  // namespace blockdem
