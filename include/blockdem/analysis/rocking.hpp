#pragma once
// A rigid block on a base that moves with a horizontal acceleration history: uplift, rocking rotation and impacts
// (the rocking problem of Housner 1963 in its DEM form: dry Mohr-Coulomb joint, no viscous damping).

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "blockdem/analysis/deformable_options.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/motion/base_motion.hpp"
#include "blockdem/motion/processing.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::analysis {

struct RockingOptions : DeformableOptions {
  RockingOptions() { young = 10e9; }  // Pa, of the block if deformable
  double width = 0.2;    // m, along the excitation (x)
  double depth = 0.5;    // m
  double height = 1.0;   // m
  double density = 2000; // kg/m^3
  double friction_angle_deg = 45;
  double normal_stiffness = 1e9;  // Pa/m; shear stiffness equal
  double duration = 2.0;  // s
  /// Dashpots beta k in the joint's springs (stiffness-proportional), beta for this fraction of critical damping of
  /// the block bouncing on its whole base, sqrt(k_n w d / m); 0: none. They make the impacts inelastic, as Housner's
  /// (1963) are: with undamped springs a block that lands on its base bounces back with most of its energy.
  double contact_damping_ratio = 0;
  /// Base acceleration along x: a record whose start_time (s, >= 0) counts from the end of the settling. The base is
  /// at rest before it and keeps, after it, the velocity it ends with. Empty (the default): the base stays at rest.
  motion::Record base_acceleration;
  /// s: a record with a longer step is resampled to a whole fraction of it no longer than this (the same
  /// piecewise-linear acceleration) before the toolkit integrates it. The table's velocity is linear between samples:
  /// at a record's own step (5-20 ms) its acceleration would be a staircase that shakes the joint (9 ms period for
  /// the default block).
  double base_sampling = 1e-4;
  double uplift_rotation = 1e-3;  // rad: a rotation beyond this is uplift (the elastic rocking of the joint is ~1e-4)
  double restitution_rotation = 0.01;  // rad: the impact's velocities are measured where the rotation passes this
  double record_interval = 1e-3;  // s
  /// Of the default timestep (0.8 of the critical one, eq. 1, with the damping's factor, eq. 11). At the default an
  /// impact on the block's edge is resolved by about two steps and the undamped landing keeps far too much of its
  /// rotation (restitution 0.769 where the converged value is 0.184; 0.190 at 0.5: docs/rocking_block.md); 0.03
  /// converges.
  double timestep_factor = 1.0;

  void validate() const {
    validate_deformable("rocking block");
    auto check = [](bool ok, const char* what) {
      if (!ok) throw InvalidArgument(std::string("rocking block: ") + what);
    };
    check(width > 0 && depth > 0 && height > 0 && width <= 1000 && depth <= 1000 && height <= 1000,
          "width, depth and height must be > 0 m and at most 1000 m");
    check(density >= 1 && density <= 1e5, "density must be in [1, 1e5] kg/m^3");
    check(friction_angle_deg > 0 && friction_angle_deg <= 89, "friction angle must be in (0, 89] degrees");
    // Beyond these the timestep and the joint's overlap leave the range where the run means anything (it diverges).
    check(normal_stiffness >= 1e6 && normal_stiffness <= 1e15, "normal stiffness must be in [1e6, 1e15] Pa/m");
    check(duration > 0 && duration <= 1e4, "duration must be in (0, 1e4] s");
    check(contact_damping_ratio >= 0 && contact_damping_ratio <= 10, "contact damping ratio must be in [0, 10]");
    check(record_interval > 0, "record interval must be > 0 s");
    check(timestep_factor > 0 && timestep_factor <= 1, "timestep factor must be in (0, 1]");
    check(restitution_rotation >= uplift_rotation && restitution_rotation < std::atan(width / height),
          "the restitution rotation must be at least the uplift rotation and below atan(width / height)");
    check(base_sampling > 0 && std::isfinite(base_sampling), "base sampling must be > 0 s");
    if (!base_acceleration.acceleration.empty()) {
      base_acceleration.validate("rocking block: base acceleration");
      check(base_acceleration.start_time >= 0 && std::isfinite(base_acceleration.start_time),
            "the base acceleration's start time must be >= 0 s (from the end of the settling)");
    }
  }
};

struct RockingResult {
  bool uplift = false;
  double max_rotation = 0;   // rad, largest |rotation about y|
  int impacts = 0;           // returns to the base after an uplift (sign changes of the rotation beyond the threshold)
  bool overturned = false;   // rotation beyond atan(width / height)
  double max_penetration = 0;  // m, deepest overlap of a rigid block and the base (separating-axis test, each record)
  /// Per impact of a rigid block, |angular velocity after / before| at the moment of impact (rotation zero), from
  /// the velocities at the last and first steps beyond `restitution_rotation` and the rigid block's energy between
  /// there and the impact; Housner's (1963) value for a rectangular block is 1 - 1.5 sin^2(alpha).
  std::vector<double> restitution;
  double housner_restitution = 0;
  std::vector<double> time, rotation, base_acceleration;  // history, s, rad, m/s^2
  long long steps = 0;
  double wall_seconds = 0;
  double timestep = 0;
  double dt_critical_unscaled = 0;  // s
  double mass_increase_percent = 0;
  std::size_t nodes = 0, tetrahedra = 0, contact_points = 0;
};

inline RockingResult analyse_rocking(const RockingOptions& o) {
  o.validate();
  const auto start = std::chrono::steady_clock::now();
  model::Model model;
  const double w = o.width, d = o.depth, h = o.height;
  const auto base = model.add_block(geometry::make_box(Vec3(-2 * w - h, -d, -0.5 * h), Vec3(2 * w + h, d, 0)), 2000, "base", 0,
                                    model::Motion::base);
  const auto block = model.add_block(geometry::make_box(Vec3(-0.5 * w, -0.5 * d, 0), Vec3(0.5 * w, 0.5 * d, h)), o.density, "block", 1);
  if (o.deformable) model.make_deformable(block, o.max_edge, model::IsotropicElastic(o.young, o.poisson));
  const contact::MohrCoulomb::Parameters joint(o.normal_stiffness, o.normal_stiffness, 0, 0, o.friction_angle_deg * pi / 180.0);
  Simulation<damping::Local, contact::MohrCoulomb> settle(model, damping::Local{}, [&](int, int) { return joint; });
  RockingResult r;
  r.dt_critical_unscaled = settle.critical_timestep();
  if (o.target_dt > 0) r.mass_increase_percent = settle.scale_density_to(o.target_dt).mass_increase_percent;
  settle.solve_to_equilibrium(1e-6, 200000);
  // The rocking run: without viscous damping (Housner's rigid block on a dry joint), or with dashpots in the joint's
  // springs that make its impacts inelastic.
  const auto rock = [&](auto& sim) {
    if (o.timestep_factor < 1) sim.set_timestep(o.timestep_factor * sim.timestep());
    const double t0 = sim.time();
    const double dt = sim.timestep();
    // The base follows the record from its start after the settling, integrated by the toolkit.
    if (const auto& a = o.base_acceleration; !a.acceleration.empty()) {
      const double parts = std::ceil(a.dt / o.base_sampling * (1 - 1e-9));  // k samplings, to rounding, split in k
      model.base_motion = motion::BaseMotion(parts > 1 ? motion::resample(a, a.dt / parts) : a, {}, Vec3::UnitX(),
                                             t0 + a.start_time);
    }
    const Quaternion q0 = model.bodies.orientation[block];
    r.timestep = dt;
    r.nodes = model.deformable.nodes.size();
    r.tetrahedra = model.deformable.tetrahedra.size();
    r.contact_points = sim.contact_points();
    // Deformable: the rotation about y from the bottom corner nodes at x = -w/2 and x = +w/2 (on y = 0 or nearest).
    std::size_t heel = 0, toe = 0;
    if (o.deformable) {
      heel = model.nearest_node(block, Vec3(-0.5 * w, 0, 0));
      toe = model.nearest_node(block, Vec3(0.5 * w, 0, 0));
    }
    const auto& nodes = model.deformable.nodes.position;
    const double heel_z0 = o.deformable ? nodes[heel].z() : 0, toe_z0 = o.deformable ? nodes[toe].z() : 0;
    const double lever = o.deformable ? nodes[toe].x() - nodes[heel].x() : 1.0;
    const double overturn = std::atan(w / h);
    r.housner_restitution = 1 - 1.5 * std::pow(std::sin(overturn), 2);
    // The rigid block rocking about an edge: omega^2 + 2 p^2 cos(alpha - |theta|) is constant (I_O = 4/3 m R^2,
    // p^2 = 3 g / (4 R), R the half-diagonal), which gives the angular velocity at theta = 0 from that at theta.
    const double p2 = 3 * 9.81 / (4 * 0.5 * std::hypot(w, h));
    const auto at_impact = [&](double omega, double theta) {
      return std::sqrt(omega * omega + 2 * p2 * (std::cos(overturn - std::abs(theta)) - std::cos(overturn)));
    };
    double next_record = 0, last_sign = 0, approach = 0, departure_sign = 0;
    while (sim.time() - t0 < o.duration) {
      sim.step();
      ++r.steps;
      const double t = sim.time() - t0;
      const Quaternion turn = model.bodies.orientation[block] * q0.conjugate();
      const double theta = o.deformable ? ((nodes[heel].z() - heel_z0) - (nodes[toe].z() - toe_z0)) / lever
                                        : 2.0 * std::atan2(turn.y(), turn.w());
      r.max_rotation = std::max(r.max_rotation, std::abs(theta));
      if (std::abs(theta) > o.uplift_rotation) {
        const double sign = theta > 0 ? 1.0 : -1.0;
        if (last_sign != 0 && sign != last_sign) ++r.impacts;
        last_sign = sign;
      }
      if (!o.deformable && std::abs(theta) >= o.restitution_rotation) {
        const double omega = model.bodies.angular_velocity[block].y(), sign = theta > 0 ? 1.0 : -1.0;
        if (departure_sign != 0 && sign != departure_sign && approach > 0 && omega * sign > 0)
          r.restitution.push_back(at_impact(omega, theta) / approach);  // the first step past the impact
        // Moving towards the base: the approach velocity of the next impact, until it comes.
        approach = omega * sign < 0 ? at_impact(omega, theta) : 0.0;
        departure_sign = sign;
      }
      if (std::abs(theta) > overturn) r.overturned = true;
      if (t >= next_record) {
        if (!o.deformable)
          r.max_penetration = std::max(r.max_penetration,
                                       -geometry::separation(model.bodies.world_shape(base), model.bodies.world_shape(block)));
        r.time.push_back(t);
        r.rotation.push_back(theta);
        r.base_acceleration.push_back(model.base_motion.acceleration(sim.time()).x());
        next_record += o.record_interval;
      }
      if (r.overturned && std::abs(theta) > 1.2) break;  // lying on its side: nothing more to learn
    }
  };
  if (o.contact_damping_ratio > 0) {
    const double omega = std::sqrt(o.normal_stiffness * w * d / model.bodies.mass[block]);  // rad/s
    Simulation<damping::StiffnessProportional, contact::MohrCoulomb> sim(
        settle, damping::StiffnessProportional{2 * o.contact_damping_ratio / omega});
    rock(sim);
  } else {
    Simulation<damping::None, contact::MohrCoulomb> sim(settle, damping::None{});
    rock(sim);
  }
  r.uplift = r.max_rotation > o.uplift_rotation;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace blockdem::analysis
