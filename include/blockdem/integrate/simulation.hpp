#pragma once
// The explicit central-difference integrator (paper Sect. 3.1, DESIGN.md §4). One Simulation type per damping
// policy and list of joint laws: every step is one fused pass over the contact points of each law (relative
// velocity -> law -> damping -> force) and one pass over the blocks (gather in a fixed order -> gravity -> damped
// velocity update -> position and orientation), each specialised at compile time, with no virtual call and no
// branch on the policy. Results do not depend on the number of OpenMP threads.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/contact_group.hpp"
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
  double balance_error = 0; // |change of (kinetic + elastic + viscous + slip) - work| / the largest term
};

enum class TimestepCheck { checked, unchecked };

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
    std::pair<std::pair<std::size_t, std::size_t>, double> deepest;
    const auto candidates = model::detect_contacts(model.bodies, settings_, &deepest);
    if (deepest.second < -settings_.tolerance)
      throw InvalidArgument("blocks '" + model.bodies.name[deepest.first.first] + "' and '" +
                            model.bodies.name[deepest.first.second] + "' interpenetrate by " +
                            std::to_string(-deepest.second) + " m, more than the contact tolerance " +
                            std::to_string(settings_.tolerance) + " m");
    assign_contacts(candidates, /*keep_history=*/false);
    pending_increment_ = false;
    set_timestep(default_timestep());
  }

  /// Continues from another simulation of the same model with another damping policy (for example after static
  /// equilibrium under local damping): block state and joint histories are kept, damping state starts at zero.
  template <damping::DampingPolicy Other>
  Simulation(Simulation<Other, Laws...>& other, Damping damping)
      : model_(other.model_), damping_(damping), properties_(other.properties_), settings_(other.settings_) {
    other.synchronize();
    resize_block_arrays();
    copy_groups(other, std::index_sequence_for<Laws...>{});
    time_ = other.time_;
    set_timestep(std::min(other.dt_, default_timestep()));
  }

  /// Eq. 1 is exact for one block on its joints but not an upper bound for chains of blocks; hence a margin.
  static constexpr double default_safety_factor = 0.5;

  /// The safety factor times the critical timestep; 1e-4 s while no block has a contact.
  double default_timestep() const {
    const double critical = critical_timestep();
    return std::isfinite(critical) ? default_safety_factor * critical : 1e-4;
  }

  // ---- timestep (eq. 1-3, 11, 20) ----

  /// Critical timestep 2 / omega_max (eq. 1) with omega_max = max over free blocks of sqrt(k / m) for translation
  /// and sqrt(k r^2 / I_min) for rotation, k the sum of max(k_n, k_s) A of the block's contact points (eq. 2-3),
  /// times the damping policy's factor (eq. 11, eq. 20). Infinite if no free block has a contact.
  double critical_timestep() const {
    const auto& b = model_->bodies;
    std::vector<double> k_translation(b.size(), 0.0), k_rotation(b.size(), 0.0);
    for_each_group([&](const auto& g) {
      using L = typename std::remove_cvref_t<decltype(g)>::LawType;
      for (std::size_t k = 0; k < g.size(); ++k) {
        const auto& p = g.properties[g.property[k]];
        const double stiffness = std::max(L::normal_stiffness(p), L::shear_stiffness(p)) * g.area[k];
        k_translation[g.body_a[k]] += stiffness;
        k_translation[g.body_b[k]] += stiffness;
        k_rotation[g.body_a[k]] += stiffness * g.arm_a[k].squaredNorm();
        k_rotation[g.body_b[k]] += stiffness * g.arm_b[k].squaredNorm();
      }
    });
    double omega_max = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free) continue;
      if ((b.fixity[i] & 7) != 7) omega_max = std::max(omega_max, std::sqrt(k_translation[i] / b.mass[i]));
      if ((b.fixity[i] & model::Fixity::all_rotations) != model::Fixity::all_rotations)
        omega_max = std::max(omega_max, std::sqrt(k_rotation[i] / b.principal_inertia[i].minCoeff()));
    }
    if (omega_max == 0) return std::numeric_limits<double>::infinity();
    return 2.0 / omega_max * damping_.timestep_factor(omega_max);
  }

  /// Sets the timestep (s). Throws InvalidArgument if it exceeds the critical timestep, unless unchecked.
  void set_timestep(double dt, TimestepCheck check = TimestepCheck::checked) {
    const double critical = critical_timestep();
    if (!(dt > 0) || !std::isfinite(dt))
      throw InvalidArgument("timestep must be > 0 s and finite, got " + std::to_string(dt));
    if (check == TimestepCheck::checked && dt > critical)
      throw InvalidArgument("timestep " + std::to_string(dt) + " s exceeds the critical timestep " +
                            std::to_string(critical) + " s (eq. 1 with the damping factor of eq. 11/20)");
    dt_ = dt;
    if constexpr (requires(Damping& d) { d.prepare(dt); }) damping_.prepare(dt_);
  }

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
    double damage = 0;    // 0 intact .. 1 failed (laws without damage: 1 once failed)
    std::size_t block_a = 0, block_b = 0;
  };

  /// Calls f(const ContactView&) for every contact point, group by group.
  template <class F>
  void visit_contacts(F&& f) const {
    const auto& b = model_->bodies;
    for_each_group([&](const auto& g) {
      for (std::size_t k = 0; k < g.size(); ++k) {
        ContactView v;
        const std::size_t a = g.body_a[k], bb = g.body_b[k];
        v.block_a = a;
        v.block_b = bb;
        v.position = 0.5 * (b.position[a] + b.rotation[a] * g.arm_a[k] + b.position[bb] + b.rotation[bb] * g.arm_b[k]);
        v.normal = b.rotation[a] * g.normal_a[k];
        v.force = g.force[k];
        v.area = g.area[k];
        const auto& h = g.history[k];
        v.gap = h.gap;
        v.normal_stress = v.force.dot(v.normal) / v.area;
        v.shear_stress = (v.force - v.force.dot(v.normal) * v.normal).norm() / v.area;
        if constexpr (requires { h.damage; }) v.damage = h.damage;
        else if constexpr (requires { h.failed; }) v.damage = h.failed ? 1.0 : 0.0;
        f(v);
      }
    });
  }

  // ---- the step ----

  void step() {
    const double increment_dt = pending_increment_ ? dt_ : 0.0;
    for_each_group([&](auto& g) { contact_pass(g, increment_dt); });
    // Joint histories are now at the current positions: the moment to detect contacts again if blocks have moved
    // (relative to the base) by more than the redetection distance. Forces of the new set, then the block pass.
    if (++steps_since_check_ >= settings_.redetection_check_interval) {
      steps_since_check_ = 0;
      if (moved_beyond_redetection_distance()) {
        assign_contacts(model::detect_contacts(model_->bodies, settings_), /*keep_history=*/true);
        for_each_group([&](auto& g) { contact_pass(g, 0.0); });
      }
    }
    block_pass(increment_dt);
    // The scheme conserves 1/2 m v(n-1/2).v(n+1/2) + U(x_n): the reference is its value at the first step.
    if (energy_reference_pending_) {
      energy0_ = energy_terms();
      energy_reference_pending_ = false;
    }
    pending_increment_ = true;
    time_ += dt_;
    ++steps_;
  }

  /// Reverses the motion exactly (up to rounding): after n more steps the blocks are back where they were n steps
  /// ago, with velocities negated. For time-reversibility checks of the scheme.
  void reverse() {
    synchronize();
    for_each_group([&](auto& g) { contact_pass(g, 0.0); });
    auto& b = model_->bodies;
    // v(n+1/2) = v(n-1/2) + dt F(x_n) / m, then negate: the leapfrog run backwards from x_n.
    block_pass(0.0, /*move=*/false);
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
    pending_increment_ = false;
  }

  // ---- energy ----

  EnergyReport energy() const {
    EnergyReport e = energy_terms();
    const double change = (e.kinetic + e.elastic + e.viscous + e.slip) - (energy0_.kinetic + energy0_.elastic) -
                          (e.gravity_work + e.base_work);
    const double scale = std::max({std::abs(e.gravity_work) + std::abs(e.base_work), e.kinetic + e.elastic + e.viscous + e.slip,
                                   energy0_.kinetic + energy0_.elastic, 1e-300});
    e.balance_error = std::abs(change) / scale;
    return e;
  }

  /// Sum of |unbalanced force| over sum of |applied force| (gravity and contact forces) of the free blocks.
  double unbalanced_force_ratio() const {
    const auto& b = model_->bodies;
    double unbalanced = 0, applied = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free) continue;
      unbalanced += b.force[i].norm();
      applied += b.mass[i] * model_->gravity.norm();
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
    const auto candidates = model::detect_contacts(model_->bodies, settings_);
    assign_contacts(candidates, /*keep_history=*/true);
    pending_increment_ = false;
  }

 private:
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
    radius_.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (const auto& v : model_->bodies.shape[i].vertices) radius_[i] = std::max(radius_[i], v.norm());
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

  /// Displacement relative to the base motion since the last detection (a structure riding on the table needs no
  /// new contacts), plus rotation times the block's radius.
  bool moved_beyond_redetection_distance() const {
    const auto& b = model_->bodies;
    const double limit = settings_.redetection();
    const Vec3 base_moved = base_displacement_ - detected_base_displacement_;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free) continue;
      // 2 |vector part of q q0^-1| = angle for small angles, without acos.
      const double angle = 2.0 * (b.orientation[i] * detected_orientation_[i].conjugate()).vec().norm();
      if ((b.position[i] - detected_position_[i] - base_moved).norm() + angle * radius_[i] > limit) return true;
    }
    return false;
  }

  template <contact::ContactLaw L>
  static constexpr std::size_t law_index() {
    constexpr bool same[] = {std::is_same_v<L, Laws>...};
    for (std::size_t i = 0; i < sizeof...(Laws); ++i)
      if (same[i]) return i;
    return sizeof...(Laws);
  }

  /// Distributes detected CPs over the groups; with keep_history, a CP within the matching distance of an old CP
  /// of the same block pair takes over its history and damping state.
  void assign_contacts(const std::vector<model::ContactCandidate>& candidates, bool keep_history) {
    const auto& b = model_->bodies;
    Groups old = std::move(groups_);
    groups_ = Groups{};
    // Property sets are kept (CP property indices stay valid); new ones are appended.
    std::apply([&](auto&... g) { ((g.properties = std::get<std::remove_cvref_t<decltype(g)>>(old).properties), ...); }, groups_);
    const double match = std::max(settings_.tolerance, 0.25 * std::sqrt(settings_.max_contact_point_area));
    // Energy dissipated at CPs that will not be taken over is kept in the totals.
    std::apply([&](auto&... g) { ((taken_over_[law_index<typename std::remove_cvref_t<decltype(g)>::LawType>()].assign(g.size(), 0)), ...); }, old);
    double carried_slip = 0, carried_viscous = 0, old_slip = 0, old_viscous = 0;
    std::apply([&](const auto&... g) {
      ((old_slip += std::accumulate(g.slip_dissipation.begin(), g.slip_dissipation.end(), 0.0),
        old_viscous += std::accumulate(g.viscous_dissipation.begin(), g.viscous_dissipation.end(), 0.0)), ...);
    }, old);
    std::map<std::pair<int, int>, Properties> chosen;
    for (const auto& c : candidates) {
      const int ta = b.joint_tag[c.a], tb = b.joint_tag[c.b];
      auto it = chosen.find({ta, tb});
      if (it == chosen.end()) it = chosen.emplace(std::make_pair(ta, tb), properties_(ta, tb)).first;
      std::visit([&](const auto& params) { add_contact(params, c, old, keep_history, match, carried_slip, carried_viscous); }, it->second);
    }
    retired_slip_ += old_slip - carried_slip;
    retired_viscous_ += old_viscous - carried_viscous;
    for_each_group([&](auto& g) { g.build_gather_lists(b.size()); });
    detected_position_ = b.position;
    detected_orientation_ = b.orientation;
    detected_base_displacement_ = base_displacement_;
    ++detections_;
  }

  template <class Params>
  void add_contact(const Params& params, const model::ContactCandidate& c, Groups& old, bool keep_history, double match,
                   double& carried_slip, double& carried_viscous) {
    using L = std::tuple_element_t<index_of_parameters<Params>(), std::tuple<Laws...>>;
    auto& g = std::get<Group<L>>(groups_);
    const auto& b = model_->bodies;
    // Property index: reuse an identical parameter set.
    std::size_t p = 0;
    while (p < g.properties.size() && !(g.properties[p] == params)) ++p;
    if (p == g.properties.size()) {
      if (p >= 65535) throw InvalidArgument("simulation: more than 65535 different contact property sets");
      g.properties.push_back(params);
    }
    const Mat3& ra = b.rotation[c.a];
    const Mat3& rb = b.rotation[c.b];
    g.body_a.push_back(static_cast<std::uint32_t>(c.a));
    g.body_b.push_back(static_cast<std::uint32_t>(c.b));
    g.property.push_back(static_cast<std::uint16_t>(p));
    g.arm_a.push_back(ra.transpose() * (c.position - b.position[c.a]));
    g.arm_b.push_back(rb.transpose() * (c.position - b.position[c.b]));
    g.normal_a.push_back(ra.transpose() * c.normal);
    g.tangent_a.push_back(ra.transpose() * c.tangent);
    g.area.push_back(c.area);
    typename L::History h{};
    h.gap = c.gap;
    typename Group<L>::SpringState spring{};
    double slip = 0, viscous = 0;
    if (keep_history) {
      const auto& o = std::get<Group<L>>(old);
      auto& taken = taken_over_[law_index<L>()];
      for (std::size_t k = 0; k < o.size(); ++k) {
        if (taken[k] || o.body_a[k] != c.a || o.body_b[k] != c.b) continue;
        // The old CP's material points on A and on B have drifted apart by the slip since the last detection; the
        // new CP sits at a vertex of one of the two faces, so it is near one of them within the contact plane
        // (along the normal they differ by the overlap).
        auto in_plane = [&](const Vec3& d) { return (d - d.dot(c.normal) * c.normal).norm(); };
        const Vec3 on_a = b.position[c.a] + ra * o.arm_a[k];
        const Vec3 on_b = b.position[c.b] + rb * o.arm_b[k];
        if (std::min(in_plane(on_a - c.position), in_plane(on_b - c.position)) > match) continue;
        taken[k] = 1;
        h = o.history[k];
        spring = o.spring_state[k];
        slip = o.slip_dissipation[k];
        viscous = o.viscous_dissipation[k];
        carried_slip += slip;
        carried_viscous += viscous;
        // Shear components follow the new tangent directions.
        if constexpr (requires { h.shear; }) {
          const Vec3 t1_old = ra * o.tangent_a[k];
          const Vec3 t2_old = (ra * o.normal_a[k]).cross(t1_old);
          const Vec3 shear = h.shear[0] * t1_old + h.shear[1] * t2_old;
          const Vec3 t2_new = c.normal.cross(c.tangent);
          h.shear = {shear.dot(c.tangent), shear.dot(t2_new)};
        }
        break;
      }
    }
    g.history.push_back(h);
    g.spring_state.push_back(spring);
    g.force.push_back(Vec3::Zero());
    g.slip_dissipation.push_back(slip);
    g.viscous_dissipation.push_back(viscous);
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
    to.arm_a = from.arm_a;
    to.arm_b = from.arm_b;
    to.normal_a = from.normal_a;
    to.tangent_a = from.tangent_a;
    to.area = from.area;
    to.history = from.history;
    to.spring_state.assign(from.size(), typename To::SpringState{});
    to.force = from.force;
    to.slip_dissipation.assign(from.size(), 0.0);
    to.viscous_dissipation.assign(from.size(), 0.0);
    to.build_gather_lists(model_->bodies.size());
  }

  /// The fused contact loop of one law: relative displacement increment -> law -> damping -> force and moments.
  template <class G>
  void contact_pass(G& g, double increment_dt) {
    using L = typename G::LawType;
    auto& b = model_->bodies;
    // Raw restrict pointers: the stores of one CP cannot alias the arrays read for the next, so the compiler keeps
    // the array addresses in registers instead of reloading them after every store.
    const Mat3* __restrict const rotation = b.rotation.data();
    const Vec3* __restrict const velocity = b.velocity.data();
    const Vec3* __restrict const omega = b.angular_velocity.data();
    const std::uint32_t* __restrict const body_a = g.body_a.data();
    const std::uint32_t* __restrict const body_b = g.body_b.data();
    const std::uint16_t* __restrict const property = g.property.data();
    const Vec3* __restrict const arm_a_local = g.arm_a.data();
    const Vec3* __restrict const arm_b_local = g.arm_b.data();
    const Vec3* __restrict const normal_local = g.normal_a.data();
    const Vec3* __restrict const tangent_local = g.tangent_a.data();
    const double* __restrict const area_of = g.area.data();
    const auto* __restrict const properties = g.properties.data();
    auto* __restrict const history = g.history.data();
    auto* __restrict const spring_state = g.spring_state.data();
    Vec3* __restrict const force = g.force.data();
    double* __restrict const slip_dissipation = g.slip_dissipation.data();
    double* __restrict const viscous_dissipation = g.viscous_dissipation.data();
    const auto count = static_cast<std::ptrdiff_t>(g.size());
    const Damping& damping = damping_;
#pragma omp parallel for schedule(static) if (count > 1024)
    for (std::ptrdiff_t kk = 0; kk < count; ++kk) {
      const auto k = static_cast<std::size_t>(kk);
      const std::uint32_t a = body_a[k];
      const std::uint32_t bb = body_b[k];
      const Mat3& ra = rotation[a];
      const Vec3 arm_a = ra * arm_a_local[k];
      const Vec3 arm_b = rotation[bb] * arm_b_local[k];
      const Vec3 n = ra * normal_local[k];
      const Vec3 t1 = ra * tangent_local[k];
      const Vec3 t2 = n.cross(t1);
      // The last move (velocities v(n-1/2)) is measured with the arms and directions half a rotation back, at the
      // middle of the move: the same move run backwards then gives exactly the opposite increment (to third order).
      // With h = -dt/2 w: w x (arm + h x arm) = c - dt/2 w x c, c = w x arm; and du . (x + h_a x x) = x . (du + du x h_a).
      const Vec3 ca = omega[a].cross(arm_a);
      const Vec3 cb = omega[bb].cross(arm_b);
      const double half_dt = 0.5 * increment_dt;
      const Vec3 relative = (velocity[bb] + cb - half_dt * omega[bb].cross(cb)) - (velocity[a] + ca - half_dt * omega[a].cross(ca));
      const Vec3 du_move = relative * increment_dt;
      const Vec3 du = du_move - half_dt * du_move.cross(omega[a]);
      const double du_n = du.dot(n);
      const contact::Shear du_s{du.dot(t1), du.dot(t2)};
      const auto& p = properties[property[k]];
      const contact::Response r = L::update(p, history[k], du_n, du_s);
      const bool active = L::damping_active(p, history[k]);
      const double kn = L::normal_stiffness(p);
      const double ks = L::shear_stiffness(p);
      double dissipated = 0.0;
      auto& spring = spring_state[k];
      // Spring elongations in the sense of the stresses: closing the gap compresses, shear stress opposes du_s.
      const double sn = r.normal_stress + damping.spring_stress(spring[0], kn, -du_n, increment_dt, active, dissipated);
      const double s1 = r.shear_stress[0] + damping.spring_stress(spring[1], ks, -du_s[0], increment_dt, active, dissipated);
      const double s2 = r.shear_stress[1] + damping.spring_stress(spring[2], ks, -du_s[1], increment_dt, active, dissipated);
      const double area = area_of[k];
      force[k] = area * (sn * n + s1 * t1 + s2 * t2);
      // Only what can be non-zero is stored: a law or a policy that never dissipates costs no memory traffic here.
      if constexpr (!std::is_same_v<L, contact::Elastic>) slip_dissipation[k] += area * r.dissipated;
      if constexpr (!std::is_same_v<typename Damping::ContactState, damping::NoState>)
        viscous_dissipation[k] += area * dissipated;
    }
  }

  /// Gather, gravity, damped velocity update, position and orientation update, for every block.
  void block_pass(double increment_dt, bool move = true) {
    auto& b = model_->bodies;
    const auto count = static_cast<std::ptrdiff_t>(b.size());
    const double dt = dt_;
    const Vec3 gravity = model_->gravity;
    const Vec3 base_velocity = model_->base_velocity(time_ + 0.5 * dt);
    if (move) base_displacement_ += dt * base_velocity;
    const Damping& damping = damping_;
#pragma omp parallel for schedule(static) if (count > 1024)
    for (std::ptrdiff_t ii = 0; ii < count; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      // Gather in a fixed order. Moments about the centroid come from the CP's arm in this block's body frame:
      // sum_k (arm_k x f_k) = R sum_k (arm_k x R^T f_k), one rotation per block instead of one per CP.
      Vec3 force = Vec3::Zero();
      Vec3 moment_body = Vec3::Zero();
      const Mat3 rt = b.rotation[i].transpose();
      for_each_group([&](const auto& g) {
        for (std::uint32_t e = g.first[i]; e < g.first[i + 1]; ++e) {
          const std::uint32_t code = g.entry[e];
          const std::uint32_t k = code >> 1;
          const Vec3 f = (code & 1u) ? Vec3(g.force[k]) : Vec3(-g.force[k]);
          force += f;
          moment_body += ((code & 1u) ? g.arm_b[k] : g.arm_a[k]).cross(rt * f);
        }
      });
      const Vec3 moment = b.rotation[i] * moment_body;
      const model::Motion motion = b.motion[i];
      if (motion == model::Motion::base) {
        b.force[i] = force;
        b.moment[i] = moment;
        if (!move) continue;
        base_work_[i] -= force.dot(b.velocity[i]) * increment_dt;  // the move that led to x_n, against `force`
        b.velocity[i] = base_velocity;
        b.angular_velocity[i].setZero();
        b.position[i] += dt * base_velocity;
        continue;
      }
      if (motion == model::Motion::fixed) {
        b.force[i] = force;
        b.moment[i] = moment;
        continue;
      }
      const double m = b.mass[i];
      force += m * gravity;
      b.force[i] = force;
      b.moment[i] = moment;
      const std::uint8_t fixity = b.fixity[i];
      const Vec3 v_old = b.velocity[i];
      Vec3 v = v_old;
      double dissipated = 0.0;
      for (int c = 0; c < 3; ++c)
        v[c] = (fixity & (1u << c)) ? 0.0 : damping.velocity_update(v_old[c], force[c], m, dt, dissipated);
      // Rotation in the principal frame (Euler's equations). The gyroscopic term is taken at the mid-step angular
      // velocity (implicit midpoint, two fixed-point passes: dt |w| is tiny), which keeps the scheme time reversible.
      const Mat3& r = b.rotation[i];
      const Vec3& inertia = b.principal_inertia[i];
      const Vec3 w_old_body = r.transpose() * b.angular_velocity[i];
      const Vec3 m_applied = r.transpose() * moment;
      Vec3 w_body = w_old_body;
      double rotation_dissipated = 0.0;
      for (int pass = 0; pass < 3; ++pass) {
        const Vec3 w_mid = 0.5 * (w_old_body + w_body);
        const Vec3 m_body = m_applied - w_mid.cross(inertia.cwiseProduct(w_mid));
        rotation_dissipated = 0.0;
        for (int c = 0; c < 3; ++c)
          w_body[c] = damping.velocity_update(w_old_body[c], m_body[c], inertia[c], dt, rotation_dissipated);
      }
      dissipated += rotation_dissipated;
      Vec3 w = r * w_body;
      if (fixity & model::Fixity::all_rotations) {
        for (int c = 0; c < 3; ++c)
          if (fixity & (8u << c)) w[c] = 0.0;
        w_body = r.transpose() * w;
      }
      b.velocity[i] = v;
      b.angular_velocity[i] = w;
      // Kinetic energy at step n from the two half-step velocities: conserved exactly by the undamped leapfrog.
      kinetic_[i] = 0.5 * m * v_old.dot(v) + 0.5 * w_old_body.cwiseProduct(inertia).dot(w_body);
      viscous_[i] += dissipated;
      // Work of gravity over the move that brought the block to x_n, where the forces and energies are evaluated.
      gravity_work_[i] += m * gravity.dot(v_old) * increment_dt;
      if (!move) continue;
      b.position[i] += dt * v;
      const double angle = w.norm() * dt;
      if (angle > 0) {
        b.orientation[i] = (Quaternion(Eigen::AngleAxisd(angle, w / w.norm())) * b.orientation[i]).normalized();
        b.rotation[i] = b.orientation[i].toRotationMatrix();
      }
    }
  }

  EnergyReport energy_terms() const {
    EnergyReport e;
    e.slip = retired_slip_;
    e.viscous = retired_viscous_;
    const auto& b = model_->bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
      e.kinetic += kinetic_[i];
      e.gravity_work += gravity_work_[i];
      e.base_work += base_work_[i];
      e.viscous += viscous_[i];
    }
    for_each_group([&](const auto& g) {
      using L = typename std::remove_cvref_t<decltype(g)>::LawType;
      for (std::size_t k = 0; k < g.size(); ++k) {
        const auto& p = g.properties[g.property[k]];
        double stored = L::stored_energy(p, g.history[k]);
        if constexpr (requires { damping_.stored_energy(g.spring_state[k][0], 1.0); }) {
          // The loop accumulated the work done on the damping springs; what they still store is not dissipated.
          const double branches = damping_.stored_energy(g.spring_state[k][0], L::normal_stiffness(p)) +
                                  damping_.stored_energy(g.spring_state[k][1], L::shear_stiffness(p)) +
                                  damping_.stored_energy(g.spring_state[k][2], L::shear_stiffness(p));
          stored += branches;
          e.viscous -= g.area[k] * branches;
        }
        e.elastic += g.area[k] * stored;
        e.slip += g.slip_dissipation[k];
        e.viscous += g.viscous_dissipation[k];
      }
    });
    return e;
  }

  model::Model* model_;
  Damping damping_;
  PropertyFunction properties_;
  model::ContactSettings settings_;
  Groups groups_;
  double dt_ = 0;
  double time_ = 0;
  long long steps_ = 0;
  int steps_since_check_ = 0;
  int detections_ = 0;
  bool pending_increment_ = false;
  std::vector<double> kinetic_, gravity_work_, base_work_, viscous_, radius_;
  std::vector<Vec3> detected_position_;
  Vec3 base_displacement_ = Vec3::Zero();           // m, integral of the base velocity
  Vec3 detected_base_displacement_ = Vec3::Zero();  // at the last detection
  std::vector<Quaternion> detected_orientation_;
  EnergyReport energy0_;
  bool energy_reference_pending_ = true;
  double retired_slip_ = 0, retired_viscous_ = 0;  // J, dissipated at CPs that no longer exist
  std::array<std::vector<std::uint8_t>, sizeof...(Laws)> taken_over_;  // old CPs already matched, during a detection
};

}  // namespace blockdem
