#pragma once
// Static stability of a semicircular masonry arch on fixed springings under its own weight plus a horizontal body
// acceleration lambda g (the equivalent static analysis of De Lorenzis et al. 2007), with dry Mohr-Coulomb joints,
// solved by the DEM with Cundall's local damping: the arch stands if the unbalanced force vanishes, and collapses
// if a mechanism keeps moving.

#include <chrono>
#include <cmath>
#include <string>

#include "blockdem/analysis/deformable_options.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/io/vtk.hpp"

namespace blockdem::analysis {

struct ArchOptions : DeformableOptions {
  int voussoirs = 40;               // 2..2000
  double thickness_ratio = 0.15;    // t / R, in (0, 1)
  double radius = 1.0;              // m, to the centreline
  double depth = 0.5;               // m
  double friction_angle_deg = 40;   // of the joints, (0, 89]
  double lambda = 0.1;              // horizontal acceleration / g, >= 0
  double density = 2000;            // kg/m^3
  double normal_stiffness = 1e10;   // Pa/m; shear stiffness = half of it
  double unbalanced_tolerance = 1e-5;
  double collapse_displacement = 0; // m: a voussoir moving this far means collapse (0: a quarter of the thickness)
  long long max_steps = 400000;
  std::string vtk_prefix;           // if set: <prefix>_blocks.vtu and <prefix>_contacts.vtu at the end
                                    // (and <prefix>_tetrahedra.vtu with the density scaling factor if deformable)

  void validate() const {
    validate_deformable("arch");
    auto check = [](bool ok, const char* what) {
      if (!ok) throw InvalidArgument(std::string("arch: ") + what);
    };
    check(voussoirs >= 2 && voussoirs <= 2000, "voussoirs must be in 2..2000");
    check(thickness_ratio > 0 && thickness_ratio < 1, "thickness ratio t/R must be in (0, 1)");
    check(radius > 0 && radius <= 1000, "radius must be in (0, 1000] m");
    check(depth > 0 && depth <= 1000, "depth must be in (0, 1000] m");
    check(friction_angle_deg > 0 && friction_angle_deg <= 89, "friction angle must be in (0, 89] degrees");
    check(lambda >= 0 && lambda <= 10, "lambda must be in [0, 10]");
    check(density >= 1 && density <= 1e5, "density must be in [1, 1e5] kg/m^3");
    // Beyond these the timestep and the joint's overlap leave the range where the run means anything (it diverges).
    check(normal_stiffness >= 1e6 && normal_stiffness <= 1e15, "normal stiffness must be in [1e6, 1e15] Pa/m");
    check(max_steps >= 100, "max steps must be >= 100");
  }
};

struct ArchResult {
  bool stands = false;
  double max_displacement = 0;  // m
  double unbalanced_ratio = 0;
  long long steps = 0;
  double wall_seconds = 0;
  double timestep = 0;
  std::size_t blocks = 0;
  std::size_t contact_points = 0;
  double dt_critical_unscaled = 0;  // s
  double mass_increase_percent = 0;
  std::size_t nodes = 0, tetrahedra = 0;
};

inline ArchResult analyse_arch(const ArchOptions& o) {
  o.validate();
  const auto start = std::chrono::steady_clock::now();
  model::Model model;
  const double thickness = o.thickness_ratio * o.radius;
  for (const auto& b : geometry::semicircular_arch(o.voussoirs, o.radius, thickness, o.depth))
    model.add_block(b.shape, o.density, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  if (o.deformable)
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      if (model.bodies.motion[i] == model::Motion::free) model.make_deformable(i, o.max_edge, model::IsotropicElastic(o.young, o.poisson));
  model.gravity = Vec3(o.lambda * 9.81, 0, -9.81);
  const contact::MohrCoulomb::Parameters joint(o.normal_stiffness, 0.5 * o.normal_stiffness, 0, 0,
                                                o.friction_angle_deg * pi / 180.0);
  model::ContactSettings contacts;
  contacts.tolerance = 1e-4 * o.radius;
  Simulation<damping::Local, contact::MohrCoulomb> sim(model, damping::Local{}, [&](int, int) { return joint; }, contacts);
  const auto initial = model.bodies.position;
  const auto initial_nodes = model.deformable.nodes.position;
  const double limit = o.collapse_displacement > 0 ? o.collapse_displacement : 0.25 * thickness;
  ArchResult r;
  r.blocks = model.bodies.size();
  r.contact_points = sim.contact_points();
  r.dt_critical_unscaled = sim.critical_timestep();
  if (o.target_dt > 0) r.mass_increase_percent = sim.scale_density_to(o.target_dt).mass_increase_percent;
  r.timestep = sim.timestep();
  r.nodes = model.deformable.nodes.size();
  r.tetrahedra = model.deformable.tetrahedra.size();
  for (r.steps = 0; r.steps < o.max_steps; ++r.steps) {
    sim.step();
    if (r.steps % 50 != 49) continue;
    r.max_displacement = 0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      r.max_displacement = std::max(r.max_displacement, (model.bodies.position[i] - initial[i]).norm());
    for (std::size_t i = 0; i < initial_nodes.size(); ++i)
      r.max_displacement = std::max(r.max_displacement, (model.deformable.nodes.position[i] - initial_nodes[i]).norm());
    r.unbalanced_ratio = sim.unbalanced_force_ratio();
    if (r.max_displacement > limit) break;
    if (r.unbalanced_ratio <= o.unbalanced_tolerance) {
      r.stands = true;
      break;
    }
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.vtk_prefix.empty()) {
    std::vector<double> displacement(model.bodies.size());
    for (std::size_t i = 0; i < model.bodies.size(); ++i) displacement[i] = (model.bodies.position[i] - initial[i]).norm();
    io::write_blocks_vtu(o.vtk_prefix + "_blocks.vtu", model, {{"displacement", displacement}});
    io::write_contacts_vtu(o.vtk_prefix + "_contacts.vtu", sim);
    if (o.deformable) io::write_tetrahedra_vtu(o.vtk_prefix + "_tetrahedra.vtu", model, initial_nodes);
  }
  return r;
}

/// The smallest lambda at which the arch collapses, by bisection to `resolution`; 0 if it does not stand under
/// its own weight, or `upper` if it still stands there.
inline double collapse_multiplier(ArchOptions o, double resolution = 0.005, double upper = 1.0) {
  o.lambda = 0;
  if (!analyse_arch(o).stands) return 0.0;
  o.lambda = upper;
  if (analyse_arch(o).stands) return upper;
  double lo = 0, hi = upper;
  while (hi - lo > resolution) {
    o.lambda = 0.5 * (lo + hi);
    (analyse_arch(o).stands ? lo : hi) = o.lambda;
  }
  return 0.5 * (lo + hi);
}

}  // namespace blockdem::analysis
