#pragma once
// A rigid block on a base that moves with a horizontal acceleration history: uplift, rocking rotation and impacts
// (the rocking problem of Housner 1963 in its DEM form: dry Mohr-Coulomb joint, no viscous damping).

#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "blockdem/analysis/deformable_options.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/simulation.hpp"

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
  /// Base acceleration along x (m/s^2) at time t (s), from t = 0.
  std::function<double(double)> base_acceleration = [](double) { return 0.0; };
  double uplift_rotation = 1e-3;  // rad: a rotation beyond this is uplift (the elastic rocking of the joint is ~1e-4)
  double record_interval = 1e-3;  // s

  void validate() const {
    validate_deformable("rocking block");
    auto check = [](bool ok, const char* what) {
      if (!ok) throw InvalidArgument(std::string("rocking block: ") + what);
    };
    check(width > 0 && depth > 0 && height > 0, "width, depth and height must be > 0 m");
    check(density > 0, "density must be > 0 kg/m^3");
    check(friction_angle_deg > 0 && friction_angle_deg <= 89, "friction angle must be in (0, 89] degrees");
    check(normal_stiffness > 0, "normal stiffness must be > 0 Pa/m");
    check(duration > 0 && duration <= 1e4, "duration must be in (0, 1e4] s");
    check(record_interval > 0, "record interval must be > 0 s");
  }
};

struct RockingResult {
  bool uplift = false;
  double max_rotation = 0;   // rad, largest |rotation about y|
  int impacts = 0;           // returns to the base after an uplift (sign changes of the rotation beyond the threshold)
  bool overturned = false;   // rotation beyond atan(width / height)
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
  (void)base;
  if (o.deformable) model.make_deformable(block, o.max_edge, model::IsotropicElastic(o.young, o.poisson));
  const contact::MohrCoulomb::Parameters joint(o.normal_stiffness, o.normal_stiffness, 0, 0, o.friction_angle_deg * pi / 180.0);
  Simulation<damping::Local, contact::MohrCoulomb> settle(model, damping::Local{}, [&](int, int) { return joint; });
  RockingResult r;
  r.dt_critical_unscaled = settle.critical_timestep();
  if (o.target_dt > 0) r.mass_increase_percent = settle.scale_density_to(o.target_dt).mass_increase_percent;
  settle.solve_to_equilibrium(1e-6, 200000);
  Simulation<damping::None, contact::MohrCoulomb> sim(settle, damping::None{});
  // Base velocity: the integral of the acceleration, by the trapezoid rule on the timestep grid.
  const double t0 = sim.time();
  const double dt = sim.timestep();
  std::vector<double> velocity{0.0};
  const auto steps = static_cast<long long>(std::ceil(o.duration / dt)) + 2;
  velocity.reserve(static_cast<std::size_t>(steps) + 1);
  for (long long n = 1; n <= steps; ++n)
    velocity.push_back(velocity.back() + 0.5 * dt * (o.base_acceleration((n - 1) * dt) + o.base_acceleration(n * dt)));
  model.base_velocity = [&, t0, dt](double t) {
    const double u = std::max(0.0, (t - t0) / dt);
    const auto n = std::min(static_cast<std::size_t>(u), velocity.size() - 2);
    const double f = u - static_cast<double>(n);
    return Vec3((1 - f) * velocity[n] + f * velocity[n + 1], 0, 0);
  };
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
  double next_record = 0, last_sign = 0;
  while (sim.time() - t0 < o.duration) {
    sim.step();
    ++r.steps;
    const double t = sim.time() - t0;
    const double theta = o.deformable ? ((nodes[heel].z() - heel_z0) - (nodes[toe].z() - toe_z0)) / lever
                                      : 2.0 * (model.bodies.orientation[block] * q0.conjugate()).vec().y();
    r.max_rotation = std::max(r.max_rotation, std::abs(theta));
    if (std::abs(theta) > o.uplift_rotation) {
      const double sign = theta > 0 ? 1.0 : -1.0;
      if (last_sign != 0 && sign != last_sign) ++r.impacts;
      last_sign = sign;
    }
    if (std::abs(theta) > overturn) r.overturned = true;
    if (t >= next_record) {
      r.time.push_back(t);
      r.rotation.push_back(theta);
      r.base_acceleration.push_back(o.base_acceleration(t));
      next_record += o.record_interval;
    }
    if (r.overturned && std::abs(theta) > 1.2) break;  // lying on its side: nothing more to learn
  }
  r.uplift = r.max_rotation > o.uplift_rotation;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace blockdem::analysis
