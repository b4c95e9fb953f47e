#pragma once
// Static stability of a semicircular masonry arch on fixed springings under its own weight plus a horizontal body
// acceleration lambda g (the equivalent static analysis of De Lorenzis et al. 2007), with dry Mohr-Coulomb joints,
// solved by the DEM with Cundall's local damping or inertial relaxation (settling.hpp): the arch stands if the
// unbalanced force vanishes, and collapses if a mechanism keeps moving. With `to_rest`, a collapse is followed to its
// end: the voussoirs fall onto a floor (fixed blocks level with the springings, inside and outside the arch), tumble
// on it with general contacts (vertex, edge and face) and come to rest there.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "blockdem/analysis/deformable_options.hpp"
#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/settling.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/integrate/inertial_relaxation.hpp"
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
  bool to_rest = false;             // after a collapse, go on until the fallen voussoirs are at rest on the floor
  // How each trial comes to equilibrium or collapse (settling.hpp): inertial relaxation or local damping; auto:
  // inertial with deformable voussoirs (local damping if nodal_damping asks for its nodal form), local damping with
  // rigid ones. A collapse followed to rest tumbles under local damping either way (a fall is no relaxation:
  // velocities set to zero would stop it in mid-air).
  Settling settling = Settling::automatic;
  bool nodal_damping = false;       // deformable, local damping: on each node's own force (3DEC's), instead of on each
                                    // voussoir's rigid-body motion and deformation apart (damping::Local)
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
    check(unbalanced_tolerance > 0 && unbalanced_tolerance <= 0.1, "unbalanced tolerance must be in (0, 0.1]");
    check(!(to_rest && deformable), "a collapse followed to rest needs rigid voussoirs (no --deformable)");
    check(!(nodal_damping && settling == Settling::inertial),
          "nodal damping is a form of local damping: it goes with settling local or auto, not inertial");
  }
  /// Whether the trials run by inertial relaxation.
  bool inertial() const { return !to_rest && !nodal_damping && resolved(settling, deformable) == Settling::inertial; }
};

struct ArchResult {
  bool stands = false;
  bool at_rest = false;             // to_rest: the collapsed voussoirs came to rest (unbalanced force ratio below tolerance)
  int voussoirs_on_floor = 0;       // to_rest: voussoirs whose lowest vertex is within the tolerance of the floor
  int detections = 0;               // contact detections during the steps
  double detection_seconds = 0;     // wall time in them, s
  double max_penetration = 0;       // m, to_rest: deepest overlap of two blocks (separating-axis test every 100 steps)
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

/// The deepest overlap (m, >= 0) of two blocks of the model that are not both fixed, by the separating-axis test
/// over the pairs whose bounding boxes meet (geometry/assembly_check.hpp).
inline double deepest_overlap(const model::Model& model) {
  const auto& b = model.bodies;
  std::vector<geometry::ConvexPolyhedron> world(b.size());
  std::vector<geometry::AssemblyBlock> blocks(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    world[i] = b.world_shape(i);
    blocks[i] = {&world[i], b.name[i], "", b.motion[i] == model::Motion::free};
  }
  std::vector<geometry::BlockIssue> ignored;
  return geometry::check_assembly(blocks, 0, ignored).deepest_overlap;
}

/// The arch as a model file describes it (analysis/model_file_writer.hpp): the voussoirs of analyse_arch, the
/// springings fixed, its dry joint law, its contact tolerance (rigid voussoirs; no floor).
inline ModelDescription arch_description(const ArchOptions& o) {
  o.validate();
  ModelDescription d;
  d.name = std::to_string(o.voussoirs) + "-voussoir semicircular arch, t/R = " + num(o.thickness_ratio);
  d.materials.push_back({"stone", o.density, 0, 0});
  d.laws = LawTable({"arch"});
  d.laws.set(0, 0, contact::MohrCoulomb::Parameters(o.normal_stiffness, 0.5 * o.normal_stiffness, 0, 0, o.friction_angle_deg * pi / 180.0));
  d.contact_tolerance = 1e-4 * o.radius;
  for (const auto& b : geometry::semicircular_arch(o.voussoirs, o.radius, o.thickness_ratio * o.radius, o.depth))
    d.blocks.push_back({b.name, 0, 0, b.support ? model::Motion::fixed : model::Motion::free, b.shape, 0.0});
  return d;
}

/// The pushover of `arch --find-collapse` as the study runs it (analysis/pushover.hpp): lambda g along +x, bisected
/// to 0.005, collapse at a voussoir moving a quarter of the ring's thickness (or o.collapse_displacement).
inline PushoverOptions arch_pushover(const ArchOptions& o) {
  PushoverOptions p;
  p.axis = 'x';
  p.resolution = 0.005;
  p.collapse_displacement = o.collapse_displacement > 0 ? o.collapse_displacement : 0.25 * o.thickness_ratio * o.radius;
  p.tolerance = o.unbalanced_tolerance;
  p.max_steps = o.max_steps;
  return p;
}

inline ArchResult analyse_arch(const ArchOptions& o) {
  o.validate();
  const auto start = std::chrono::steady_clock::now();
  model::Model model;
  const double thickness = o.thickness_ratio * o.radius;
  for (const auto& b : geometry::semicircular_arch(o.voussoirs, o.radius, thickness, o.depth))
    model.add_block(b.shape, o.density, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  // The floor, its top level with the springings (z = 0): between the supports and outside them, 2 R on each side.
  const double ri = o.radius - 0.5 * thickness, re = o.radius + 0.5 * thickness, span = re + 2 * o.radius + thickness;
  const std::size_t floor_begin = model.bodies.size();
  if (o.to_rest) {
    const double y0 = -2 * o.depth, y1 = 2 * o.depth, inner = ri - 0.5 * thickness, outer = re + 0.5 * thickness;
    model.add_block(geometry::make_box(Vec3(-inner, y0, -thickness), Vec3(inner, y1, 0)), o.density, "floor", 0, model::Motion::fixed);
    model.add_block(geometry::make_box(Vec3(outer, y0, -thickness), Vec3(span, y1, 0)), o.density, "floor right", 0, model::Motion::fixed);
    model.add_block(geometry::make_box(Vec3(-span, y0, -thickness), Vec3(-outer, y1, 0)), o.density, "floor left", 0, model::Motion::fixed);
  }
  if (o.deformable)
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      if (model.bodies.motion[i] == model::Motion::free) model.make_deformable(i, o.max_edge, model::IsotropicElastic(o.young, o.poisson));
  model.gravity = Vec3(o.lambda * 9.81, 0, -9.81);
  const contact::MohrCoulomb::Parameters joint(o.normal_stiffness, 0.5 * o.normal_stiffness, 0, 0,
                                                o.friction_angle_deg * pi / 180.0);
  model::ContactSettings contacts;
  contacts.tolerance = 1e-4 * o.radius;
  damping::Local local;
  local.split_rigid_motion = !o.nodal_damping && !o.inertial();
  if (o.inertial()) local.coefficient = 0;
  InertialRelaxation relaxation;
  Simulation<damping::Local, contact::MohrCoulomb> sim(model, local, [&](int, int) { return joint; }, contacts);
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
    if (o.inertial()) relaxation.after_step(model, sim.timestep());
    if (r.steps % 50 != 49) continue;
    r.max_displacement = 0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      r.max_displacement = std::max(r.max_displacement, (model.bodies.position[i] - initial[i]).norm());
    for (std::size_t i = 0; i < initial_nodes.size(); ++i)
      r.max_displacement = std::max(r.max_displacement, (model.deformable.nodes.position[i] - initial_nodes[i]).norm());
    r.unbalanced_ratio = sim.unbalanced_force_ratio();
    if (!o.to_rest && r.max_displacement > limit) break;
    if (o.to_rest && r.steps % 100 == 99) r.max_penetration = std::max(r.max_penetration, deepest_overlap(model));
    if (r.unbalanced_ratio <= o.unbalanced_tolerance) {
      r.stands = r.max_displacement <= limit;
      r.at_rest = !r.stands;
      break;
    }
  }
  if (o.to_rest) {
    r.max_penetration = std::max(r.max_penetration, deepest_overlap(model));
    for (std::size_t i = 0; i < floor_begin; ++i) {
      if (model.bodies.motion[i] != model::Motion::free) continue;
      double lowest = std::numeric_limits<double>::infinity();
      for (const auto& v : model.bodies.world_shape(i).vertices) lowest = std::min(lowest, v.z());
      if (lowest < contacts.tolerance && (model.bodies.position[i] - initial[i]).norm() > limit) ++r.voussoirs_on_floor;
    }
  }
  r.detections = sim.detections();
  r.detection_seconds = sim.detection_seconds();
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
