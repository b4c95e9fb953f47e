#pragma once
// The explicit central-difference integrator (paper Sect. 3.1, DESIGN.md §4). One Simulation type per damping
// policy and list of joint laws: it keeps the state and the order of the passes, each pass a function template of
// its own header, specialised at compile time, with no virtual call and no branch on the policy:
//   contact pass (integrate/contact_pass.hpp, the Maxwell contact field: integrate/maxwell_field.hpp)
//   -> node contacts, elements, trusses of deformable blocks (integrate/node_pass.hpp, integrate/element_pass.hpp)
//   -> [re-detection: integrate/contact_assignment.hpp, integrate/node_contact_assignment.hpp]
//   -> block pass (integrate/block_pass.hpp) -> node pass (integrate/node_pass.hpp).
// The timestep and density scaling are in integrate/timestep.hpp, the energy balance in integrate/energy.hpp, the
// output view of the contacts in integrate/contact_view.hpp. Results do not depend on the number of OpenMP threads.
// The members that detect and assign contacts are defined in integrate/simulation_contacts.hpp, those that set the
// timestep and the masses in integrate/simulation_masses.hpp, the checkpoint state in integrate/simulation_state.hpp.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/frame.hpp"
#include "blockdem/integrate/block_pass.hpp"
#include "blockdem/integrate/contact_assignment.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/integrate/contact_pass.hpp"
#include "blockdem/integrate/contact_view.hpp"
#include "blockdem/integrate/deformable_forces.hpp"
#include "blockdem/integrate/deformable_state.hpp"
#include "blockdem/integrate/element_pass.hpp"
#include "blockdem/integrate/energy.hpp"
#include "blockdem/integrate/frequency_bound.hpp"
#include "blockdem/integrate/node_contact_assignment.hpp"
#include "blockdem/integrate/node_pass.hpp"
#include "blockdem/integrate/run_guard.hpp"
#include "blockdem/integrate/timestep.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
class Simulation {
  static_assert(sizeof...(Laws) >= 1, "Simulation needs at least one joint law");

 public:
  using Properties = std::variant<typename Laws::Parameters...>;
  /// Chooses the law and its parameters for the joint between blocks with these joint tags.
  using PropertyFunction = std::function<Properties(int tag_a, int tag_b)>;
  using ContactView = blockdem::ContactView;

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
    ContactAssignment<Damping, Laws...>::copy_histories(other.groups_, groups_, damping_, model_->bodies.size());
    // The mixed step only for what needs it: not for a rigid-only model whose real masses were put back.
    mixed_ = other.mixed_ && (!model_->deformable.empty() || other.scaled_rigid_blocks());
    if (mixed_) deformable_.take_over(other.deformable_, *model_);
    time_ = other.time_;
    // The other's timestep if one was chosen below its default (and below this policy's), else this policy's default.
    const bool chosen = other.dt_ < other.default_timestep() * (1 - 1e-12);
    set_timestep(chosen ? std::min(other.dt_, default_timestep()) : default_timestep());
    density_safety_ = other.density_safety_;
    damping_frame_ = other.damping_frame_;
  }

  // ---- the step (Sect. 3.1) ----

  void step() {
    if (mixed_) mixed_step();
    else step_impl<false>();
  }

  /// Reverses the motion exactly (up to rounding): after n more steps the blocks are back where they were n steps
  /// ago, with velocities negated. For time-reversibility checks of the scheme.
  void reverse() {
    synchronize();
    for_each_group([&](auto& g) { contact_pass(g, model_->bodies, damping_, 0.0, closure_inverse_omega_squared()); });
    auto& b = model_->bodies;
    // v(n+1/2) = v(n-1/2) + dt F(x_n) / m, then negate: the leapfrog run backwards from x_n.
    if (mixed_) {
      mixed_forces(0.0);
      run_block_pass<true>(0.0, /*move=*/false);
      node_pass(deformable_, *model_, damping_, dt_, 0.0, false, settings_.redetection());
      for (auto& v : model_->deformable.nodes.velocity) v = -v;
    } else {
      run_block_pass<false>(0.0, /*move=*/false);
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
    for_each_group([&](auto& g) { contact_pass(g, model_->bodies, damping_, move_timestep(), closure_inverse_omega_squared()); });
    if (mixed_) mixed_forces(move_timestep());
    pending_increment_ = false;
  }

  /// Detects the contacts again now: existing CPs keep their history (matched by block pair and location), new
  /// contacts appear, CPs of blocks that moved apart are dropped.
  void redetect() {
    synchronize();
    if (mixed_) redetect_and_update<true>();
    else redetect_and_update<false>();
    pending_increment_ = false;
  }

  // ---- timestep (eq. 1-3, 11, 20) and density scaling (Sect. 3.2): integrate/timestep.hpp ----

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

  /// Critical timestep 2 / omega_max (eq. 1) times the damping policy's factor (eq. 11, eq. 20); infinite if no
  /// free block or node has a spring. omega_max: the upper bound of FrequencyBound; under static masses the largest
  /// of sqrt(k / m) over the nodes (eq. 2-3) and over the free blocks sqrt(k / m) for translation and
  /// sqrt(k r^2 / I_min) for rotation, k the sum of max(k_n, k_s) A of their contact points.
  double critical_timestep() const { return critical_timestep(omega_max()); }
  /// The same for a given omega_max (rad/s).
  double critical_timestep(double omega) const {
    if (omega == 0) return std::numeric_limits<double>::infinity();
    return 2.0 / omega * damping_.timestep_factor(omega);
  }

  /// omega_max of eq. 1 (rad/s), without the damping policy: the bound or the estimate (see critical_timestep()).
  double omega_max() const { return bounded_frequency() ? frequency_bound().omega_max() : estimated_omega_max(); }

  /// The upper bound on omega_max for the present contacts, elements, trusses and masses.
  FrequencyBound frequency_bound() const { return blockdem::frequency_bound(*model_, groups_, deformable()); }

  /// Eq. 1-3's estimate of omega_max (rad/s): per node and per rigid block on its own (see critical_timestep()).
  double estimated_omega_max() const { return blockdem::estimated_omega_max(*model_, groups_, deformable()); }

  /// Stiffness (N/m) on each rigid block (translation; rotation k r^2 in N m) and on each node: contacts, elements
  /// (eq. 2) and trusses.
  void stiffnesses(std::vector<double>& k_translation, std::vector<double>& k_rotation, std::vector<double>& k_node) const {
    blockdem::stiffnesses(*model_, groups_, deformable(), k_translation, k_rotation, k_node);
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
  double density_scaling_mass(double target_dt, Factor timestep_factor) const;
  /// The same from `bound`, this simulation's frequency_bound() of the present masses and contacts: one bound for
  /// many targets (a search for the target timestep), the same result as forming it at each call.
  template <class Factor>
  double density_scaling_mass(double target_dt, Factor timestep_factor, const FrequencyBound& bound) const;

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
  void restore_real_masses();

  /// Whether the masses are those of scale_masses_for_statics() (not yet restored).
  bool static_masses() const { return static_masses_; }

  /// Density scaling factor m_scaled / m_real of every node (the VTK field `density_scaling_factor`).
  std::vector<double> density_scaling_factors() const {
    const auto& nd = model_->deformable.nodes;
    std::vector<double> f(nd.size());
    for (std::size_t i = 0; i < nd.size(); ++i) f[i] = nd.density_scaling_factor(i);
    return f;
  }

  /// Sets the timestep (s). Throws InvalidArgument if it exceeds the critical timestep, unless unchecked.
  void set_timestep(double dt, TimestepCheck check = TimestepCheck::checked);

  /// closure_inverse_omega_squared() for the present contacts, masses and timestep.
  void refresh_closure_bound() { set_closure_bound(bounded_frequency() ? omega_max() : 0.0); }
  /// The same from omega_max already computed (0: none, or static masses).
  void set_closure_bound(double omega) {
    const double half_step = 0.5 * dt_;
    closure_inverse_omega_squared_ = omega > 0 && std::isfinite(omega) ? 1.0 / (omega * omega) : half_step * half_step;
  }

  /// The bounds a run must stay within (RunGuard): a velocity, traction or stress that is not finite, a speed above
  /// guard.max_speed or an overlap deeper than guard.max_overlap times the contact's size stops step() with
  /// RunawayError naming the block, node, element or contact point and the component.
  void set_run_guard(const RunGuard& guard) {
    guard.validate();
    guard_ = guard;
  }
  const RunGuard& run_guard() const { return guard_; }

  /// Called at every re-detection, before the contacts are detected again (the histories are then at the present
  /// positions): what output must remember of the contact points about to be dropped or replaced (a study's damage
  /// memory) is read there. Empty: nothing is called.
  void set_detection_observer(std::function<void()> observer) { detection_observer_ = std::move(observer); }

  /// The frame in which mass-proportional damping (and Rayleigh's mass term) measures velocities: the table's (the
  /// default) or the ground's (damping/frame.hpp). Other policies ignore it.
  void set_damping_frame(damping::Frame frame) { damping_frame_ = frame; }
  damping::Frame damping_frame() const { return damping_frame_; }

  /// What holding the timestep against new contacts has done so far (see TimestepHold).
  const TimestepHold& timestep_hold() const { return hold_; }

  // ---- state ----

  double timestep() const { return dt_; }
  /// 1 / omega^2 (s^2) for the laws' closure impulse (contact/closure_impulse.hpp): omega the upper bound on
  /// omega_max of the present contacts and masses (FrequencyBound), taken when the timestep is set and after every
  /// re-detection (the only moments the contacts or the masses change); 2 / dt (stability alone) under static
  /// masses, whose estimate is no bound, or while no block has a contact.
  double closure_inverse_omega_squared() const { return closure_inverse_omega_squared_; }
  double time() const { return time_; }
  long long steps() const { return steps_; }
  const model::Model& model() const { return *model_; }
  model::Model& model() { return *model_; }
  const Damping& damping() const { return damping_; }
  const model::ContactSettings& contact_settings() const { return settings_; }
  int detections() const { return detections_; }
  /// Wall time (s) spent detecting the contacts again and assigning them during the steps of this object (not the
  /// first detection, nor those before a checkpoint it was loaded from).
  double detection_seconds() const { return detection_seconds_; }
  /// Whether the model has deformable blocks, trusses or scaled rigid blocks (the mixed step runs).
  bool mixed() const { return mixed_; }
  const DeformableState<Damping, Laws...>& deformable_state() const { return deformable_; }

  std::size_t contact_points() const {
    std::size_t n = 0;
    for_each_group([&](const auto& g) { n += g.size(); });
    if (mixed_) n += deformable_.contact_points();
    return n;
  }

  template <contact::ContactLaw L>
  const auto& group() const { return std::get<ContactGroup<L, Damping>>(groups_); }
  template <contact::ContactLaw L>
  auto& group() { return std::get<ContactGroup<L, Damping>>(groups_); }

  // ---- output (integrate/contact_view.hpp) and energy (integrate/energy.hpp) ----

  /// Calls f(block_a, block_b, const History&), or f(block_a, block_b, std::type_identity<Law>, const History&), for
  /// every contact point: the block contacts, then the node contacts of deformable blocks (block_a: the node's block).
  template <class F>
  void visit_contact_histories(F&& f) const { blockdem::visit_contact_histories(groups_, deformable(), f); }

  /// Calls f(const ContactView&) for every contact point, group by group.
  template <class F>
  void visit_contacts(F&& f) const { blockdem::visit_contacts(*model_, groups_, deformable(), f); }

  EnergyReport energy() const { return with_balance(energy_terms(), energy0_); }

  /// Sum of |unbalanced force| over sum of |applied force| (the real weights) of the free blocks and nodes.
  double unbalanced_force_ratio() const { return blockdem::unbalanced_force_ratio(*model_, *real_masses().mass); }

  /// Steps until the unbalanced-force ratio is at most `tolerance` (checked every 10 steps) or `max_steps` are
  /// done. Returns true if the tolerance was met. Meant for a simulation with damping::Local.
  bool solve_to_equilibrium(double tolerance = 1e-5, long long max_steps = 1000000) {
    for (long long n = 0; n < max_steps; ++n) {
      step();
      if (n % 10 == 9 && unbalanced_force_ratio() <= tolerance) return true;
    }
    return unbalanced_force_ratio() <= tolerance;
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
    if (mixed_) deformable_.build_thread_ranges(*model_);
    update_redetection_distances();
  }

 private:
  template <damping::DampingPolicy, contact::ContactLaw...>
  friend class Simulation;

  using Groups = std::tuple<ContactGroup<Laws, Damping>...>;

  /// The step, specialised at compile time: the rigid-only instantiation is the rigid kernel exactly; the mixed
  /// one adds the node contacts, elements and trusses, the extra forces on rigid blocks and the node pass. The mixed
  /// step is kept out of line so that it does not change how the compiler inlines the rigid one.
  [[gnu::noinline]] void mixed_step() { step_impl<true>(); }

  template <bool Mixed>
  void step_impl() {
    // The increment of the positions since the last step is the move the last step made (its timestep; the present
    // one unless set since).
    const double increment_dt = pending_increment_ ? move_timestep() : 0.0;
    const double inverse_omega_squared = closure_inverse_omega_squared();
    for_each_group([&](auto& g) { contact_pass(g, model_->bodies, damping_, increment_dt, inverse_omega_squared); });
    if constexpr (Mixed) mixed_forces(increment_dt);
    // Joint histories are now at the current positions: the moment to detect contacts again if blocks have moved
    // (relative to the base) by more than the redetection distance. Forces of the new set, then the block pass.
    if (++steps_since_check_ >= settings_.redetection_check_interval) {
      steps_since_check_ = 0;
      if (moved_since_detection_) redetect_and_update<Mixed>();
    }
    // A step with another timestep than the move before it (set_timestep() between steps, the hold after a
    // re-detection): the scheme's kinetic energy 1/2 m v(n-1/2).v(n+1/2) changes its measure with it (energy.hpp,
    // half_step_kinetic); the change is booked with the model's other changes, as what the balance must not count.
    const bool timestep_changed = increment_dt > 0.0 && dt_ != increment_dt && !energy_reference_pending_;
    const double half_step = timestep_changed ? half_step_kinetic(*model_) : 0.0;
    run_block_pass<Mixed>(increment_dt, /*move=*/true);
    if constexpr (Mixed) {
      const bool nodes_moved =
          node_pass(deformable_, *model_, damping_, dt_, increment_dt, true, settings_.redetection(), frame_velocity(increment_dt));
      moved_since_detection_ = moved_since_detection_ || nodes_moved;
    }
    if (timestep_changed) [[unlikely]]
      contact_update_ += (1.0 - increment_dt / dt_) * (free_kinetic() - half_step);
    last_move_dt_ = dt_;
    // The scheme conserves 1/2 m v(n-1/2).v(n+1/2) + U(x_n): the reference is its value at the first step.
    if (energy_reference_pending_) {
      energy0_ = energy_terms();
      energy_reference_pending_ = false;
    }
    pending_increment_ = true;
    time_ += dt_;
    ++steps_;
    if (++steps_since_guard_ >= guard_.check_interval) {
      steps_since_guard_ = 0;
      check_run(*model_, groups_, deformable(), guard_, time_, steps_);
    }
  }

  /// Node contacts, elements, trusses, then what they apply to rigid blocks.
  void mixed_forces(double increment_dt) {
    deformable_forces(deformable_, *model_, damping_, increment_dt, closure_inverse_omega_squared());
    truss_pass(deformable_, *model_);
    gather_rigid(deformable_, *model_, increment_dt);
  }

  /// The velocity of the damping's frame around the present step: the table's at t - dt/2 (the move that led here;
  /// at the first step, none: the table's next) and t + dt/2; zero in the ground's frame, or for a policy that has
  /// no mass-proportional term.
  damping::FrameVelocity frame_velocity(double increment_dt) const {
    damping::FrameVelocity f;
    if constexpr (damping::damps_velocities<Damping>()) {
      if (damping_frame_ == damping::Frame::table) {
        f.after = model_->base_velocity(time_ + 0.5 * dt_);
        f.before = increment_dt > 0.0 ? model_->base_velocity(time_ - 0.5 * increment_dt) : f.after;
      }
    }
    (void)increment_dt;
    return f;
  }

  template <bool Mixed>
  void run_block_pass(double increment_dt, bool move) {
    const ExtraForces extra = Mixed ? ExtraForces{deformable_.extra_force.data(), deformable_.extra_moment.data()} : ExtraForces{};
    const damping::FrameVelocity frame = move ? frame_velocity(increment_dt) : damping::FrameVelocity{};
    const bool moved = block_pass<Mixed>(*model_, blocks_, groups_, damping_, extra, time_, dt_, increment_dt, move, frame);
    moved_since_detection_ = moved_since_detection_ || moved;
  }

  /// Detects the contacts again and computes the forces of the new set. The discrete model changes here: CPs of a
  /// re-drawn joint that start at the closure of the joint's point they inherit, CPs dropped while loaded, CPs whose
  /// tributary area changed (CPs found in overlap start touching: integrate/contact_history.hpp). The energy stored
  /// in the contacts that this adds or removes is done by no force; it is kept as its own term of the balance
  /// (EnergyReport::contact_update), measured, not inferred from the residual.
  template <bool Mixed>
  void redetect_and_update();

  /// After a re-detection of a dynamic run: the new contact points may have raised omega_max (eq. 1) above what
  /// the timestep allows. A density-scaled run (scale_density_to) keeps its timestep and raises, by the same rule
  /// and safety factor, the masses of the free nodes and rigid blocks whose row of FrequencyBound now exceeds the
  /// target, at their present velocities (the kinetic energy this adds is a change of the model, kept in the
  /// balance's contact_update term); any other run with a checked timestep keeps its margin dt / dt_critical by
  /// lowering the timestep. Without this, one stiff new contact point at a light node diverges in a few steps.
  /// Returns omega_max() after the hold (0 under static masses), from one FrequencyBound unless it raised masses.
  double hold_timestep();

  /// The mass (kg) a plan adds to the present masses (negative where it lowers them).
  double added_mass(const MassPlan& plan) const;

  /// The mass scaling of scale_density_to() and scale_masses_for_statics(), by `rule`.
  DensityScaling scale_masses(double target_dt, double safety_factor, MassRule rule);

  /// The deformable state for the passes that read it, null while the rigid kernel runs.
  const DeformableState<Damping, Laws...>* deformable() const { return mixed_ ? &deformable_ : nullptr; }

  /// The rigid blocks' real masses and inertias (only the mixed step keeps them apart from the present ones).
  RealMasses real_masses() const {
    return mixed_ ? RealMasses{&deformable_.rigid_real_mass, &deformable_.rigid_real_inertia}
                  : RealMasses{&model_->bodies.mass, &model_->bodies.principal_inertia};
  }

  /// Whether a rigid block's mass or inertia differs from its real one (only the mixed step keeps the real ones).
  bool scaled_rigid_blocks() const {
    if (!mixed_) return false;
    const auto& b = model_->bodies;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.mass[i] != deformable_.rigid_real_mass[i] || b.principal_inertia[i] != deformable_.rigid_real_inertia[i]) return true;
    return false;
  }

  /// The timestep of the last step's move (the present one before any step).
  double move_timestep() const { return last_move_dt_ > 0.0 ? last_move_dt_ : dt_; }

  /// The scheme's kinetic energy at the present step, of the free blocks and the nodes.
  double free_kinetic() const {
    const auto& b = model_->bodies;
    double sum = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.motion[i] == model::Motion::free) sum += blocks_.kinetic[i];
    if (mixed_)
      for (const double k : deformable_.node_kinetic) sum += k;
    return sum;
  }

  EnergyReport energy_terms() const {
    EnergyReport e;
    e.slip = retired_slip_;
    e.viscous = retired_viscous_;
    e.contact_update = contact_update_;
    add_block_energy(blocks_, e);
    add_contact_energy(groups_, damping_, e);
    if (mixed_) {
      const auto d = deformable_.energy(*model_, damping_);
      e.kinetic += d.kinetic;
      e.elastic += d.elastic;
      e.gravity_work += d.gravity_work;
      e.base_work += d.base_work;
      e.viscous += d.viscous;
      e.slip += d.slip;
    }
    return e;
  }

  // ---- contact assignment (integrate/contact_assignment.hpp, integrate/node_contact_assignment.hpp) ----

  /// Rigid-rigid pairs to the rigid groups, pairs with a deformable block to the node groups.
  void assign_all(const std::vector<model::ContactCandidate>& candidates, bool keep_history);
  /// The rigid-rigid contacts of a detection; the poses it was made at.
  void assign_contacts(const std::vector<model::ContactCandidate>& candidates, bool keep_history);
  /// The joint's properties for a pair of joint tags, asked of the property function once per pair.
  Properties choose_properties(int ta, int tb);
  /// Per block, how far it may move before the contacts are detected again (model::redetection_distances), from
  /// the poses at the last detection, so that a loaded checkpoint gets the same distances.
  void update_redetection_distances();

  void resize_block_arrays() {
    blocks_.reset(model_->bodies);
    update_redetection_distances();
  }

  template <class F>
  void for_each_group(F&& f) { for_each_in(groups_, f); }
  template <class F>
  void for_each_group(F&& f) const { for_each_in(groups_, f); }

  /// The one list of the saved fields, for both directions. Not saved: model_ (the caller's model, whose state is
  /// saved in its place); properties_ and settings_ (the description: the constructor's arguments);
  /// chosen_properties_ (a memo of properties_, filled again identically); the blocks' radii (from the shapes) and
  /// redetection distances (from the poses at the last detection); the assignments' scratch. The damping policy is
  /// saved whole: its parameters and the constants of prepare(dt).
  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar);

  model::Model* model_;
  Damping damping_;
  damping::Frame damping_frame_ = damping::Frame::table;
  bool mixed_ = false;
  DeformableState<Damping, Laws...> deformable_;
  std::map<std::pair<int, int>, Properties> chosen_properties_;
  PropertyFunction properties_;
  model::ContactSettings settings_;
  std::function<void()> detection_observer_;
  Groups groups_;
  BlockState blocks_;
  ContactAssignment<Damping, Laws...> assignment_;
  NodeContactAssignment<Damping, Laws...> node_assignment_;
  double dt_ = 0;
  double time_ = 0;
  long long steps_ = 0;
  int steps_since_check_ = 0;
  RunGuard guard_;
  int steps_since_guard_ = 0;  // (not in checkpoints: when the checks fall changes no result)
  int detections_ = 0;
  double detection_seconds_ = 0;
  bool pending_increment_ = false;
  bool moved_since_detection_ = false;
  bool static_masses_ = false;  // scale_masses_for_statics() until restore_real_masses()
  double density_safety_ = 0;   // the safety factor of scale_density_to() while its masses hold; 0: not density-scaled
  double timestep_margin_ = 0;  // dt / dt_critical when the timestep was set (checked); 0: unchecked
  double closure_inverse_omega_squared_ = 0;  // s^2, see closure_inverse_omega_squared()
  TimestepHold hold_;
  EnergyReport energy0_;
  bool energy_reference_pending_ = true;
  double retired_slip_ = 0, retired_viscous_ = 0;  // J, dissipated at CPs that no longer exist
  double contact_update_ = 0;  // J, energy stored in the contacts that re-detection added (redetect_and_update)
  double last_move_dt_ = 0;    // s, the timestep of the last step's move (0: none yet)
};

}  // namespace blockdem

// The members' definitions by job: the timestep and the masses (density scaling, static mass scaling, the hold),
// and the checkpoint state.
#include "blockdem/integrate/simulation_contacts.hpp"
#include "blockdem/integrate/simulation_masses.hpp"
#include "blockdem/integrate/simulation_state.hpp"
