// arch: does a semicircular masonry arch on fixed springings stand under its own weight plus a horizontal body
// acceleration lambda g? With --find-collapse, the collapse multiplier by bisection to 0.005.
//
//   arch --voussoirs 40 --thickness-ratio 0.15 --radius 1 --depth 0.5 --friction-angle 40 --lambda 0.1
//        [--find-collapse] [--to-rest] [--json] [--vtk PREFIX]
//        [--deformable [--max-edge 0.25] [--young 5e9] [--poisson 0.2]] [--target-dt DT]
//
// With --to-rest a collapse is followed to its end: the voussoirs fall onto a floor level with the springings and come
// to rest there (general contacts: they tumble onto edges and corners); the VTK files then show the heap.
//
// Exit status: 0 on success, 2 on bad input, 1 if the run left every physical bound (it diverged).

#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/arch.hpp"
#include "blockdem/io/json.hpp"
#include "cli.hpp"

int main(int argc, char** argv) {
  using namespace blockdem;
  CLI::App app{"Static stability of a semicircular masonry arch under gravity and a horizontal acceleration (blockdem)"};
  analysis::ArchOptions o;
  bool find_collapse = false;
  bool json = false;
  app.add_option("--voussoirs", o.voussoirs, "number of voussoirs, 2..2000")->capture_default_str();
  app.add_option("--thickness-ratio", o.thickness_ratio, "ring thickness over centreline radius t/R, (0, 1)")->capture_default_str();
  app.add_option("--radius", o.radius, "centreline radius R, m")->capture_default_str();
  app.add_option("--depth", o.depth, "depth of the arch, m")->capture_default_str();
  app.add_option("--friction-angle", o.friction_angle_deg, "joint friction angle, degrees, (0, 89]")->capture_default_str();
  app.add_option("--lambda", o.lambda, "horizontal body acceleration over g, [0, 10]")->capture_default_str();
  app.add_option("--density", o.density, "kg/m^3")->capture_default_str();
  app.add_option("--normal-stiffness", o.normal_stiffness, "joint normal stiffness, Pa/m (shear: half)")->capture_default_str();
  app.add_flag("--find-collapse", find_collapse, "find the collapse multiplier lambda by bisection to 0.005");
  bool model_file = false;
  app.add_flag("--model", model_file, "write the arch and the pushover of --find-collapse as a model file (docs/model-file.md) "
                                      "on stdout: `blockdem run` on it finds the same multiplier");
  app.add_option("--unbalanced-tolerance", o.unbalanced_tolerance,
                 "unbalanced force ratio below which the arch stands (or, --to-rest, its pieces rest), (0, 0.1]")
      ->capture_default_str();
  app.add_option("--max-steps", o.max_steps, "most steps, >= 100")->capture_default_str();
  app.add_option("--settling", o.settling,
                 "how each trial comes to equilibrium or collapse: inertial (relaxation without damping, stopped when it "
                 "starts uphill), local (local damping) or auto (inertial with --deformable, local for rigid voussoirs)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, analysis::Settling>{{"auto", analysis::Settling::automatic},
                                                                                    {"inertial", analysis::Settling::inertial},
                                                                                    {"local", analysis::Settling::local}}));
  app.add_flag("--nodal-damping", o.nodal_damping, "deformable: local damping (so not inertial relaxation) on each node's own force "
               "(3DEC's), not on each voussoir's rigid-body motion and deformation apart (docs/arch.md)");
  app.add_flag("--to-rest", o.to_rest, "after a collapse, go on until the voussoirs rest on the floor");
  app.add_flag("--json", json, "print a JSON object");
  app.add_option("--vtk", o.vtk_prefix, "write PREFIX_blocks.vtu and PREFIX_contacts.vtu (final state) for ParaView");
  programs::add_deformable_options(app, o, "the voussoirs");
  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;
  try {
    o.validate();
    if (model_file) {
      if (o.deformable) throw InvalidArgument("--model writes rigid voussoirs: leave out --deformable");
      analysis::StudyOptions study;
      study.contacts = model::ContactKinds::general;
      const auto pushover = analysis::arch_pushover(o);
      analysis::write_model_file(std::cout, analysis::arch_description(o), study, &pushover);
      return std::cout.flush() ? 0 : 1;
    }
    const auto r = analysis::analyse_arch(o);
    auto bisection = o;
    bisection.vtk_prefix.clear();
    const double lambda_collapse = find_collapse ? analysis::collapse_multiplier(bisection) : -1.0;
    if (json) {
      io::JsonObject out;
      out.add("stands", r.stands)
          .add("lambda", o.lambda)
          .add("settling", o.inertial() ? "inertial" : "local")
          .add("lambda_collapse", find_collapse ? lambda_collapse : std::numeric_limits<double>::quiet_NaN())
          .add("max_displacement_m", r.max_displacement)
          .add("at_rest", r.at_rest)
          .add("voussoirs_on_floor", r.voussoirs_on_floor)
          .add("max_penetration_m", r.max_penetration)
          .add("detections", r.detections)
          .add("detection_seconds", r.detection_seconds)
          .add("unbalanced_ratio", r.unbalanced_ratio)
          .add("steps", static_cast<long long>(r.steps))
          .add("wall_seconds", r.wall_seconds)
          .add("dt", r.timestep)
          .add("dt_critical_unscaled", r.dt_critical_unscaled)
          .add("mass_increase_percent", r.mass_increase_percent)
          .add("blocks", static_cast<int>(r.blocks))
          .add("nodes", static_cast<int>(r.nodes))
          .add("tetrahedra", static_cast<int>(r.tetrahedra))
          .add("contact_points", static_cast<int>(r.contact_points));
      fmt::print("{}\n", out.str());
    } else {
      fmt::print("arch of {} voussoirs, t/R = {:g}, R = {:g} m, friction {:g} deg, lambda = {:g}: {}\n", o.voussoirs,
                 o.thickness_ratio, o.radius, o.friction_angle_deg, o.lambda, r.stands ? "STANDS" : "COLLAPSES");
      fmt::print("max displacement {:.3e} m, unbalanced force ratio {:.2e}, {} steps of {:.3e} s ({}), {:.2f} s\n",
                 r.max_displacement, r.unbalanced_ratio, r.steps, r.timestep, o.inertial() ? "inertial relaxation" : "local damping",
                 r.wall_seconds);
      if (o.to_rest)
        fmt::print("{}: {} voussoirs on the floor, deepest overlap of two blocks {:.3e} m\n",
                   r.at_rest ? "at rest" : "still moving at max steps", r.voussoirs_on_floor, r.max_penetration);
      if (o.deformable)
        fmt::print("deformable: {} nodes, {} tetrahedra, {} contact points; critical dt {:.3e} s unscaled, mass +{:.2f} %\n",
                   r.nodes, r.tetrahedra, r.contact_points, r.dt_critical_unscaled, r.mass_increase_percent);
      if (find_collapse) fmt::print("collapse multiplier lambda = {:.4f} (bisection to 0.005)\n", lambda_collapse);
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "arch: error: %s\n", e.what());
    return 2;
  } catch (const RunawayError& e) {
    std::fprintf(stderr, "arch: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
