// rocking_block: a rigid block on a base moved by a horizontal acceleration (constant, or a history from a file):
// does it uplift, how far does it rock, how many impacts, does it overturn?
//
//   rocking_block --width 0.2 --height 1 [--depth 0.5] (--constant-acceleration A | --history FILE [--in-g])
//   (a constant acceleration is ramped in over 0.2 s)
//                 [--duration 2] [--friction-angle 45] [--contact-damping 0] [--timestep-factor 1] [--out rotation.csv]
//                 [--json]
//                 [--deformable [--max-edge 0.25] [--young 10e9] [--poisson 0.2]] [--target-dt DT]
//
// The block keeps its contact with the base however far it rocks (general contacts: edge and vertex as well as face):
// --json reports its largest rotation, the deepest penetration into the base (max_penetration_m) and, per impact,
// the ratio of angular velocities after and before against Housner's 1 - 1.5 sin^2(alpha); --contact-damping makes
// the impacts inelastic, as Housner's are.
//
// FILE has two columns, time (s) and acceleration (m/s^2, or g with --in-g). Exit status 2 on bad input, 1 if the run
// left every physical bound (it diverged, or the block was thrown off).

#include <cstdio>
#include <span>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/rocking.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/columns.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/motion/acceleration_unit.hpp"
#include "blockdem/motion/processing.hpp"
#include "blockdem/motion/synthetic.hpp"
#include "cli.hpp"

int main(int argc, char** argv) {
  using namespace blockdem;
  CLI::App app{"A rigid block rocking on a moving base (blockdem)"};
  analysis::RockingOptions o;
  double constant = 0;
  std::string history, out_path;
  bool in_g = false, json = false;
  app.add_option("--width", o.width, "block width along the excitation, m")->capture_default_str();
  app.add_option("--height", o.height, "block height, m")->capture_default_str();
  app.add_option("--depth", o.depth, "block depth, m")->capture_default_str();
  app.add_option("--density", o.density, "kg/m^3")->capture_default_str();
  app.add_option("--friction-angle", o.friction_angle_deg, "degrees, (0, 89]")->capture_default_str();
  app.add_option("--normal-stiffness", o.normal_stiffness, "joint normal (and shear) stiffness, Pa/m")->capture_default_str();
  app.add_option("--duration", o.duration, "simulated time, s")->capture_default_str();
  app.add_option("--timestep-factor", o.timestep_factor,
                 "fraction of the default timestep, (0, 1]: 0.03 resolves the impacts (docs/rocking_block.md)")
      ->capture_default_str();
  app.add_option("--contact-damping", o.contact_damping_ratio,
                 "dashpots in the joint's springs, fraction of critical for the block bouncing on its base, [0, 10]")
      ->capture_default_str();
  auto* constant_option = app.add_option("--constant-acceleration", constant, "constant base acceleration along x, m/s^2, [-100, 100]");
  auto* history_option = app.add_option("--history", history, "two-column file: time (s), base acceleration");
  constant_option->excludes(history_option);
  app.add_flag("--in-g", in_g, "the history's accelerations are in g");
  app.add_option("--out", out_path, "write time_s,rotation_rad,base_acceleration_m_s2 to this CSV file");
  app.add_flag("--json", json, "print a JSON object");
  programs::add_deformable_options(app, o, "the block");
  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;
  try {
    o.validate();  // first: the ramp below would refuse a bad --duration without naming it
    if (!(constant >= -100 && constant <= 100))
      throw InvalidArgument(fmt::format("--constant-acceleration must be in [-100, 100] m/s^2 (about 10 g), got {:g}", constant));
    if (!history.empty()) {
      const auto columns = io::read_two_columns(history);
      const auto unit = in_g ? motion::AccelerationUnit::g : motion::AccelerationUnit::m_s2;
      o.base_acceleration = motion::scale(motion::record_from_samples(columns.x, columns.y, history), motion::to_m_s2(unit));
    } else {
      // Ramped in over 0.2 s (long against the joint's vibration period): a sudden step would make the undamped
      // elastic joint overshoot and lift the heel below the static threshold g tan(alpha). Held a step past the
      // duration, which the last timestep may pass.
      o.base_acceleration = motion::ramp_record(constant, 0.2, o.duration + 0.01, 0.01);
    }
    const auto r = analysis::analyse_rocking(o);
    if (!out_path.empty()) {
      io::write_atomically(out_path, [&](std::ostream& out) {
        out << "time_s,rotation_rad,base_acceleration_m_s2\n";
        for (std::size_t k = 0; k < r.time.size(); ++k) out << fmt::format("{},{},{}\n", r.time[k], r.rotation[k], r.base_acceleration[k]);
      });
    }
    if (json) {
      io::JsonObject j;
      j.add("uplift", r.uplift).add("max_rotation_rad", r.max_rotation).add("max_rotation_deg", r.max_rotation * 180 / pi)
          .add("max_penetration_m", r.max_penetration).add("impacts", r.impacts)
          .add("restitution", std::span<const double>(r.restitution)).add("housner_restitution", r.housner_restitution)
          .add("overturned", r.overturned).add("uplift_threshold_m_s2", 9.81 * o.width / o.height)
          .add("steps", static_cast<long long>(r.steps)).add("dt", r.timestep).add("wall_seconds", r.wall_seconds)
          .add("dt_critical_unscaled", r.dt_critical_unscaled).add("mass_increase_percent", r.mass_increase_percent)
          .add("nodes", static_cast<int>(r.nodes)).add("tetrahedra", static_cast<int>(r.tetrahedra))
          .add("contact_points", static_cast<int>(r.contact_points));
      fmt::print("{}\n", j.str());
    } else {
      fmt::print("block {:g} x {:g} x {:g} m (tan alpha = {:.4f}, static uplift at {:.4f} m/s^2)\n", o.width, o.depth,
                 o.height, o.width / o.height, 9.81 * o.width / o.height);
      fmt::print("uplift: {}, max rotation {:.4e} rad ({:.2f} deg), {} impacts, {}\n", r.uplift ? "yes" : "no", r.max_rotation,
                 r.max_rotation * 180 / pi, r.impacts, r.overturned ? "OVERTURNED" : "did not overturn");
      if (!o.deformable) fmt::print("deepest penetration into the base {:.3e} m\n", r.max_penetration);
      if (!r.restitution.empty())
        fmt::print("restitution at the impacts (omega after / before): {:.3f} (Housner 1 - 1.5 sin^2 alpha = {:.3f})\n",
                   fmt::join(r.restitution, ", "), r.housner_restitution);
      fmt::print("{} steps of {:.3e} s in {:.2f} s\n", r.steps, r.timestep, r.wall_seconds);
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "rocking_block: error: %s\n", e.what());
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "rocking_block: error: %s\n", e.what());
    return 2;
  } catch (const RunawayError& e) {
    std::fprintf(stderr, "rocking_block: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
