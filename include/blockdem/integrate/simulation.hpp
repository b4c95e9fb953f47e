#pragma once
// The explicit central-difference integrator (paper Sect. 3.1, DESIGN.md §4). One Simulation type per damping
// policy and list of joint laws: every step is one fused pass over the contact points of each law (relative
// velocity -> law -> damping -> force) and one pass over the blocks (gather in a fixed order -> gravity -> damped
// velocity update -> position and orientation), each specialised at compile time, with no virtual call and no
// branch on the policy. Results do not depend on the number of OpenMP threads.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/rotation.hpp"
#include "blockdem/core/triple.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/integrate/frequency_bound.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/kinematics/deformable.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// Energy terms since the start of the simulation (J). The balance: kinetic + elastic + viscous + slip
/// - gravity_work - base_work stays equal to its value at the start.
struct EnergyReport {
  double kinetic = 0;       // of the free blocks
  double elastic = 0;       // stored in the joint springs and the damping springs (Maxwell branches)
  double gravity_work = 0;  // done by gravity on the free blocks
  double base_work = 0;     // done by the base blocks on the rest
  double viscous = 0;       // dissipated by viscous damping
  double slip = 0;          // dissipated by the joint laws (friction, softening)
  // Stored in the contacts by re-detection, not by any force: CPs that start in overlap, minus the energy of CPs
  // dropped while loaded, plus that of CPs whose tributary area changed (a change of the discrete model, as a
  // contact's polygon changes; with the joints intact it stays near 0).
  double contact_update = 0;
  double balance_error = 0; // |change of (kinetic + elastic + viscous + slip) - work - contact_update| / the largest term
};

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

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
class Simulation {
  static_assert(sizeof...(Laws) >= 1, "Simulation needs at least one joint law");

 public:
  using Properties = std::variant<typename Laws::Parameters...>;
  /// Chooses the law and its parameters for the joint between blocks with these joint tags.
  using PropertyFunction = std::function<Properties(int tag_a, int tag_b)>;

  Simulation(model::Model& model, Damping damping, PropertyFunction properties, model::ContactSettings settings = {})
      : model_(&model), damping_(damping), properties_(std::move(properties)), settings_(settings) {
    settings_.validate();
    if (!properties_) throw InvalidArgument("simulation: a contact property function is required");
    resize_block_arrays();
    mixed_ = !model.deformable.empty();
    if (mixed_) deformable_.setup(model);
    std::pair<std::pair<std::size_t, std::size_t>, double> deepest;
    const auto candidates = model::detect_contacts(model.bodies, settings_, &deepest);
    if (deepest.second < -settings_.tolerance)
      throw InvalidArgument("blocks '" + model.bodies.name[deepest.first.first] + "' and '" +
                            model.bodies.name[deepest.first.second] + "' interpenetrate by " +
                            std::to_string(-deepest.second) + " m, more than the contact tolerance " +
                            std::to_string(settings_.tolerance) + " m");
    assign_all(candidates, /*keep_history=*/false);
    pending_increment_ = false;
    set_timestep(default_timestep());
  }

  /// Continues from another simulation of the same model with another damping policy (for example after static
  /// equilibrium under local damping): block state and joint histories are kept, damping state starts at zero.
  template <damping::DampingPolicy Other>
  Simulation(Simulation<Other, Laws...>& other, Damping damping)
      : model_(other.model_), damping_(damping), properties_(other.properties_), settings_(other.settings_) {
    if (other.static_masses_)
      throw InvalidArgument("simulation: the simulation to continue from runs with static mass scaling; call "
                            "restore_real_masses() on it first");
    other.synchronize();
    resize_block_arrays();  // inverse masses from the model's present masses
    copy_groups(other, std::index_sequence_for<Laws...>{});
    // The mixed step only for what needs it: not for a rigid-only model whose real masses were put back.
    mixed_ = other.mixed_ && (!model_->deformable.empty() || other.scaled_rigid_blocks());
    if (mixed_) deformable_.take_over(other.deformable_, *model_);
    time_ = other.time_;
    // The other's timestep if one was chosen below its default (and below this policy's), else this policy's default.
    const bool chosen = other.dt_ < other.default_timestep() * (1 - 1e-12);
    set_timestep(chosen ? std::min(other.dt_, default_timestep()) : default_timestep());
    density_safety_ = other.density_safety_;
  }

  /// The margin of the timestep below the critical one, by how omega_max is found (eq. 1). Dynamic masses: the
  /// block Gershgorin bound (FrequencyBound), an upper bound for the present contacts, elements and trusses; the
  /// margin is for the stiffness that the contacts gain between two estimates (re-detection in impacts). Static
  /// masses (scale_masses_for_statics): the per-node and per-block estimate of eq. 1-3, exact for one block or node
  /// on fixed supports but not an upper bound for a chain of them (by up to a factor 2 on the timestep).
  static constexpr double bound_safety_factor = 0.8;
  static constexpr double estimate_safety_factor = 0.5;

  /// Whether omega_max comes from FrequencyBound (not under static mass scaling, whose masses follow the estimate).
  bool bounded_frequency() const { return !static_masses_; }
  double safety_factor() const { return bounded_frequency() ? bound_safety_factor : estimate_safety_factor; }

  /// The safety factor times the critical timestep; 1e-4 s while no block has a contact.
  double default_timestep() const {
    const double critical = critical_timestep();
    return std::isfinite(critical) ? safety_factor() * critical : 1e-4;
  }

  // ---- timestep (eq. 1-3, 11, 20) ----

  /// Critical timestep 2 / omega_max (eq. 1) times the damping policy's factor (eq. 11, eq. 20); infinite if no
  /// free block or node has a spring. omega_max: the upper bound of FrequencyBound; under static masses the largest
  /// of sqrt(k / m) over the nodes (eq. 2-3) and over the free blocks sqrt(k / m) for translation and
  /// sqrt(k r^2 / I_min) for rotation, k the sum of max(k_n, k_s) A of their contact points.
  double critical_timestep() const {
    const double omega = omega_max();
    if (omega == 0) return std::numeric_limits<double>::infinity();
    return 2.0 / omega * damping_.timestep_factor(omega);
  }

  /// omega_max of eq. 1 (rad/s), without the damping policy: the bound or the estimate (see critical_timestep()).
  double omega_max() const { return bounded_frequency() ? frequency_bound().omega_max() : estimated_omega_max(); }

  /// The upper bound on omega_max for the present contacts, elements, trusses and masses.
  FrequencyBound frequency_bound() const {
    const auto& b = model_->bodies;
    FrequencyBound bound(*model_);
    for_each_group([&](const auto& g) {
      using L = typename std::remove_cvref_t<decltype(g)>::LawType;
      for (std::size_t c = 0; c < g.contacts(); ++c) {
        const auto& p = g.properties[g.property[c]];
        const double kn = L::normal_stiffness(p), ks = L::shear_stiffness(p);
        const ContactFrame fr = frame(g, c);
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
    for (const auto& t : model_->deformable.trusses) {
      const auto point = [&](const model::TrussEnd& e) {
        return e.node >= 0 ? FrequencyBound::node_point(static_cast<std::size_t>(e.node))
                           : FrequencyBound::block_point(e.block, b.position[e.block] + rotate(b.rotation[e.block], e.body_point));
      };
      const Vec3 e = (model_->end_position(t.end[1]) - model_->end_position(t.end[0])).normalized();
      bound.spring({point(t.end[0])}, {point(t.end[1])}, Mat3(t.axial_stiffness() * e * e.transpose()));
    }
    if (mixed_) deformable_.add_to(*model_, bound);
    return bound;
  }

  /// Eq. 1-3's estimate of omega_max (rad/s): per node and per rigid block on its own (see critical_timestep()).
  double estimated_omega_max() const {
    const auto& b = model_->bodies;
    std::vector<double> k_translation, k_rotation, k_node;
    stiffnesses(k_translation, k_rotation, k_node);
    double omega_max = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free) continue;
      if ((b.fixity[i] & 7) != 7) omega_max = std::max(omega_max, std::sqrt(k_translation[i] / b.mass[i]));
      if ((b.fixity[i] & model::Fixity::all_rotations) != model::Fixity::all_rotations)
        omega_max = std::max(omega_max, std::sqrt(k_rotation[i] / b.principal_inertia[i].minCoeff()));
    }
    const auto& nd = model_->deformable.nodes;
    for (std::size_t i = 0; i < k_node.size(); ++i)
      if ((nd.fixity[i] & 7) != 7) omega_max = std::max(omega_max, std::sqrt(k_node[i] / nd.mass[i]));  // eq. 1-3
    return omega_max;
  }

  /// Stiffness (N/m) on each rigid block (translation; rotation k r^2 in N m) and on each node: contacts, elements
  /// (eq. 2) and trusses.
  void stiffnesses(std::vector<double>& k_translation, std::vector<double>& k_rotation, std::vector<double>& k_node) const {
    const auto& b = model_->bodies;
    k_translation.assign(b.size(), 0.0);
    k_rotation.assign(b.size(), 0.0);
    for_each_group([&](const auto& g) {
      using L = typename std::remove_cvref_t<decltype(g)>::LawType;
      for (std::size_t c = 0; c < g.contacts(); ++c) {
        const auto& p = g.properties[g.property[c]];
        const double k_spring = std::max(L::normal_stiffness(p), L::shear_stiffness(p));
        const std::size_t a = g.body_a[c], bb = g.body_b[c];
        const ContactFrame fr = frame(g, c);
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
    if (mixed_) deformable_.add_stiffness(*model_, k_node, k_translation, k_rotation);
  }

  /// Partial density scaling to a target timestep (s, the timestep to run with: the safety factor times the
  /// critical one): every free node and free rigid block whose own limit is below the target gets just the mass
  /// (rigid blocks: mass and inertia, by one factor) that brings it to the target; the others keep theirs. A block's
  /// or node's own limit: its row of FrequencyBound (its neighbours as they are, so that scaling them too only
  /// lowers it), under static masses 2 safety f / sqrt(k / m) as in critical_timestep(). Weights stay those of the
  /// real masses. Sets the timestep to the target and reports what was added. Call before stepping (the energy
  /// reference is taken at the first step). Throws InvalidArgument if the target is not positive and finite.
  DensityScaling scale_density_to(double target_dt) { return scale_density_to(target_dt, safety_factor()); }
  DensityScaling scale_density_to(double target_dt, double safety_factor) {
    return scale_masses(target_dt, safety_factor, MassRule::raise_only);
  }

  /// The mass (kg) that scale_density_to(target_dt) would add, the model left as it is; `timestep_factor(omega)`
  /// in place of the damping policy's (eq. 11, eq. 20), for the policy of a simulation still to come.
  template <class Factor>
  double density_scaling_mass(double target_dt, Factor timestep_factor) const {
    const MassPlan plan = plan_masses(target_dt, safety_factor(), MassRule::raise_only, timestep_factor);
    double added = 0;
    for (std::size_t i = 0; i < plan.block_mass.size(); ++i) added += plan.block_mass[i] - model_->bodies.mass[i];
    for (std::size_t i = 0; i < plan.node_mass.size(); ++i) added += plan.node_mass[i] - model_->deformable.nodes.mass[i];
    return added;
  }

  /// Static mass scaling (3DEC's for static solutions; statics do not depend on the masses): every free node gets
  /// exactly the mass whose own limit 2 safety f / sqrt(k / m) is the target timestep, raised or lowered, and every
  /// free rigid block the mass of its translational limit and the inertia (its principal moments by one factor, from
  /// the real ones) of its rotational limit: all degrees of freedom with a stiffness share one frequency, and the
  /// local damping (damping::Local) brings them to rest together. Those without contact stiffness (or fixed) keep
  /// their real masses. Weights stay those of the real masses. The timestep then follows eq. 1-3's estimate with
  /// its margin (estimate_safety_factor), also for rigid blocks. Sets the timestep to the target and reports what
  /// was changed (added_mass may be negative). For settling only: call restore_real_masses() before continuing with
  /// a dynamic simulation (the continuation constructor refuses a simulation with static masses). Throws
  /// InvalidArgument if the target is not positive and finite.
  DensityScaling scale_masses_for_statics(double target_dt) { return scale_masses_for_statics(target_dt, estimate_safety_factor); }
  DensityScaling scale_masses_for_statics(double target_dt, double safety_factor) {
    return scale_masses(target_dt, safety_factor, MassRule::exact);
  }

  /// Gives every block and node back its real mass and inertia (bitwise those before any scaling) and updates the
  /// inverse masses; then sets the timestep to default_timestep() for the real masses (the one the simulation would
  /// be constructed with now; a smaller one set before scaling is not remembered). Undoes scale_density_to() and
  /// scale_masses_for_statics(). The kinetic energy is that of the real masses from the next step on: call it at
  /// rest (after settling), where the energy balance does not notice. The mixed step stays on (its weight correction
  /// is then zero); a simulation continued from this one runs the rigid kernel if the model is rigid-only.
  void restore_real_masses() {
    auto& b = model_->bodies;
    auto& nd = model_->deformable.nodes;
    if (mixed_) {  // blocks are scaled only in the mixed step, which keeps their real masses
      b.mass = deformable_.rigid_real_mass;
      b.principal_inertia = deformable_.rigid_real_inertia;
      nd.mass = nd.real_mass;
      for (std::size_t i = 0; i < nd.size(); ++i) deformable_.node_inverse_mass[i] = 1.0 / nd.mass[i];
    }
    set_inverse_masses();
    static_masses_ = false;
    density_safety_ = 0;
    set_timestep(default_timestep());
  }

  /// Whether the masses are those of scale_masses_for_statics() (not yet restored).
  bool static_masses() const { return static_masses_; }

  /// Density scaling factor m_scaled / m_real of every node (the VTK field `density_scaling_factor`).
  std::vector<double> density_scaling_factors() const {
    const auto& nd = model_->deformable.nodes;
    std::vector<double> f(nd.size());
    for (std::size_t i = 0; i < nd.size(); ++i) f[i] = nd.density_scaling_factor(i);
    return f;
  }

  /// Whether the model has deformable blocks, trusses or scaled rigid blocks (the mixed step runs).
  bool mixed() const { return mixed_; }
  const kinematics::DeformableState<Damping, Laws...>& deformable_state() const { return deformable_; }

  /// Sets the timestep (s). Throws InvalidArgument if it exceeds the critical timestep, unless unchecked.
  void set_timestep(double dt, TimestepCheck check = TimestepCheck::checked) {
    const double critical = critical_timestep();
    if (!(dt > 0) || !std::isfinite(dt))
      throw InvalidArgument("timestep must be > 0 s and finite, got " + std::to_string(dt));
    if (check == TimestepCheck::checked && dt > critical)
      throw InvalidArgument("timestep " + std::to_string(dt) + " s exceeds the critical timestep " +
                            std::to_string(critical) + " s (eq. 1 with the damping factor of eq. 11/20)");
    dt_ = dt;
    timestep_margin_ = check == TimestepCheck::checked && std::isfinite(critical) ? dt / critical : 0.0;
    if constexpr (requires(Damping& d) { d.prepare(dt); }) damping_.prepare(dt_);
  }

  /// What holding the timestep against new contacts has done so far (see TimestepHold).
  const TimestepHold& timestep_hold() const { return hold_; }

  double timestep() const { return dt_; }
  double time() const { return time_; }
  long long steps() const { return steps_; }
  const model::Model& model() const { return *model_; }
  model::Model& model() { return *model_; }
  const Damping& damping() const { return damping_; }
  const model::ContactSettings& contact_settings() const { return settings_; }
  int detections() const { return detections_; }

  std::size_t contact_points() const {
    std::size_t n = 0;
    for_each_group([&](const auto& g) { n += g.size(); });
    if (mixed_) n += deformable_.contact_points();
    return n;
  }

  template <contact::ContactLaw L>
  const auto& group() const { return std::get<Group<L>>(groups_); }
  template <contact::ContactLaw L>
  auto& group() { return std::get<Group<L>>(groups_); }

  /// One contact point as output sees it (world frame).
  struct ContactView {
    Vec3 position;        // m, midway between the material points on A and B
    Vec3 normal;          // from A to B
    Vec3 force;           // N, on B
    double area = 0;      // m^2
    double gap = 0;       // m, positive open
    double normal_stress = 0;  // Pa, compression positive (joint law plus damping)
    double shear_stress = 0;   // Pa, magnitude
    double damage = 0;    // 0 intact .. 1 failed (laws without damage: 1 once failed); 0 if never bonded
    bool never_bonded = false;  // appeared during the run (contact::never_bonded): a new contact, not a broken joint
    std::size_t block_a = 0, block_b = 0;
  };

  /// Calls f(block_a, block_b, const History&) for every contact point with its joint law's history: the block
  /// contacts, then the node contacts of deformable blocks (block_a: the node's block).
  template <class F>
  void visit_contact_histories(F&& f) const {
    for_each_group([&](const auto& g) {
      for (std::size_t c = 0; c < g.contacts(); ++c)
        for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k)
          f(std::size_t{g.body_a[c]}, std::size_t{g.body_b[c]}, g.history[k]);
    });
    if (!mixed_) return;
    deformable_.for_each_group([&](const auto& g) {
      for (std::size_t k = 0; k < g.size(); ++k) f(std::size_t{g.node_block[k]}, std::size_t{g.face_block[k]}, g.history[k]);
    });
  }

  /// The damage of a CP for output: the law's, or 1 once failed; 0 for a CP that appeared during the run and
  /// was never bonded (contact::never_bonded), which ContactView::never_bonded marks instead.
  template <class H>
  static void set_damage(ContactView& v, const H& h) {
    if constexpr (requires { h.failed; }) v.never_bonded = h.failed == contact::never_bonded;
    if (v.never_bonded) return;
    if constexpr (requires { h.damage; }) v.damage = h.damage;
    else if constexpr (requires { h.failed; }) v.damage = h.failed ? 1.0 : 0.0;
  }

  /// Calls f(const ContactView&) for every contact point, group by group.
  template <class F>
  void visit_contacts(F&& f) const {
    for_each_group([&](const auto& g) {
      for (std::size_t c = 0; c < g.contacts(); ++c) {
        const ContactFrame fr = frame(g, c);
        for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) {
          ContactView v;
          v.block_a = g.body_a[c];
          v.block_b = g.body_b[c];
          v.position = fr.point(g.s1[k], g.s2[k]);
          v.normal = fr.n;
          v.area = g.area[k];
          const auto t = g.traction_at(c, k);
          v.force = v.area * (t[0] * fr.n + t[1] * fr.t1 + t[2] * fr.t2);
          const auto& h = g.history[k];
          v.gap = h.gap;
          v.normal_stress = t[0];
          v.shear_stress = std::hypot(t[1], t[2]);
          set_damage(v, h);
          f(v);
        }
      }
    });
    if (!mixed_) return;
    const auto& x = model_->deformable.nodes.position;
    deformable_.for_each_group([&](const auto& g) {
      for (std::size_t k = 0; k < g.size(); ++k) {
        ContactView v;
        v.block_a = g.node_block[k];
        v.block_b = g.face_block[k];
        v.position = x[g.node[k]];
        v.force = g.force[k];
        if constexpr (std::remove_cvref_t<decltype(g)>::FaceKinematics::deformable) {
          const auto& t = g.triangle[k];
          v.normal = -(x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).normalized();
        } else {
          v.normal = rotate(model_->bodies.rotation[g.face_block[k]], g.normal_local[k]);
        }
        v.area = g.area[k];
        const auto& h = g.history[k];
        v.gap = h.gap;
        v.normal_stress = g.traction[k][0];
        v.shear_stress = std::hypot(g.traction[k][1], g.traction[k][2]);
        set_damage(v, h);
        f(v);
      }
    });
  }

  // ---- the step ----

  void step() {
    if (mixed_) mixed_step();
    else step_impl<false>();
  }

  /// Reverses the motion exactly (up to rounding): after n more steps the blocks are back where they were n steps
  /// ago, with velocities negated. For time-reversibility checks of the scheme.
  void reverse() {
    synchronize();
    for_each_group([&](auto& g) { contact_pass(g, 0.0); });
    auto& b = model_->bodies;
    // v(n+1/2) = v(n-1/2) + dt F(x_n) / m, then negate: the leapfrog run backwards from x_n.
    if (mixed_) {
      mixed_forces(0.0);
      block_pass<true>(0.0, /*move=*/false);
      deformable_.node_pass(*model_, damping_, dt_, 0.0, false, settings_.redetection());
      for (auto& v : model_->deformable.nodes.velocity) v = -v;
    } else {
      block_pass(0.0, /*move=*/false);
    }
    for (std::size_t i = 0; i < b.size(); ++i) {
      b.velocity[i] = -b.velocity[i];
      b.angular_velocity[i] = -b.angular_velocity[i];
    }
    pending_increment_ = false;
  }

  /// Brings the joint histories up to the current positions (the increment of the last move is otherwise applied
  /// at the start of the next step).
  void synchronize() {
    if (!pending_increment_) return;
    for_each_group([&](auto& g) { contact_pass(g, dt_); });
    if (mixed_) mixed_forces(dt_);
    pending_increment_ = false;
  }

  // ---- energy ----

  EnergyReport energy() const {
    EnergyReport e = energy_terms();
    const double change = (e.kinetic + e.elastic + e.viscous + e.slip) - (energy0_.kinetic + energy0_.elastic) -
                          (e.gravity_work + e.base_work) - (e.contact_update - energy0_.contact_update);
    const double scale = std::max({std::abs(e.gravity_work) + std::abs(e.base_work), e.kinetic + e.elastic + e.viscous + e.slip,
                                   energy0_.kinetic + energy0_.elastic, 1e-300});
    e.balance_error = std::abs(change) / scale;
    return e;
  }

  /// Sum of |unbalanced force| over sum of |applied force| (the real weights) of the free blocks and nodes.
  double unbalanced_force_ratio() const {
    const auto& b = model_->bodies;
    double unbalanced = 0, applied = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free || model_->deformable.is_deformable(i)) continue;
      unbalanced += b.force[i].norm();
      applied += (mixed_ ? deformable_.rigid_real_mass[i] : b.mass[i]) * model_->gravity.norm();  // not the scaled one
    }
    const auto& nd = model_->deformable.nodes;
    for (std::size_t i = 0; i < nd.size(); ++i) {
      if ((nd.fixity[i] & 7) == 7) continue;
      Vec3 f = nd.force[i];
      for (int c = 0; c < 3; ++c)
        if (nd.fixity[i] & (1u << c)) f[c] = 0;
      unbalanced += f.norm();
      applied += nd.real_mass[i] * model_->gravity.norm();
    }
    return applied > 0 ? unbalanced / applied : 0.0;
  }

  /// Steps until the unbalanced-force ratio is at most `tolerance` (checked every 10 steps) or `max_steps` are
  /// done. Returns true if the tolerance was met. Meant for a simulation with damping::Local.
  bool solve_to_equilibrium(double tolerance = 1e-5, long long max_steps = 1000000) {
    for (long long n = 0; n < max_steps; ++n) {
      step();
      if (n % 10 == 9 && unbalanced_force_ratio() <= tolerance) return true;
    }
    return unbalanced_force_ratio() <= tolerance;
  }

  /// Detects the contacts again now: existing CPs keep their history (matched by block pair and location), new
  /// contacts appear, CPs of blocks that moved apart are dropped.
  void redetect() {
    synchronize();
    if (mixed_) redetect_and_update<true>();
    else redetect_and_update<false>();
    pending_increment_ = false;
  }

  // ---- checkpoints ----

  /// Writes the complete state (the model's too) for io::save_checkpoint. A simulation constructed the same way
  /// (same model description, policy, property function, settings) that calls load_state() continues bitwise as
  /// this one does; the load may be followed by nothing else (no scale_density_to(), no set_timestep()): masses,
  /// timestep and the damping policy's constants are in the state. load_state throws InvalidArgument (naming the
  /// file and the field) on a checkpoint of another layout or model size; the simulation is then unusable.
  void save_state(io::CheckpointWriter& out) const { visit_state(*this, out); }
  void load_state(io::CheckpointReader& in) {
    visit_state(*this, in);
    update_redetection_distances();
  }

 private:
  /// The one list of the saved fields, for both directions. Not saved: model_ (the caller's model, whose state is
  /// saved in its place); properties_ and settings_ (the description: the constructor's arguments);
  /// chosen_properties_ (a memo of properties_, filled again identically); radius_ (from the shapes);
  /// redetection_distance_ (from the poses at the last detection);
  /// taken_over_ and old_contacts_ (scratch of a detection). The damping policy is saved whole: its parameters
  /// and the constants of prepare(dt).
  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar) {
    ar.check("the simulation type (damping policy, joint laws)", io::type_name<Simulation>());
    ar("model", *s.model_);
    static_assert(io::plain_checkpoint_value<Damping>, "a checkpoint saves the damping policy as its bytes");
    ar("damping policy", s.damping_);
    ar("mixed step", s.mixed_);
    ar("deformable state", s.deformable_);
    std::apply([&](auto&... g) { (ar("contact group", g), ...); }, s.groups_);
    ar("timestep", s.dt_);
    ar("time", s.time_);
    ar("steps", s.steps_);
    ar("steps since the last detection check", s.steps_since_check_);
    ar("detections", s.detections_);
    ar("pending increment", s.pending_increment_);
    ar("moved since the last detection", s.moved_since_detection_);
    ar("static masses", s.static_masses_);
    ar.same_size("block kinetic energies", s.kinetic_);
    ar.same_size("block gravity work", s.gravity_work_);
    ar.same_size("block base work", s.base_work_);
    ar.same_size("block viscous work", s.viscous_);
    ar.same_size("block inverse masses", s.inverse_mass_);
    ar.same_size("block inverse inertias", s.inverse_inertia_);
    ar.same_size("block positions at the last detection", s.detected_position_);
    ar.same_size("block orientations at the last detection", s.detected_orientation_);
    ar("base displacement", s.base_displacement_);
    ar("base displacement at the last detection", s.detected_base_displacement_);
    ar("energy reference", s.energy0_);
    ar("energy reference pending", s.energy_reference_pending_);
    ar("retired slip", s.retired_slip_);
    ar("retired viscous work", s.retired_viscous_);
    ar("energy added by contact updates", s.contact_update_);
    ar("density scaling safety factor", s.density_safety_);
    ar("timestep margin", s.timestep_margin_);
    ar("timestep hold", s.hold_);
  }

  template <damping::DampingPolicy, contact::ContactLaw...>
  friend class Simulation;

  template <contact::ContactLaw L>
  struct Group : ContactGroup<L, Damping> {
    using LawType = L;
  };
  using Groups = std::tuple<Group<Laws>...>;

  template <class F>
  void for_each_group(F&& f) {
    std::apply([&](auto&... g) { (f(g), ...); }, groups_);
  }
  template <class F>
  void for_each_group(F&& f) const {
    std::apply([&](const auto&... g) { (f(g), ...); }, groups_);
  }

  void resize_block_arrays() {
    const std::size_t n = model_->bodies.size();
    kinetic_.assign(n, 0.0);
    gravity_work_.assign(n, 0.0);
    base_work_.assign(n, 0.0);
    viscous_.assign(n, 0.0);
    detected_position_ = model_->bodies.position;
    detected_orientation_ = model_->bodies.orientation;
    set_inverse_masses();
    radius_.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (const auto& v : model_->bodies.shape[i].vertices) radius_[i] = std::max(radius_[i], v.norm());
    update_redetection_distances();
    for (std::size_t i = 0; i < n; ++i) {
      const auto& b = model_->bodies;
      kinetic_[i] = b.motion[i] == model::Motion::free
                        ? 0.5 * b.mass[i] * b.velocity[i].squaredNorm() +
                              0.5 * (b.rotation[i].transpose() * b.angular_velocity[i])
                                        .cwiseProduct(b.rotation[i].transpose() * b.angular_velocity[i])
                                        .dot(b.principal_inertia[i])
                        : 0.0;
    }
  }

  void set_inverse_masses() {
    const auto& b = model_->bodies;
    inverse_mass_.assign(b.size(), 0.0);
    inverse_inertia_.assign(b.size(), Vec3::Zero());
    for (std::size_t i = 0; i < b.size(); ++i) {
      inverse_mass_[i] = 1.0 / b.mass[i];
      inverse_inertia_[i] = b.principal_inertia[i].cwiseInverse();
    }
  }

  /// Whether a rigid block's mass or inertia differs from its real one (only the mixed step keeps the real ones).
  bool scaled_rigid_blocks() const {
    if (!mixed_) return false;
    const auto& b = model_->bodies;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.mass[i] != deformable_.rigid_real_mass[i] || b.principal_inertia[i] != deformable_.rigid_real_inertia[i]) return true;
    return false;
  }

  /// How scale_masses() sets masses: raise only those whose own limit is below the target (partial density
  /// scaling), or set every one to the mass of the target (static mass scaling).
  enum class MassRule { raise_only, exact };

  /// The masses that scale_masses() sets (free nodes; rigid blocks: mass and principal inertia).
  struct MassPlan {
    std::vector<double> node_mass, block_mass;
    std::vector<Vec3> block_inertia;
  };

  /// The rigid blocks' real masses and inertias (only the mixed step keeps them apart from the present ones).
  const std::vector<double>& real_block_masses() const { return mixed_ ? deformable_.rigid_real_mass : model_->bodies.mass; }
  const std::vector<Vec3>& real_block_inertias() const {
    return mixed_ ? deformable_.rigid_real_inertia : model_->bodies.principal_inertia;
  }

  template <class Factor>
  MassPlan plan_masses(double target_dt, double safety_factor, MassRule rule, Factor timestep_factor) const {
    const auto& b = model_->bodies;
    const auto& nd = model_->deformable.nodes;
    // omega_t with safety 2 f(omega_t) / omega_t = target (f: eq. 11 or eq. 20), by bisection in log omega.
    auto limit = [&](double omega) { return safety_factor * 2.0 / omega * timestep_factor(omega); };
    double lo = 1e-12, hi = 1e15;
    for (int it = 0; it < 200; ++it) {
      const double mid = std::sqrt(lo * hi);
      (limit(mid) > target_dt ? lo : hi) = mid;
    }
    const double margin = 1.0 + 1e-9;
    const double omega2 = lo * lo / margin;
    MassPlan plan{nd.mass, b.mass, b.principal_inertia};
    const bool bounded = rule == MassRule::raise_only && bounded_frequency();
    std::vector<double> kt, kr, kn;
    if (!bounded) stiffnesses(kt, kr, kn);
    const std::optional<FrequencyBound> bound = bounded ? std::optional<FrequencyBound>(frequency_bound()) : std::nullopt;
    // mass (and inertia) times s: own / s + coupled / sqrt(s) <= omega_t^2, solved for x = 1 / sqrt(s)
    const auto bounded_factor = [&](const FrequencyBound::Row& row) {
      if (row.omega_squared() <= omega2) return 1.0;
      const double x = row.own > 0 ? (std::sqrt(row.coupled * row.coupled + 4 * row.own * omega2) - row.coupled) / (2 * row.own)
                                   : omega2 / row.coupled;
      return 1.0 / (x * x) * margin;
    };
    for (std::size_t i = 0; i < nd.size(); ++i) {
      if ((nd.fixity[i] & 7) == 7) continue;
      if (bounded) {
        plan.node_mass[i] *= bounded_factor(bound->node_row(i));
        continue;
      }
      const double required = kn[i] / omega2;
      plan.node_mass[i] = rule == MassRule::raise_only ? std::max(nd.mass[i], required) : (kn[i] > 0 ? required : nd.real_mass[i]);
    }
    const auto& real_mass = real_block_masses();
    const auto& real_inertia = real_block_inertias();
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free || model_->deformable.is_deformable(i)) continue;
      const bool translates = (b.fixity[i] & 7) != 7;
      const bool turns = (b.fixity[i] & model::Fixity::all_rotations) != model::Fixity::all_rotations;
      double& mass = plan.block_mass[i];
      Vec3& inertia = plan.block_inertia[i];
      if (bounded) {
        const double factor = bounded_factor(bound->row(i));
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
    return plan;
  }

  /// The mass scaling of scale_density_to() and scale_masses_for_statics(), by `rule`.
  DensityScaling scale_masses(double target_dt, double safety_factor, MassRule rule) {
    const std::string what = rule == MassRule::raise_only ? "density scaling" : "static mass scaling";
    if (!(target_dt > 0) || !std::isfinite(target_dt))
      throw InvalidArgument(what + ": the target timestep must be > 0 s and finite, got " + std::to_string(target_dt));
    if (!(safety_factor > 0 && safety_factor <= 1))
      throw InvalidArgument(what + ": the safety factor must be in (0, 1], got " + std::to_string(safety_factor));
    auto& b = model_->bodies;
    auto& nd = model_->deformable.nodes;
    DensityScaling r;
    r.target_dt = target_dt;
    r.dt_critical_unscaled = critical_timestep();
    // Static masses: the one frequency without the policy's factor (Local's 1 / sqrt(1 + c) lies inside the
    // estimate's margin: omega dt = 2 safety = 1 < 2 / sqrt(1.8) for a block on its own).
    const MassPlan plan = plan_masses(target_dt, safety_factor, rule, [&](double omega) {
      return rule == MassRule::exact ? 1.0 : damping_.timestep_factor(omega);
    });
    if (!mixed_) {  // the weight correction of scaled rigid blocks runs in the mixed path, which keeps the real masses
      mixed_ = true;
      deformable_.setup(*model_);
    }
    const auto factor_range = [&](double factor) {
      r.max_density_scaling_factor = std::max(r.max_density_scaling_factor, factor);
      r.min_density_scaling_factor = std::min(r.min_density_scaling_factor, factor);
    };
    for (std::size_t i = 0; i < nd.size(); ++i) {
      if ((nd.fixity[i] & 7) == 7) continue;
      if (plan.node_mass[i] != nd.mass[i]) {
        nd.mass[i] = plan.node_mass[i];
        deformable_.node_inverse_mass[i] = 1.0 / nd.mass[i];
        ++r.scaled_nodes;
      }
      r.real_mass += nd.real_mass[i];
      r.added_mass += nd.mass[i] - nd.real_mass[i];
      factor_range(nd.density_scaling_factor(i));
    }
    const auto& real_mass = real_block_masses();
    const auto& real_inertia = real_block_inertias();
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free || model_->deformable.is_deformable(i)) continue;
      if (plan.block_mass[i] != b.mass[i] || plan.block_inertia[i] != b.principal_inertia[i]) {
        b.mass[i] = plan.block_mass[i];
        b.principal_inertia[i] = plan.block_inertia[i];
        inverse_mass_[i] = 1.0 / b.mass[i];
        inverse_inertia_[i] = b.principal_inertia[i].cwiseInverse();
        ++r.scaled_blocks;
      }
      r.real_mass += real_mass[i];
      r.added_mass += b.mass[i] - real_mass[i];
      factor_range(b.mass[i] / real_mass[i]);
      factor_range(b.principal_inertia[i].minCoeff() / real_inertia[i].minCoeff());
    }
    r.mass_increase_percent = r.real_mass > 0 ? 100.0 * r.added_mass / r.real_mass : 0.0;
    static_masses_ = rule == MassRule::exact;
    density_safety_ = rule == MassRule::raise_only ? safety_factor : 0.0;
    r.dt_critical = critical_timestep();
    set_timestep(target_dt);
    r.dt = dt_;
    return r;
  }

  template <contact::ContactLaw L>
  static constexpr std::size_t law_index() {
    constexpr bool same[] = {std::is_same_v<L, Laws>...};
    for (std::size_t i = 0; i < sizeof...(Laws); ++i)
      if (same[i]) return i;
    return sizeof...(Laws);
  }

  /// The world frame of contact c: origin, n (from A to B), t1, t2, all turning with block A.
  struct ContactFrame {
    Vec3 origin, n, t1, t2;
    Vec3 point(double u, double v) const { return origin + u * t1 + v * t2; }
  };
  template <class G>
  ContactFrame frame(const G& g, std::size_t c) const {
    const auto& b = model_->bodies;
    const Mat3& ra = b.rotation[g.body_a[c]];
    ContactFrame fr;
    fr.origin = b.position[g.body_a[c]] + rotate(ra, g.origin_a[c]);
    fr.n = rotate(ra, g.normal_a[c]);
    fr.t1 = rotate(ra, g.tangent_a[c]);
    fr.t2 = fr.n.cross(fr.t1);
    return fr;
  }

  /// Distributes detected CPs over the groups, one contact per block pair (detection emits the CPs of a pair
  /// together, on one common plane); with keep_history, a CP within the matching distance of an old CP of the
  /// same block pair takes over its history and damping state.
  void assign_contacts(const std::vector<model::ContactCandidate>& candidates, bool keep_history) {
    const auto& b = model_->bodies;
    Groups old = std::move(groups_);
    groups_ = Groups{};
    // Property sets are kept (property indices stay valid); new ones are appended.
    std::apply([&](auto&... g) { ((g.properties = std::get<std::remove_cvref_t<decltype(g)>>(old).properties), ...); }, groups_);
    const double match = std::max(settings_.tolerance, 0.25 * std::sqrt(settings_.max_contact_point_area));
    // Old contacts by block pair, and which of their CPs have been taken over. Energy dissipated at CPs that will
    // not be taken over is kept in the totals.
    std::apply([&](auto&... g) {
      ((taken_over_[law_index<typename std::remove_cvref_t<decltype(g)>::LawType>()].assign(g.size(), 0)), ...);
      ((old_contacts_[law_index<typename std::remove_cvref_t<decltype(g)>::LawType>()] = contacts_by_pair(g)), ...);
    }, old);
    double carried_slip = 0, carried_viscous = 0, old_slip = 0, old_viscous = 0;
    std::apply([&](const auto&... g) {
      ((old_slip += std::accumulate(g.slip_dissipation.begin(), g.slip_dissipation.end(), 0.0),
        old_viscous += std::accumulate(g.viscous_dissipation.begin(), g.viscous_dissipation.end(), 0.0) +
                       field_viscous_work(g)), ...);
    }, old);
    std::map<std::pair<int, int>, Properties> chosen;
    // With contact fields (Maxwell), the contacts in the field form first and those whose CPs keep their own branch
    // states after them, so that the contact pass's tiles of four are of one form (at most one mixed tile a group).
    constexpr int passes = (Group<Laws>::has_field || ...) ? 2 : 1;
    for (int pass = 0; pass < passes; ++pass) {
      for (std::size_t begin = 0, end = 0; begin < candidates.size(); begin = end) {
        const auto& c = candidates[begin];
        end = begin + 1;
        while (end < candidates.size() && candidates[end].a == c.a && candidates[end].b == c.b) ++end;
        const int ta = b.joint_tag[c.a], tb = b.joint_tag[c.b];
        auto it = chosen.find({ta, tb});
        if (it == chosen.end()) it = chosen.emplace(std::make_pair(ta, tb), properties_(ta, tb)).first;
        std::visit([&](const auto& params) {
          add_contact(params, candidates.data() + begin, candidates.data() + end, old, keep_history, match, carried_slip,
                      carried_viscous, passes == 2 ? pass : -1);
        }, it->second);
      }
    }
    retired_slip_ += old_slip - carried_slip;
    retired_viscous_ += old_viscous - carried_viscous;
    for_each_group([&](auto& g) { g.complete(b.size()); });
    detected_position_ = b.position;
    detected_orientation_ = b.orientation;
    detected_base_displacement_ = base_displacement_;
    update_redetection_distances();
    moved_since_detection_ = false;
    ++detections_;
  }

  /// Per block, how far it may move before the contacts are detected again (model::redetection_distances), from
  /// the poses at the last detection, so that a loaded checkpoint gets the same distances.
  void update_redetection_distances() {
    const auto& d = model_->deformable;
    redetection_distance_ = model::redetection_distances(model_->bodies, detected_position_, detected_orientation_, settings_,
                                                         [&](std::size_t i) { return d.is_deformable(i); });
  }

  static std::uint64_t pair_key(std::size_t a, std::size_t b) { return (std::uint64_t{a} << 32) | std::uint64_t{b}; }

  /// The viscous work of a group's fields (J; 0 without fields).
  template <class G>
  static double field_viscous_work(const G& g) {
    double w = 0.0;
    if constexpr (G::has_field)
      for (std::size_t c = 0; c < g.contacts(); ++c) w += g.field_work(c);
    return w;
  }

  template <class G>
  static std::unordered_map<std::uint64_t, std::uint32_t> contacts_by_pair(const G& g) {
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    index.reserve(g.contacts());
    for (std::size_t c = 0; c < g.contacts(); ++c) index.emplace(pair_key(g.body_a[c], g.body_b[c]), static_cast<std::uint32_t>(c));
    return index;
  }

  /// Adds the contact of the CPs [first, last) (one block pair) to the group of the law of `params`.
  template <class Params>
  void add_contact(const Params& params, const model::ContactCandidate* first, const model::ContactCandidate* last,
                   Groups& old, bool keep_history, double match, double& carried_slip, double& carried_viscous,
                   int form_pass) {
    using L = std::tuple_element_t<index_of_parameters<Params>(), std::tuple<Laws...>>;
    auto& g = std::get<Group<L>>(groups_);
    const auto& b = model_->bodies;
    const std::size_t a = first->a, bb = first->b;
    const Group<L>* o = nullptr;
    std::size_t oc = 0;
    if (keep_history) {
      const auto& index = old_contacts_[law_index<L>()];
      if (const auto it = index.find(pair_key(a, bb)); it != index.end()) {
        o = &std::get<Group<L>>(old);
        oc = it->second;
      }
    }
    // form_pass 0: only contacts that will be in the field form; 1: only the others; -1: every contact.
    if (form_pass >= 0) {
      bool field_form = false;
      if constexpr (Group<L>::has_field) field_form = o ? o->field_form[oc] != 0 : damping_.contact_field;
      if (field_form != (form_pass == 0)) return;
    }
    // Property index: reuse an identical parameter set.
    std::size_t p = 0;
    while (p < g.properties.size() && !(g.properties[p] == params)) ++p;
    if (p == g.properties.size()) {
      if (p >= 65535) throw InvalidArgument("simulation: more than 65535 different contact property sets");
      g.properties.push_back(params);
    }
    // The frame of the CPs' areas: the origin at their centroid, t1 along a principal axis (AreaMoments). The
    // plane coordinates stay small, and a Maxwell field's stiffness is diagonal (damping::Maxwell::contact_stiffness).
    Vec3 origin = Vec3::Zero();
    double total_area = 0;
    for (auto c = first; c != last; ++c) {
      origin += c->area * c->position;
      total_area += c->area;
    }
    origin /= total_area;
    const Vec3 n = first->normal;
    Vec3 t1 = first->tangent;
    {
      const Vec3 t2 = n.cross(t1);
      AreaMoments moments;
      for (auto c = first; c != last; ++c) {
        const Vec3 d = c->position - origin;
        moments.add(d.dot(t1), d.dot(t2), c->area);
      }
      const double turn = moments.principal_turn();
      t1 = (std::cos(turn) * t1 + std::sin(turn) * t2).normalized();
    }
    const Vec3 t2 = n.cross(t1);
    const ContactFrame old_frame = o ? frame(*o, oc) : ContactFrame{};
    // A branch field (Maxwell) continues on the new contact, moved to its origin and frame; a contact whose CPs
    // had their own branch states passes them on CP by CP (below).
    bool in_field_form = false;
    typename Group<L>::Field field{};
    double field_viscous = 0;
    if constexpr (Group<L>::has_field) {
      in_field_form = o ? o->field_form[oc] != 0 : damping_.contact_field;
      if (o) {
        field_viscous = o->field_work(oc);
        carried_viscous += field_viscous;
      }
      if (o && in_field_form) {
        // The old contact's field in elongation form, moved; begin_contact takes it so (complete() turns it back).
        const Vec3 shift = origin - old_frame.origin;
        const auto elongations = o->field_elongations(oc);
        for (std::size_t i = 0; i < field.size(); ++i) {
          const auto& h = elongations[i];
          const Vec3 e0 = h[0] * old_frame.n + h[1] * old_frame.t1 + h[2] * old_frame.t2;
          const Vec3 r = h[3] * old_frame.n + h[4] * old_frame.t1 + h[5] * old_frame.t2;
          const Vec3 e = e0 + r.cross(shift);  // the elongation of the same rigid relative motion at the new origin
          field[i] = {e.dot(n), e.dot(t1), e.dot(t2), r.dot(n), r.dot(t1), r.dot(t2)};
        }
      }
    }
    const Mat3& ra = b.rotation[a];
    g.begin_contact(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(bb), static_cast<std::uint16_t>(p),
                    ra.transpose() * (origin - b.position[a]), ra.transpose() * n, ra.transpose() * t1, in_field_form, field,
                    field_viscous);
    for (auto c = first; c != last; ++c) {
      const Vec3 d = c->position - origin;
      typename L::History h{};
      h.gap = c->gap;
      typename Group<L>::SpringState spring{};
      double slip = 0, viscous = 0;
      bool matched = false;
      if (o) {
        auto& taken = taken_over_[law_index<L>()];
        // The nearest old CP not yet taken, within the matching distance. The old CP sits on A where it was
        // detected; the new one at a vertex of the current overlap, so near it within the contact plane (along the
        // normal they differ by the overlap).
        const std::uint32_t none = o->first_point[oc + 1];
        std::uint32_t k = none, closest = none;
        double nearest = match, closest_distance = std::numeric_limits<double>::infinity();
        for (std::uint32_t j = o->first_point[oc]; j < none; ++j) {
          Vec3 e = old_frame.point(o->s1[j], o->s2[j]) - c->position;
          e -= e.dot(n) * n;
          if (e.norm() < closest_distance) {
            closest_distance = e.norm();
            closest = j;
          }
          if (taken[j]) continue;
          if (e.norm() <= nearest) {
            nearest = e.norm();
            k = j;
          }
        }
        if (k != none) {
          taken[k] = 1;
          matched = true;
          h = o->history[k];
          if (!in_field_form) {
            // The shear springs' states follow the new tangent directions, like the law's shear stresses below.
            spring = o->spring_state[k];
            if constexpr (!std::is_same_v<typename Group<L>::SpringState::value_type, damping::NoState>)
              turn_shear(spring[1], spring[2], old_frame, t1, t2);
          }
          slip = o->slip_dissipation[k];
          viscous = o->viscous_dissipation[k];
          carried_slip += slip;
          carried_viscous += viscous;
          // Shear components follow the new tangent directions.
          if constexpr (requires { h.shear; }) turn_shear(h.shear[0], h.shear[1], old_frame, t1, t2);
        } else if (closest != none) {
          // A CP that the contact's new polygon adds (a corner that appeared as the faces turned, a CP split off):
          // the joint is the same, so it takes the state of the joint where it is, that of the old contact's
          // closest CP (bond, damage, stresses; its own gap; no damping state), not a new contact's.
          matched = true;
          h = o->history[closest];
          h.gap = c->gap;
          if constexpr (requires { h.shear; }) turn_shear(h.shear[0], h.shear[1], old_frame, t1, t2);
        }
      }
      // A CP that appears during the run where there was no contact (an impact after separation, a new pair after
      // sliding) was never part of a bonded joint: it starts from the law's failed state (no tension, residual
      // cohesion), so that a joint that broke and separated does not heal when it closes again.
      if (keep_history && !matched) {
        if constexpr (requires { h.failed; }) h.failed = contact::never_bonded;
        if constexpr (requires { h.damage; }) h.damage = 1.0;
      }
      g.add_point(d.dot(t1), d.dot(t2), c->area, h, spring, slip, viscous);
    }
  }

  /// A shear pair (s1, s2) along the old frame's t1, t2 re-expressed along the new t1, t2 (the same plane):
  /// component by component for a state that holds one value per Maxwell branch.
  template <class S>
  static void turn_shear(S& s1, S& s2, const ContactFrame& old_frame, const Vec3& t1, const Vec3& t2) {
    if constexpr (std::is_arithmetic_v<S>) {
      const Vec3 shear = s1 * old_frame.t1 + s2 * old_frame.t2;
      s1 = shear.dot(t1);
      s2 = shear.dot(t2);
    } else {
      for (std::size_t i = 0; i < s1.size(); ++i) turn_shear(s1[i], s2[i], old_frame, t1, t2);
    }
  }

  template <class Params>
  static constexpr std::size_t index_of_parameters() {
    constexpr bool same[] = {std::is_same_v<Params, typename Laws::Parameters>...};
    for (std::size_t i = 0; i < sizeof...(Laws); ++i)
      if (same[i]) return i;
    return 0;
  }

  template <damping::DampingPolicy Other, std::size_t... I>
  void copy_groups(Simulation<Other, Laws...>& other, std::index_sequence<I...>) {
    (copy_group(std::get<I>(other.groups_), std::get<I>(groups_)), ...);
  }
  template <class From, class To>
  void copy_group(const From& from, To& to) {
    to.properties = from.properties;
    to.body_a = from.body_a;
    to.body_b = from.body_b;
    to.property = from.property;
    to.origin_a = from.origin_a;
    to.normal_a = from.normal_a;
    to.tangent_a = from.tangent_a;
    to.first_point = from.first_point;
    to.force = from.force;
    to.moment = from.moment;
    to.s1 = from.s1;
    to.s2 = from.s2;
    to.area = from.area;
    to.history = from.history;
    to.spring_state.assign(from.size(), typename To::SpringState{});
    if constexpr (To::has_field) {
      to.field.assign((from.contacts() + lane_count - 1) / lane_count, typename To::FieldRecord{});
      to.field_form.assign(to.field.size() * lane_count, 0);
      std::fill_n(to.field_form.begin(), from.contacts(), damping_.contact_field ? 1 : 0);
    }
    to.slip_dissipation.assign(from.size(), 0.0);
    to.viscous_dissipation.assign(from.size(), 0.0);
    to.complete(model_->bodies.size());
  }

  /// Adds the force (an, a1, a2) (N; normal, t1, t2) of a CP at plane coordinates (x1, x2) to its contact's
  /// resultants in the contact frame: the force and the moment S x f about the origin, S = x1 t1 + x2 t2
  /// (n x t1 = t2, t1 x t2 = n, t2 x n = t1).
  [[gnu::always_inline]] static void add_cp_force(double x1, double x2, double an, double a1, double a2, double& fn,
                                                  double& f1, double& f2, double& mn, double& m1, double& m2) {
    fn += an;
    f1 += a1;
    f2 += a2;
    mn += x1 * a2 - x2 * a1;
    m1 += x2 * an;
    m2 -= x1 * an;
  }

  /// Adds resultants in the contact frame (force along n, t1, t2, moment about the origin along n, t1, t2) to lane
  /// `lane` of the contact pass's resultants.
  [[gnu::always_inline]] static void add_to_lane(Lanes (&resultant)[6], std::size_t lane, const std::array<double, 6>& r) {
    for (std::size_t j = 0; j < 6; ++j) resultant[j].set(lane, resultant[j][lane] + r[j]);
  }

  /// A contact in the field form some of whose CPs failed or opened in this step (contact_pass_of): those CPs
  /// release their branches. A released CP's new stress is 0, and its work over the step is that of its old stress
  /// only. (With no time passing, its branches only stop acting: nothing is released.) From the next step on every
  /// CP of the contact keeps its own branch states, from the field's values; those of the released CPs are zero.
  /// Adds the released stresses' force to the lane's resultants (the contact frame's six).
  template <bool AdvanceFields, class G>
  void release_field(G& g, std::size_t c, const Lanes (&motion)[6], std::size_t lane, Lanes (&resultant)[6]) {
    using L = typename G::LawType;
    const auto& p = g.properties[g.property[c]];
    const double kn = L::normal_stiffness(p);
    const double ks = L::shear_stiffness(p);
    const std::uint32_t begin = g.first_point[c], end = g.first_point[c + 1];
    const typename G::FieldSum q{-motion[0][lane], -motion[1][lane], -motion[2][lane],
                                 -motion[3][lane], -motion[4][lane], -motion[5][lane]};
    double field_work = 0.0;
    const auto elongations = g.field_elongations(c);
    typename G::FieldSum after{};
    for (const auto& branch : elongations)
      for (std::size_t j = 0; j < 6; ++j) after[j] += branch[j];
    double fn = 0, f1 = 0, f2 = 0, mn = 0, m1 = 0, m2 = 0;
    for (std::uint32_t k = begin; k < end; ++k) {
      if (L::damping_active(p, g.history[k])) continue;
      const double x1 = g.s1[k], x2 = g.s2[k], area = g.area[k];
      const auto now = Damping::field_stress(after, kn, ks, x1, x2);
      const auto e = Damping::field_stress(q, 1.0, 1.0, x1, x2);  // B q: the CP's elongations
      field_work -= 0.5 * area * (now[0] * e[0] + now[1] * e[1] + now[2] * e[2]);
      add_cp_force(x1, x2, -area * now[0], -area * now[1], -area * now[2], fn, f1, f2, mn, m1, m2);
    }
    if constexpr (AdvanceFields) {
      for (std::uint32_t k = begin; k < end; ++k)
        g.spring_state[k] = L::damping_active(p, g.history[k])
                                ? Damping::field_branch_stresses(elongations, kn, ks, g.s1[k], g.s2[k])
                                : typename G::SpringState{};
      g.field_form[c] = 0;
    }
    g.add_field_work(c, field_work);
    add_to_lane(resultant, lane, {fn, f1, f2, mn, m1, m2});
  }

  /// The fused contact loop of one law (contact_pass_of). Groups with Maxwell fields get the loop compiled twice,
  /// for steps in which time passes and for those in which none does (increment_dt 0: the forces of the present
  /// state only), so that the loop has no branch on it per contact.
  template <class G>
  void contact_pass(G& g, double increment_dt) {
    if constexpr (G::has_field) {
      if (increment_dt > 0.0)
        contact_pass_of<true>(g, increment_dt);
      else
        contact_pass_of<false>(g, increment_dt);
    } else {
      contact_pass_of<true>(g, increment_dt);
    }
  }

  /// The fused contact loop of one law. Per contact: the frame and the relative motion of the two blocks, reduced
  /// to the displacement increment at the origin and the relative rotation; per CP: the increment by four
  /// multiply-adds -> law -> damping -> traction, summed into the contact's force and moments. AdvanceFields:
  /// whether time passes for the Maxwell fields (contact_pass; no use without fields).
  template <bool AdvanceFields, class G>
  void contact_pass_of(G& g, double increment_dt) {
    using L = typename G::LawType;
    auto& b = model_->bodies;
    // Raw pointers in locals: the compiler keeps the array addresses in registers instead of reloading them from the
    // vectors after every store. (GCC honours restrict only on parameters: the CP loop below gets its arrays as the
    // parameters of a lambda; here restrict documents the intent.)
    const Mat3* __restrict const rotation = b.rotation.data();
    const Vec3* __restrict const position = b.position.data();
    const Vec3* __restrict const velocity = b.velocity.data();
    const Vec3* __restrict const omega = b.angular_velocity.data();
    const std::uint32_t* __restrict const body_a = g.body_a.data();
    const std::uint32_t* __restrict const body_b = g.body_b.data();
    const std::uint16_t* __restrict const property = g.property.data();
    const Vec3* __restrict const origin_local = g.origin_a.data();
    const Vec3* __restrict const normal_local = g.normal_a.data();
    const Vec3* __restrict const tangent_local = g.tangent_a.data();
    const std::uint32_t* __restrict const first_point = g.first_point.data();
    Vec3* __restrict const contact_force = g.force.data();
    Vec3* __restrict const contact_moment = g.moment.data();
    const double* __restrict const plane_1 = g.s1.data();
    const double* __restrict const plane_2 = g.s2.data();
    const double* __restrict const area_of = g.area.data();
    const auto* __restrict const properties = g.properties.data();
    auto* __restrict const history = g.history.data();
    auto* __restrict const spring_state = g.spring_state.data();
    double* __restrict const slip_dissipation = g.slip_dissipation.data();
    double* __restrict const viscous_dissipation = g.viscous_dissipation.data();
    auto* __restrict const field = g.field.data();
    std::uint8_t* __restrict const field_form = g.field_form.data();
    const auto count = static_cast<std::ptrdiff_t>(g.contacts());
    const Damping& damping = damping_;
    const double h = 0.5 * increment_dt;
    // Whether the CP loop evaluates viscous stresses per CP (not for None, MassProportional, Local, nor for a
    // contact field, which acts on the contact's resultant).
    constexpr bool cp_viscous = !G::has_field && !std::is_same_v<typename Damping::ContactState, damping::NoState>;
    // Four contacts at a time, one per lane: their kinematics (frame, increment at the origin, relative rotation)
    // and, after their CP loops, their forces and moments in lanes; the CP loops, the law and the damping one
    // contact after another. The last group of a pass repeats its last contact in the lanes it has no contact for
    // and keeps nothing of them. Which contacts share a group does not depend on the number of threads.
    static_assert(lane_count == 4);
    constexpr auto lanes = static_cast<std::ptrdiff_t>(lane_count);
    const std::ptrdiff_t groups_of_lanes = (count + lanes - 1) / lanes;
#pragma omp parallel for schedule(static) if (count > 256)
    for (std::ptrdiff_t lg = 0; lg < groups_of_lanes; ++lg) {
      const auto first = static_cast<std::size_t>(lg * lanes);
      const auto used = static_cast<std::size_t>(std::min(lanes, count - lg * lanes));  // lanes with a contact
      const auto contact_of = [&](std::size_t j) { return first + std::min(j, used - 1); };
      const std::size_t cs[4] = {contact_of(0), contact_of(1), contact_of(2), contact_of(3)};
      const std::uint32_t as[4] = {body_a[cs[0]], body_a[cs[1]], body_a[cs[2]], body_a[cs[3]]};
      const std::uint32_t bs[4] = {body_b[cs[0]], body_b[cs[1]], body_b[cs[2]], body_b[cs[3]]};
      // Lane j of v[index[j]], for the blocks (as, bs) or the contacts (cs) of the lanes.
      const auto gather = [](const Vec3* v, const auto& index) __attribute__((always_inline)) {
        return Triple{Lanes::of([&](int j) { return v[index[j]][0]; }), Lanes::of([&](int j) { return v[index[j]][1]; }),
                      Lanes::of([&](int j) { return v[index[j]][2]; })};
      };
      Lanes ra[3][3];
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) ra[i][k] = Lanes::of([&](int j) { return rotation[as[j]](i, k); });
      const Triple n = turn(ra, gather(normal_local, cs));
      const Triple t1 = turn(ra, gather(tangent_local, cs));
      const Triple t2 = n.cross(t1);
      const Triple arm_a = turn(ra, gather(origin_local, cs));           // origin - x_A
      const Triple arm_b = gather(position, as) + arm_a - gather(position, bs);  // origin - x_B
      // The last move (velocities v(n-1/2)) is measured half a move back, at its middle, so that the same move
      // run backwards gives exactly the opposite increment (to third order): A turned back by h w_A (h = dt/2),
      // both centroids moved back by h v. The CP at origin + S, S = s1 t1 + s2 t2 fixed in A, then moves by
      // du = dt (u + W x S_mid), W = w_B - w_A, read in the mid-step frame (n, t1, t2)_mid = (I - h [w_A]x)(...).
      // In that frame W x S has the components (s2 W_1 - s1 W_2, -s2 W_n, s1 W_n): per CP the increment is
      // du0 plus four products.
      const Triple wa = gather(omega, as), wb = gather(omega, bs);
      const Triple dv = gather(velocity, bs) - gather(velocity, as);
      const Triple wa_arm_a = wa.cross(arm_a);
      const Triple u = increment_dt * (dv + wb.cross(arm_b + h * (dv - wa_arm_a)) - wa.cross(arm_a - h * wa_arm_a));
      const Triple w = increment_dt * (wb - wa);
      const Triple n_mid = n - h * wa.cross(n);
      const Triple t1_mid = t1 - h * wa.cross(t1);
      const Triple t2_mid = t2 - h * wa.cross(t2);
      // The increment at the origin and the relative rotation, in the contact frame, and the resultants that the
      // CP loops give back (force along n, t1, t2 and moment about the origin): one lane per contact.
      const Lanes motion[6] = {dot(u, n_mid), dot(u, t1_mid), dot(u, t2_mid), dot(w, n_mid), dot(w, t1_mid), dot(w, t2_mid)};
      // The resultants of the four contacts (force along n, t1, t2 and moment about the origin), one lane per contact:
      // each contact's CP loop sums from zero and writes its lane; a lane without a contact is set to zero here, so
      // that a full group writes the lanes only once. With Maxwell fields, the four contacts' fields are advanced
      // first, in lanes, and their force is added to the resultants after the CP loops, in vectors: when all four
      // are in the field form, as the fields keep it (the record, just written, is still in L1); else as the
      // masked advance gives it in `field_sum` (zero for the lanes whose CPs keep their own branch states). The
      // CP loops are then those of the policies without fields, and need no lane of the fields' force each. (The
      // simpler order, the advance after the CP loops adding its sums at once, made Maxwell<3> 4-5 % slower:
      // Elastic 415.0 instead of 401.6 instructions per contact.)
      Lanes resultant[6];
      [[maybe_unused]] Lanes field_sum[6];  // the fields' force where not all four lanes are in the field form
      [[maybe_unused]] unsigned released = 0;  // bit `lane`: a CP of the lane's contact failed or opened in this step
      [[maybe_unused]] std::uint32_t forms = 0;  // byte `lane`: the lane's field_form (0 past the last contact)
      constexpr std::uint32_t all_in_field_form = 0x01010101u;
      if constexpr (G::has_field) {
        std::memcpy(&forms, field_form + first, sizeof forms);
        const auto keep = [&] {
          return LaneMask::of(field_form[first], field_form[first + 1], field_form[first + 2], field_form[first + 3]);
        };
        if constexpr (AdvanceFields) {
          if (forms == all_in_field_form) [[likely]]
            damping.advance_field(field[lg], motion);
          else if (forms == 0)  // four contacts whose CPs keep their own branch states (or none)
            for (auto& f : field_sum) f = Lanes::zero();
          else
            damping.advance_field(field[lg], motion, keep(), field_sum);
        } else {
          Damping::field_force(field[lg], keep(), field_sum);
        }
      }
      if (used < lane_count)
        for (auto& r : resultant) r = Lanes::zero();
      for (std::size_t lane = 0; lane < used; ++lane) {
        const std::size_t c = first + lane;
        const double du0_n = motion[0][lane], du0_1 = motion[1][lane], du0_2 = motion[2][lane];
        const double w_n = motion[3][lane], w_1 = motion[4][lane], w_2 = motion[5][lane];
        const auto& p = properties[property[c]];
        const double kn = L::normal_stiffness(p);
        const double ks = L::shear_stiffness(p);
        // Resultants in the contact frame: force (normal, t1, t2) and moment about the origin.
        double fn = 0, f1 = 0, f2 = 0, mn = 0, m1 = 0, m2 = 0;
        const std::uint32_t begin = first_point[c], end = first_point[c + 1];
        // Maxwell branches in the contact-field form (damping::Maxwell::ContactField) are not evaluated per CP: the
        // field keeps each branch's generalised force on the contact, F_i = G h_i, advanced once per step under the
        // contact's generalised elongation increment q = (-du0, -w) through G q (G the contact's stiffness, diagonal
        // in the frame of the CPs' areas); the field's force on the contact is sum_i F_i, added to the resultants
        // after the CP loops, and its tractions at the CPs are evaluated only when asked for
        // (ContactGroup::traction_at). For such a contact the CP loop runs the law only and notes whether a CP
        // failed or opened. A contact whose CPs keep their own branch states (field_form 0, after a CP released its
        // branches) updates them in its CP loop, in the same pass over the CPs (a second pass after the CP loops
        // read every CP twice: on the damaged vault, where nearly every contact has a released CP, 20 % slower).
        [[maybe_unused]] bool inactive = false;
        // The CP loop through restrict parameters: GCC honours restrict on parameters, not on the local pointers above,
        // and without it guards the loop with a run-time check that the histories do not overlap the CPs' coordinates.
        // `own`: the contact's CPs keep their own branch states (a contact with a field after a CP released its
        // branches), updated in this loop; the contacts of a group are ordered by form (assign_contacts), so that the
        // choice per contact is predicted.
        const auto cp_loop = [&](auto own, const double* __restrict const point_1, const double* __restrict const point_2,
            const double* __restrict const point_area, typename G::History* __restrict const point_history,
            typename G::SpringState* __restrict const point_spring, double* __restrict const point_slip,
            double* __restrict const point_viscous) __attribute__((always_inline)) {
          constexpr bool own_branches = decltype(own)::value;
          constexpr bool viscous_here = cp_viscous || own_branches;
          for (std::uint32_t k = begin; k < end; ++k) {
            const double x1 = point_1[k], x2 = point_2[k];
            const double du_n = du0_n + x2 * w_1 - x1 * w_2;
            const contact::Shear du_s{du0_1 - x2 * w_n, du0_2 + x1 * w_n};
            const contact::Response r = L::update(p, point_history[k], du_n, du_s);
            const bool active = r.damping_active;  // L::damping_active(p, point_history[k]), from the step's registers
            const double area = point_area[k];
            double dissipated = 0.0;
            // Spring elongations in the sense of the stresses: closing the gap compresses, shear stress opposes du_s.
            [[maybe_unused]] const std::array<double, 3> e{-du_n, -du_s[0], -du_s[1]};
            std::array<double, 3> v{0.0, 0.0, 0.0};  // viscous stresses, Pa
            if constexpr (own_branches) {
              v = damping.spring_stresses(point_spring[k], kn, ks, e, increment_dt, active, dissipated);
            } else if constexpr (G::has_field) {
              inactive = inactive || !active;
            } else if constexpr (requires { damping.spring_stresses(point_spring[k], kn, ks, e, increment_dt, active, dissipated); }) {
              v = damping.spring_stresses(point_spring[k], kn, ks, e, increment_dt, active, dissipated);
            } else {
              auto& spring = point_spring[k];
              v[0] = damping.spring_stress(spring[0], kn, e[0], increment_dt, active, dissipated);
              v[1] = damping.spring_stress(spring[1], ks, e[1], increment_dt, active, dissipated);
              v[2] = damping.spring_stress(spring[2], ks, e[2], increment_dt, active, dissipated);
            }
            // The traction is not stored: ContactGroup::traction_at() gets it back from the history and the state.
            // Policies without viscous stresses at the CP do not add v's zeros (x + 0.0 is not x for x = -0.0, so the
            // compiler keeps the additions).
            double sn = r.normal_stress, s1 = r.shear_stress[0], s2 = r.shear_stress[1];
            if constexpr (viscous_here) {
              sn += v[0];
              s1 += v[1];
              s2 += v[2];
            }
            add_cp_force(x1, x2, area * sn, area * s1, area * s2, fn, f1, f2, mn, m1, m2);
            // Only what can be non-zero is stored: a law or a policy that never dissipates costs no memory traffic here.
            if constexpr (!std::is_same_v<L, contact::Elastic>) point_slip[k] += area * r.dissipated;
            if constexpr (viscous_here) point_viscous[k] += area * dissipated;
          }
        };
        if constexpr (G::has_field) {
          if (field_form[c]) [[likely]]
            cp_loop(std::false_type{}, plane_1, plane_2, area_of, history, spring_state, slip_dissipation, viscous_dissipation);
          else
            cp_loop(std::true_type{}, plane_1, plane_2, area_of, history, spring_state, slip_dissipation, viscous_dissipation);
        } else {
          cp_loop(std::false_type{}, plane_1, plane_2, area_of, history, spring_state, slip_dissipation, viscous_dissipation);
        }
        if constexpr (G::has_field) released |= static_cast<unsigned>(inactive) << lane;
        resultant[0].set(lane, fn);
        resultant[1].set(lane, f1);
        resultant[2].set(lane, f2);
        resultant[3].set(lane, mn);
        resultant[4].set(lane, m1);
        resultant[5].set(lane, m2);
      }
      // The fields' force; then contacts whose CPs keep their own branch states, and contacts in the field form
      // with a CP that released its branches in this step: both rare.
      if constexpr (G::has_field) {
        if (AdvanceFields && forms == all_in_field_form) [[likely]] {
          for (std::size_t j = 0; j < 6; ++j) resultant[j] += Damping::field_sum(field[lg], j);
        } else {
          for (std::size_t j = 0; j < 6; ++j) resultant[j] += field_sum[j];
        }
        if (forms != all_in_field_form || released != 0) [[unlikely]] {
          for (std::size_t lane = 0; lane < used; ++lane)
            if (field_form[first + lane] && (released >> lane & 1u))
              release_field<AdvanceFields>(g, first + lane, motion, lane, resultant);
        }
      }
      const Triple f = combine(n, t1, t2, resultant[0], resultant[1], resultant[2]);
      const Triple m_origin = combine(n, t1, t2, resultant[3], resultant[4], resultant[5]);
      const Triple moment_a = -(arm_a.cross(f) + m_origin);
      const Triple moment_b = arm_b.cross(f) + m_origin;
      for (std::size_t lane = 0; lane < used; ++lane) {
        const std::size_t c = first + lane;
        contact_force[c] = f.vec(lane);
        contact_moment[2 * c] = moment_a.vec(lane);
        contact_moment[2 * c + 1] = moment_b.vec(lane);
      }
    }
  }

  /// Blocks per tile of the block pass. Tiles, not threads, decide which blocks share a group of vector lanes, so
  /// that results do not depend on the number of threads; and a tile's gathered resultants are still in L1 when its
  /// update reads them.
  static constexpr std::size_t block_tile = 64;

  /// What the vector loops of a tile overwrite for blocks that are not free, put back afterwards.
  struct KeptBlock {
    std::size_t i;
    Vec3 position, velocity, angular_velocity;
    Quaternion orientation;
    Mat3 rotation;
    double kinetic, viscous, gravity_work;
  };

  /// Gather, gravity, damped velocity update; then position and orientation update, for every block, tile by tile.
  template <bool Mixed = false>
  void block_pass(double increment_dt, bool move = true) {
    auto& b = model_->bodies;
    const std::size_t n = b.size();
    const auto tiles = static_cast<std::ptrdiff_t>((n + block_tile - 1) / block_tile);
    const Vec3 base_velocity = model_->base_velocity(time_ + 0.5 * dt_);
    if (move) base_displacement_ += dt_ * base_velocity;
    const Vec3 base_moved = base_displacement_ - detected_base_displacement_;
    bool moved = false;
#pragma omp parallel for schedule(static) if (n > 1024) reduction(|| : moved)
    for (std::ptrdiff_t t = 0; t < tiles; ++t) {
      const std::size_t begin = static_cast<std::size_t>(t) * block_tile, end = std::min(begin + block_tile, n);
      gather_resultants<Mixed>(begin, end, increment_dt, base_velocity, move);
      std::array<KeptBlock, block_tile> kept;
      std::size_t kept_count = 0;
      for (std::size_t i = begin; i < end; ++i)
        if (b.motion[i] != model::Motion::free)
          kept[kept_count++] = {i, b.position[i], b.velocity[i], b.angular_velocity[i], b.orientation[i], b.rotation[i],
                                kinetic_[i], viscous_[i], gravity_work_[i]};
      update_velocities(begin, end, increment_dt);
      if (move) moved = update_positions(begin, end, base_moved) || moved;
      for (std::size_t k = 0; k < kept_count; ++k) {
        const KeptBlock& e = kept[k];
        b.position[e.i] = e.position;
        b.velocity[e.i] = e.velocity;
        b.angular_velocity[e.i] = e.angular_velocity;
        b.orientation[e.i] = e.orientation;
        b.rotation[e.i] = e.rotation;
        kinetic_[e.i] = e.kinetic;
        viscous_[e.i] = e.viscous;
        gravity_work_[e.i] = e.gravity_work;
      }
    }
    moved_since_detection_ = moved_since_detection_ || moved;
  }

  /// The contacts' resultants on blocks [begin, end), summed in a fixed order, plus gravity on free blocks; base
  /// blocks follow the base velocity.
  template <bool Mixed>
  void gather_resultants(std::size_t begin, std::size_t end, double increment_dt, const Vec3& base_velocity, bool move) {
    auto& b = model_->bodies;
    const Vec3 gravity = model_->gravity;
    for (std::size_t i = begin; i < end; ++i) {
      Vec3 force = Vec3::Zero();
      Vec3 moment = Vec3::Zero();
      for_each_group([&](const auto& g) {
        for (std::uint32_t e = g.first[i]; e < g.first[i + 1]; ++e) {
          const std::uint32_t code = g.entry[e];
          // Branch-free: the side of the block in the contact is random from one entry to the next.
          const double sign = static_cast<double>(code & 1u) * 2.0 - 1.0;
          force += sign * g.force[code >> 1];
          moment += g.moment[code];
        }
      });
      if constexpr (Mixed) {  // node contacts, trusses, weight correction of scaled blocks
        force += deformable_.extra_force[i];
        moment += deformable_.extra_moment[i];
      }
      const model::Motion motion = b.motion[i];
      if (motion == model::Motion::free) force += b.mass[i] * gravity;
      b.force[i] = force;
      b.moment[i] = moment;
      if (motion == model::Motion::base && move) {
        base_work_[i] -= force.dot(b.velocity[i]) * increment_dt;  // the move that led to x_n, against `force`
        b.velocity[i] = base_velocity;
        b.angular_velocity[i].setZero();
        b.position[i] += dt_ * base_velocity;
      }
    }
  }

  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Mat3) == 9 * sizeof(double) &&
                sizeof(Quaternion) == 4 * sizeof(double), "the block update reads Eigen's coefficients in place");

  /// a where the mask is all ones, b where it is zero. A ternary would let the compiler move the arithmetic of the
  /// side not taken into a branch, which the vectoriser does not turn back into a selection (floating-point
  /// operations may trap).
  [[gnu::always_inline]] static double select(std::uint64_t mask, double a, double b) noexcept {
    return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) | (std::bit_cast<std::uint64_t>(b) & ~mask));
  }

  /// Damped velocity update of blocks [begin, end), one block per vector lane and all of them as if free (the
  /// caller puts back the others). Fixed degrees of freedom are selected, not branched around.
  void update_velocities(std::size_t begin, std::size_t end, double increment_dt) {
    auto& b = model_->bodies;
    // The arrays as restrict parameters of a function: with restrict local pointers GCC 12 left this loop scalar
    // (too many run-time alias checks).
    // Fixity widened to the width of the doubles: one byte-sized array makes the vectoriser put as many blocks in
    // a vector iteration as bytes fit in a register (32), which spilled most of the loop's state to the stack.
    const std::size_t count = end - begin;
    std::uint64_t fixity_wide[block_tile];
    for (std::size_t k = 0; k < count; ++k) fixity_wide[k] = b.fixity[begin + k];
    const auto update = [damping = damping_, dt = dt_, increment_dt, count, gravity = model_->gravity](
                            const std::uint64_t* __restrict fixity_of, const double* __restrict mass,
                            const double* __restrict inverse_mass, const double* __restrict principal_inertia,
                            const double* __restrict inverse_principal_inertia, const double* __restrict orientation,
                            const double* __restrict force, const double* __restrict moment, double* __restrict velocity,
                            double* __restrict angular_velocity, double* __restrict kinetic, double* __restrict viscous,
                            double* __restrict gravity_work) {
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t fixity = fixity_of[i];
        const double mass_i = mass[i], inverse_mass_i = inverse_mass[i];
        const double* inertia = principal_inertia + 3 * i;
        const double* inverse_inertia = inverse_principal_inertia + 3 * i;
        double r[9];  // r(j, k) at 3 k + j
        rotation_coefficients(orientation + 4 * i, r);
        double dissipated = 0.0;
        double v_old[3], v[3], w_old[3], m_world[3];
        for (int c = 0; c < 3; ++c) {
          v_old[c] = velocity[3 * i + c];
          w_old[c] = angular_velocity[3 * i + c];
          m_world[c] = moment[3 * i + c];
          double with_this = dissipated;
          const double updated =
              damping.velocity_update(v_old[c], force[3 * i + c], damping::Inertia{mass_i, inverse_mass_i}, dt, with_this);
          const std::uint64_t fixed = 0 - ((fixity >> c) & 1u);
          v[c] = select(fixed, 0.0, updated);
          dissipated = select(fixed, dissipated, with_this);
        }
        // Rotation in the principal frame (Euler's equations). The gyroscopic term is taken at the mid-step angular
        // velocity (implicit midpoint, fixed-point passes: dt |w| is tiny), which keeps the scheme time reversible.
        double w_old_body[3], m_applied[3], w_body[3];
        for (int k = 0; k < 3; ++k) {
          w_old_body[k] = r[3 * k] * w_old[0] + r[3 * k + 1] * w_old[1] + r[3 * k + 2] * w_old[2];
          m_applied[k] = r[3 * k] * m_world[0] + r[3 * k + 1] * m_world[1] + r[3 * k + 2] * m_world[2];
          w_body[k] = w_old_body[k];
        }
        double rotation_dissipated = 0.0;
        for (int pass = 0; pass < 3; ++pass) {
          double w_mid[3], l[3];
          for (int c = 0; c < 3; ++c) {
            w_mid[c] = 0.5 * (w_old_body[c] + w_body[c]);
            l[c] = inertia[c] * w_mid[c];  // angular momentum
          }
          const double m_body[3] = {m_applied[0] - (w_mid[1] * l[2] - w_mid[2] * l[1]),
                                    m_applied[1] - (w_mid[2] * l[0] - w_mid[0] * l[2]),
                                    m_applied[2] - (w_mid[0] * l[1] - w_mid[1] * l[0])};
          rotation_dissipated = 0.0;
          for (int c = 0; c < 3; ++c)
            w_body[c] = damping.velocity_update(w_old_body[c], m_body[c], damping::Inertia{inertia[c], inverse_inertia[c]},
                                                dt, rotation_dissipated);
        }
        dissipated += rotation_dissipated;
        double w[3], w_back[3];
        for (int j = 0; j < 3; ++j)
          w[j] = select(0 - ((fixity >> (3 + j)) & 1u), 0.0, r[j] * w_body[0] + r[3 + j] * w_body[1] + r[6 + j] * w_body[2]);
        for (int k = 0; k < 3; ++k) w_back[k] = r[3 * k] * w[0] + r[3 * k + 1] * w[1] + r[3 * k + 2] * w[2];
        const std::uint64_t rotation_fixed = 0 - static_cast<std::uint64_t>((fixity & model::Fixity::all_rotations) != 0);
        for (int c = 0; c < 3; ++c) {
          w_body[c] = select(rotation_fixed, w_back[c], w_body[c]);
          velocity[3 * i + c] = v[c];
          angular_velocity[3 * i + c] = w[c];
        }
        // Kinetic energy at step n from the two half-step velocities: conserved exactly by the undamped leapfrog.
        kinetic[i] = 0.5 * mass_i * (v_old[0] * v[0] + v_old[1] * v[1] + v_old[2] * v[2]) +
                     0.5 * (w_old_body[0] * inertia[0] * w_body[0] + w_old_body[1] * inertia[1] * w_body[1] +
                            w_old_body[2] * inertia[2] * w_body[2]);
        viscous[i] += dissipated;
        // Work of gravity over the move that brought the block to x_n, where the forces and energies are evaluated.
        gravity_work[i] += mass_i * (gravity[0] * v_old[0] + gravity[1] * v_old[1] + gravity[2] * v_old[2]) * increment_dt;
      }
    };
    // The rotation matrix from the orientation (four numbers per block, loaded as whole vectors) instead of from
    // `rotation` (nine, whose stride the vectoriser cannot load as a group); rotation is rotation_matrix(orientation).
    update(fixity_wide, b.mass.data() + begin, inverse_mass_.data() + begin, b.principal_inertia[begin].data(),
           inverse_inertia_[begin].data(), b.orientation[begin].coeffs().data(), b.force[begin].data(),
           b.moment[begin].data(), b.velocity[begin].data(), b.angular_velocity[begin].data(), kinetic_.data() + begin,
           viscous_.data() + begin, gravity_work_.data() + begin);
  }

  /// Positions and orientations of blocks [begin, end), one block per vector lane and all of them as if free (the
  /// caller puts back the others); whether a free block moved (relative to the base) by more than its redetection
  /// distance (update_redetection_distances) since the last detection, rotation counting with the block's radius.
  /// Turns beyond the range of turned()'s series, and blocks near their redetection distance, are finished one by
  /// one afterwards.
  bool update_positions(std::size_t begin, std::size_t end, const Vec3& base_moved) {
    auto& b = model_->bodies;
    const double dt = dt_;
    const double h = 0.5 * dt;
    const double shift[3] = {base_moved[0], base_moved[1], base_moved[2]};
    // The turned quaternion before its normalisation, whose square root (with libm's errno check) would keep the
    // loop from being vectorised; the half angle squared, to find turns beyond the series; the reach (|d|^2 + a^2)
    // of the move since the last detection; the old orientation, for turns beyond the series.
    alignas(64) double turned_x[block_tile], turned_y[block_tile], turned_z[block_tile], turned_w[block_tile];
    alignas(64) double half_angle2[block_tile], scale[block_tile], reach[block_tile], old_orientation[4 * block_tile];
    const std::size_t count = end - begin;
    // Restrict parameters, as in update_velocities().
    const auto turn = [&](const double* __restrict velocity, const double* __restrict angular_velocity,
                          double* __restrict position, const double* __restrict orientation) {
      for (std::size_t k = 0; k < count; ++k) {
        for (int c = 0; c < 3; ++c) position[3 * k + c] += dt * velocity[3 * k + c];
        // turned(), with cos x and sin x / x of the half angle x from their series.
        const double wx = angular_velocity[3 * k], wy = angular_velocity[3 * k + 1], wz = angular_velocity[3 * k + 2];
        const double x2 = 0.25 * dt * dt * (wx * wx + wy * wy + wz * wz);
        double cx, sx;
        half_angle_series(x2, cx, sx);
        const double f = h * sx;
        const double vx = f * wx, vy = f * wy, vz = f * wz;
        const double qx = orientation[4 * k], qy = orientation[4 * k + 1], qz = orientation[4 * k + 2], qw = orientation[4 * k + 3];
        turned_x[k] = cx * qx + qw * vx + (vy * qz - vz * qy);
        turned_y[k] = cx * qy + qw * vy + (vz * qx - vx * qz);
        turned_z[k] = cx * qz + qw * vz + (vx * qy - vy * qx);
        turned_w[k] = cx * qw - (vx * qx + vy * qy + vz * qz);
        half_angle2[k] = x2;
      }
    };
    turn(b.velocity[begin].data(), b.angular_velocity[begin].data(), b.position[begin].data(),
         b.orientation[begin].coeffs().data());
    for (std::size_t k = 0; k < count; ++k)
      scale[k] = 1.0 / std::sqrt(turned_w[k] * turned_w[k] + turned_x[k] * turned_x[k] + turned_y[k] * turned_y[k] +
                                 turned_z[k] * turned_z[k]);
    // The rotation matrices, column by column (r(j, m) in rotation_of[3 m + j]): nine numbers per block at a stride
    // of nine are no group the vectoriser stores, so they are copied into `rotation` one by one below.
    alignas(64) double rotation_of[9][block_tile];
    const auto normalise = [&](double* __restrict orientation, const double* __restrict position,
                               const double* __restrict detected_position, const double* __restrict detected_orientation,
                               const double* __restrict radius) {
      for (std::size_t k = 0; k < count; ++k) {
        for (int c = 0; c < 4; ++c) old_orientation[4 * k + c] = orientation[4 * k + c];
        const double s = scale[k];
        const double q[4] = {s * turned_x[k], s * turned_y[k], s * turned_z[k], s * turned_w[k]};
        for (int c = 0; c < 4; ++c) orientation[4 * k + c] = q[c];
        double r[9];
        rotation_coefficients(q, r);
        for (int j = 0; j < 9; ++j) rotation_of[j][k] = r[j];
        const double dx = position[3 * k] - detected_position[3 * k] - shift[0];
        const double dy = position[3 * k + 1] - detected_position[3 * k + 1] - shift[1];
        const double dz = position[3 * k + 2] - detected_position[3 * k + 2] - shift[2];
        // Twice the vector part of q q0^-1 (small_angle_between()).
        const double* q0 = detected_orientation + 4 * k;
        const double ex = q0[3] * q[0] - q[3] * q0[0] - (q[1] * q0[2] - q[2] * q0[1]);
        const double ey = q0[3] * q[1] - q[3] * q0[1] - (q[2] * q0[0] - q[0] * q0[2]);
        const double ez = q0[3] * q[2] - q[3] * q0[2] - (q[0] * q0[1] - q[1] * q0[0]);
        reach[k] = (dx * dx + dy * dy + dz * dz) + 4.0 * (ex * ex + ey * ey + ez * ez) * radius[k] * radius[k];
      }
    };
    normalise(b.orientation[begin].coeffs().data(), b.position[begin].data(),
              detected_position_[begin].data(), detected_orientation_[begin].coeffs().data(), radius_.data() + begin);
    bool moved = false;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = begin + k;
      for (int j = 0; j < 9; ++j) b.rotation[i].data()[j] = rotation_of[j][k];
      if (b.motion[i] != model::Motion::free) continue;
      const bool large_turn = !(half_angle2[k] < 1e-4);
      if (large_turn) {
        b.orientation[i] = turned(Quaternion(old_orientation[4 * k + 3], old_orientation[4 * k], old_orientation[4 * k + 1],
                                             old_orientation[4 * k + 2]),
                                  b.angular_velocity[i], dt);
        b.rotation[i] = rotation_matrix(b.orientation[i]);
      }
      // (|d| + a)^2 <= 2 (|d|^2 + a^2): most blocks are far below the redetection distance, without square roots.
      const double redetection = redetection_distance_[i];
      if (large_turn || 2.0 * reach[k] > redetection * redetection) {
        const double angle = small_angle_between(b.orientation[i], detected_orientation_[i]);
        moved = moved || (b.position[i] - detected_position_[i] - base_moved).norm() + angle * radius_[i] > redetection;
      }
    }
    return moved;
  }

  EnergyReport energy_terms() const {
    EnergyReport e;
    e.slip = retired_slip_;
    e.viscous = retired_viscous_;
    e.contact_update = contact_update_;
    const auto& b = model_->bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
      e.kinetic += kinetic_[i];
      e.gravity_work += gravity_work_[i];
      e.base_work += base_work_[i];
      e.viscous += viscous_[i];
    }
    for_each_group([&](const auto& g) {
      using L = typename std::remove_cvref_t<decltype(g)>::LawType;
      for (std::size_t c = 0; c < g.contacts(); ++c) {
        const auto& p = g.properties[g.property[c]];
        if constexpr (std::remove_cvref_t<decltype(g)>::has_field) e.viscous += g.field_work(c);
        for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k)
          add_contact_point_energy<L>(damping_, p, g.history[k], g.spring_at(c, k), g.area[k], g.slip_dissipation[k],
                                      g.viscous_dissipation[k], e.elastic, e.slip, e.viscous);
      }
    });
    if (mixed_) {
      const auto d = deformable_.energy(*model_, damping_);
      e.kinetic += d.kinetic;
      e.elastic += d.elastic;
      e.gravity_work += d.gravity_work;
      e.viscous += d.viscous;
      e.slip += d.slip;
    }
    return e;
  }

  /// The step, specialised at compile time: the rigid-only instantiation is the rigid kernel exactly; the mixed
  /// one adds the node contacts, elements and trusses, the extra forces on rigid blocks and the node pass. The mixed
  /// step is kept out of line so that it does not change how the compiler inlines the rigid one.
  [[gnu::noinline]] void mixed_step() { step_impl<true>(); }

  template <bool Mixed>
  void step_impl() {
    const double increment_dt = pending_increment_ ? dt_ : 0.0;
    for_each_group([&](auto& g) { contact_pass(g, increment_dt); });
    if constexpr (Mixed) mixed_forces(increment_dt);
    // Joint histories are now at the current positions: the moment to detect contacts again if blocks have moved
    // (relative to the base) by more than the redetection distance. Forces of the new set, then the block pass.
    if (++steps_since_check_ >= settings_.redetection_check_interval) {
      steps_since_check_ = 0;
      if (moved_since_detection_) redetect_and_update<Mixed>();
    }
    block_pass<Mixed>(increment_dt);
    if constexpr (Mixed) {
      const bool nodes_moved = deformable_.node_pass(*model_, damping_, dt_, increment_dt, true, settings_.redetection());
      moved_since_detection_ = moved_since_detection_ || nodes_moved;
    }
    // The scheme conserves 1/2 m v(n-1/2).v(n+1/2) + U(x_n): the reference is its value at the first step.
    if (energy_reference_pending_) {
      energy0_ = energy_terms();
      energy_reference_pending_ = false;
    }
    pending_increment_ = true;
    time_ += dt_;
    ++steps_;
  }

  /// Detects the contacts again and computes the forces of the new set. The discrete model changes here: CPs that
  /// start in overlap (an impact, a vertex that slid onto a face), CPs dropped while loaded, CPs whose tributary area
  /// changed. The energy stored in the contacts that this adds or removes is done by no force; it is kept as its own
  /// term of the balance (EnergyReport::contact_update), measured, not inferred from the residual.
  template <bool Mixed>
  void redetect_and_update() {
    const auto stored = [&] {
      const EnergyReport e = energy_terms();
      return e.elastic + e.viscous + e.slip;
    };
    const double before = stored();
    if constexpr (Mixed) {
      update_proxies();
      assign_all(model::detect_contacts(model_->bodies, settings_), /*keep_history=*/true);
    } else {
      assign_contacts(model::detect_contacts(model_->bodies, settings_), /*keep_history=*/true);
    }
    for_each_group([&](auto& g) { contact_pass(g, 0.0); });
    if constexpr (Mixed) mixed_forces(0.0);
    contact_update_ += stored() - before;
    hold_timestep();
  }

  /// After a re-detection of a dynamic run: the new contact points may have raised omega_max (eq. 1) above what
  /// the timestep allows. A density-scaled run (scale_density_to) keeps its timestep and raises, by the same rule
  /// and safety factor, the masses of the free nodes and rigid blocks whose row of FrequencyBound now exceeds the
  /// target, at their present velocities (the kinetic energy this adds is a change of the model, kept in the
  /// balance's contact_update term); any other run with a checked timestep keeps its margin dt / dt_critical by
  /// lowering the timestep. Without this, one stiff new contact point at a light node diverges in a few steps.
  void hold_timestep() {
    if (!bounded_frequency()) return;  // static masses (settling): the estimate's wide margin, and local damping
    if (density_safety_ > 0) {
      ++hold_.checks;
      const MassPlan plan = plan_masses(dt_, density_safety_, MassRule::raise_only,
                                        [&](double omega) { return damping_.timestep_factor(omega); });
      auto& b = model_->bodies;
      auto& nd = model_->deformable.nodes;
      double added = 0, kinetic = 0;
      long long nodes = 0, blocks = 0;
      for (std::size_t i = 0; i < nd.size(); ++i) {
        if (!(plan.node_mass[i] > nd.mass[i])) continue;
        const double dm = plan.node_mass[i] - nd.mass[i];
        added += dm;
        kinetic += 0.5 * dm * nd.velocity[i].squaredNorm();
        nd.mass[i] = plan.node_mass[i];
        deformable_.node_inverse_mass[i] = 1.0 / nd.mass[i];
        ++nodes;
      }
      for (std::size_t i = 0; i < b.size(); ++i) {
        if (!(plan.block_mass[i] > b.mass[i])) continue;
        const double f = plan.block_mass[i] / b.mass[i];
        const Vec3 w = b.rotation[i].transpose() * b.angular_velocity[i];
        added += plan.block_mass[i] - b.mass[i];
        kinetic += (f - 1) * 0.5 * (b.mass[i] * b.velocity[i].squaredNorm() + w.cwiseProduct(w).dot(b.principal_inertia[i]));
        b.mass[i] = plan.block_mass[i];
        b.principal_inertia[i] = plan.block_inertia[i];
        inverse_mass_[i] = 1.0 / b.mass[i];
        inverse_inertia_[i] = b.principal_inertia[i].cwiseInverse();
        ++blocks;
      }
      if (nodes + blocks == 0) return;
      ++hold_.raises;
      hold_.raised_nodes += nodes;
      hold_.raised_blocks += blocks;
      hold_.added_mass += added;
      hold_.kinetic_energy += kinetic;
      contact_update_ += kinetic;
    } else if (timestep_margin_ > 0) {
      ++hold_.checks;
      const double critical = critical_timestep();
      if (!(dt_ > timestep_margin_ * critical)) return;
      const double margin = timestep_margin_;
      set_timestep(margin * critical);
      timestep_margin_ = margin;
      ++hold_.reductions;
      hold_.smallest_dt = dt_;
    }
  }

  /// Node contacts, elements, trusses, then what they apply to rigid blocks.
  void mixed_forces(double increment_dt) {
    deformable_.contact_pass(*model_, damping_, increment_dt);
    deformable_.element_pass(*model_, damping_, increment_dt);
    deformable_.truss_pass(*model_);
    deformable_.gather_rigid(*model_, increment_dt);
  }

  /// Rigid-rigid pairs to the rigid groups, pairs with a deformable block to the node groups.
  void assign_all(const std::vector<model::ContactCandidate>& candidates, bool keep_history) {
    if (!mixed_) {
      assign_contacts(candidates, keep_history);
      return;
    }
    std::vector<model::ContactCandidate> rigid, deformable;
    for (const auto& c : candidates)
      (model_->deformable.is_deformable(c.a) || model_->deformable.is_deformable(c.b) ? deformable : rigid).push_back(c);
    assign_contacts(rigid, keep_history);
    deformable_.assign(*model_, deformable, [&](int ta, int tb) { return choose_properties(ta, tb); }, settings_, keep_history);
  }

  Properties choose_properties(int ta, int tb) {
    auto it = chosen_properties_.find({ta, tb});
    if (it == chosen_properties_.end()) it = chosen_properties_.emplace(std::make_pair(ta, tb), properties_(ta, tb)).first;
    return it->second;
  }

  /// Moves the rigid entry of each deformable block with the mean motion of its nodes (for the detection).
  void update_proxies() {
    if (!mixed_) return;
    auto& b = model_->bodies;
    const auto& x = model_->deformable.nodes.position;
    for (const auto& blk : model_->deformable.blocks) {
      Vec3 shift = Vec3::Zero();
      for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) shift += x[i] - blk.reference_position[i - blk.first_node];
      b.position[blk.body] = blk.reference_centroid + shift / static_cast<double>(blk.end_node - blk.first_node);
    }
  }

  model::Model* model_;
  Damping damping_;
  bool mixed_ = false;
  kinematics::DeformableState<Damping, Laws...> deformable_;
  std::map<std::pair<int, int>, Properties> chosen_properties_;
  PropertyFunction properties_;
  model::ContactSettings settings_;
  Groups groups_;
  double dt_ = 0;
  double time_ = 0;
  long long steps_ = 0;
  int steps_since_check_ = 0;
  int detections_ = 0;
  bool pending_increment_ = false;
  bool moved_since_detection_ = false;
  bool static_masses_ = false;  // scale_masses_for_statics() until restore_real_masses()
  double density_safety_ = 0;   // the safety factor of scale_density_to() while its masses hold; 0: not density-scaled
  double timestep_margin_ = 0;  // dt / dt_critical when the timestep was set (checked); 0: unchecked
  TimestepHold hold_;
  std::vector<double> kinetic_, gravity_work_, base_work_, viscous_, radius_;
  std::vector<double> redetection_distance_;  // m, per block (update_redetection_distances)
  std::vector<double> inverse_mass_;     // 1/kg, of each block (set with the block arrays)
  std::vector<Vec3> inverse_inertia_;    // 1/(kg m^2), principal
  std::vector<Vec3> detected_position_;
  Vec3 base_displacement_ = Vec3::Zero();           // m, integral of the base velocity
  Vec3 detected_base_displacement_ = Vec3::Zero();  // at the last detection
  std::vector<Quaternion> detected_orientation_;
  EnergyReport energy0_;
  bool energy_reference_pending_ = true;
  double retired_slip_ = 0, retired_viscous_ = 0;  // J, dissipated at CPs that no longer exist
  double contact_update_ = 0;  // J, energy stored in the contacts that re-detection added (redetect_and_update)
  std::array<std::vector<std::uint8_t>, sizeof...(Laws)> taken_over_;  // old CPs already matched, during a detection
  std::array<std::unordered_map<std::uint64_t, std::uint32_t>, sizeof...(Laws)> old_contacts_;  // by block pair, idem
};

}  // namespace blockdem
