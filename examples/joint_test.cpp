// joint_test: one elasto-softening contact (paper Sect. 3.1, Fig. 5C) of a given area driven along a displacement
// path; prints the peak, residual and dissipated energy against the strengths and fracture energies of eq. 4-7, and
// writes the stress-displacement curve as CSV (scripts/plot_joint_curve.py plots it).
//
//   joint_test [--path tension|shear|compression|cyclic-tension|cyclic-shear] [--normal-stress 0.5e6] [--area 0.01]
//              [--steps 2000] [--amplitude A] [--cycles 4] [--csv FILE] [--json]
//              [material: --unit-modulus --mortar-modulus --mortar-thickness --poisson-ratio --tensile-strength
//               --compressive-strength --cohesion --friction-angle --residual-friction-angle --cap-shear-factor]
//
// Material defaults: the paper's Table 1 with t_m = 10 mm. SI units (Pa, m), angles in degrees. Exit status 2 on bad
// input, with a message naming the option and its allowed range.

#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/joint_test.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/json.hpp"
#include "cli.hpp"

namespace {

using namespace blockdem;

void write_csv(const std::string& path, const analysis::JointTestOptions& o, const analysis::JointTestResult& r) {
  io::write_atomically(path, [&](std::ostream& out) {
    out << fmt::format("# joint_test path={} area_m2={} normal_stress_pa={} amplitude_m={}\n", analysis::to_string(o.path),
                       o.area, o.normal_stress, r.amplitude);
    out << "step,opening_m,slip_m,normal_stress_pa,shear_stress_pa,normal_force_n,shear_force_n,damage,dissipated_j_m2,"
           "stored_j_m2\n";
    for (std::size_t k = 0; k < r.samples.size(); ++k) {
      const auto& s = r.samples[k];
      out << fmt::format("{},{},{},{},{},{},{},{},{},{}\n", k, s.opening, s.slip, s.normal_stress, s.shear_stress,
                         o.area * s.normal_stress, o.area * s.shear_stress, s.damage, s.dissipated, s.stored);
    }
  });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"One elasto-softening joint driven along a displacement path (blockdem)"};
  analysis::JointTestOptions o;
  contact::MasonryJointProperties m;
  std::string path = "tension", csv;
  double friction_deg = 38, residual_friction_deg = -1, cap_shear_factor = 9;
  bool json = false;
  app.add_option("--path", path, "tension, shear, compression, cyclic-tension or cyclic-shear")
      ->check(CLI::IsMember({"tension", "shear", "compression", "cyclic-tension", "cyclic-shear"}))
      ->capture_default_str();
  app.add_option("--normal-stress", o.normal_stress, "Pa, compression positive, held during shear, in (-f_t, f_c)")
      ->capture_default_str();
  app.add_option("--area", o.area, "contact area, m^2, > 0")->capture_default_str();
  app.add_option("--steps", o.steps, "steps of the driven path, 10..10000000")->capture_default_str();
  app.add_option("--amplitude", o.amplitude,
                 "m, largest opening, slip or closure; 0: where the strength above residual is 1e-6 of its peak")
      ->capture_default_str();
  app.add_option("--cycles", o.cycles, "cyclic paths: amplitudes A/n, 2A/n, ..., A; 1..1000")->capture_default_str();
  app.add_option("--csv", csv, "write the curve (step, opening, slip, stresses, forces, damage, energies) to this file");
  app.add_flag("--json", json, "print a JSON object");
  app.add_option("--unit-modulus", m.unit_modulus, "E_b, Pa (eq. 7)")->capture_default_str();
  app.add_option("--mortar-modulus", m.mortar_modulus, "E_m, Pa (eq. 7)")->capture_default_str();
  app.add_option("--mortar-thickness", m.mortar_thickness, "t_m, m (eq. 7)")->capture_default_str();
  app.add_option("--poisson-ratio", m.poisson_ratio, "nu (eq. 7)")->capture_default_str();
  app.add_option("--tensile-strength", m.tensile_strength, "f_t, Pa (and G_f^I by eq. 4)")->capture_default_str();
  app.add_option("--compressive-strength", m.compressive_strength, "f_c, Pa (and G_c by eq. 6)")->capture_default_str();
  app.add_option("--cohesion", m.cohesion, "c, Pa")->capture_default_str();
  app.add_option("--friction-angle", friction_deg, "phi, degrees")->capture_default_str();
  app.add_option("--residual-friction-angle", residual_friction_deg, "phi_r, degrees (default: phi)");
  app.add_option("--cap-shear-factor", cap_shear_factor, "C_s of the elliptic cap, >= 0 (0: none)")->capture_default_str();
  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;
  try {
    o.path = analysis::joint_path_from_string(path);
    m.friction_angle = friction_deg * pi / 180.0;
    o.joint = contact::ElastoSoftening::Parameters::from_material(m, cap_shear_factor);
    if (residual_friction_deg >= 0) {
      const auto& j = o.joint;
      o.joint = contact::ElastoSoftening::Parameters(
          {j.normal_stiffness, j.shear_stiffness},
          {j.tensile_strength, j.cohesion, j.friction_angle, j.compressive_strength, 0, 0, residual_friction_deg * pi / 180.0},
          {j.tension_fracture_energy, j.shear_fracture_energy, j.compression_fracture_energy}, cap_shear_factor);
    }
    const auto r = analysis::run_joint_test(o);
    if (!csv.empty()) write_csv(csv, o, r);
    const auto& p = o.joint;
    const bool shear = o.path == analysis::JointPath::shear || o.path == analysis::JointPath::cyclic_shear;
    if (json) {
      io::JsonObject j;
      j.add("path", analysis::to_string(o.path))
          .add("area_m2", o.area)
          .add("steps", static_cast<long long>(r.samples.size() - 1))
          .add("amplitude_m", r.amplitude)
          .add("peak_stress_pa", r.peak_stress)
          .add("expected_peak_stress_pa", r.expected_peak)
          .add("peak_force_n", r.peak_stress * o.area)
          .add("residual_stress_pa", r.residual_stress)
          .add("dissipated_energy_per_area", r.dissipated)
          .add("dissipated_energy_j", r.dissipated * o.area)
          .add("final_damage", r.final_damage)
          .add("failed", r.failed)
          .add("work_per_area", r.work)
          .add("stored_energy_per_area", r.stored)
          .add("energy_balance_error", r.energy_balance_error)
          .add("normal_stiffness_pa_m", p.normal_stiffness)
          .add("shear_stiffness_pa_m", p.shear_stiffness)
          .add("fracture_energy_tension", p.tension_fracture_energy)
          .add("fracture_energy_shear", p.shear_fracture_energy)
          .add("fracture_energy_compression", p.compression_fracture_energy);
      if (shear) j.add("normal_stress_pa", o.normal_stress);
      fmt::print("{}\n", j.str());
    } else {
      fmt::print("joint_test: {} path, {:g} m^2 contact, {} steps to {:.4g} mm{}\n", analysis::to_string(o.path), o.area,
                 r.samples.size() - 1, 1e3 * r.amplitude,
                 shear ? fmt::format(" under {:.4g} MPa", o.normal_stress / 1e6) : std::string());
      fmt::print("joint (eq. 4-7): k_n = {:.4e} Pa/m, k_s = {:.4e} Pa/m, G_f^I = {:.4f}, G_f^II = {:.4f}, G_c = {:.1f} J/m^2\n",
                 p.normal_stiffness, p.shear_stiffness, p.tension_fracture_energy, p.shear_fracture_energy,
                 p.compression_fracture_energy);
      fmt::print("peak {:.6f} MPa (expected {:.6f} MPa), residual {:.6g} MPa\n", r.peak_stress / 1e6, r.expected_peak / 1e6,
                 r.residual_stress / 1e6);
      fmt::print("dissipated {:.6f} J/m^2 ({:.6g} J), final damage {:.6f}{}, energy balance error {:.1e}\n", r.dissipated,
                 r.dissipated * o.area, r.final_damage, r.failed ? " (failed)" : "", r.energy_balance_error);
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "joint_test: error: %s\n", e.what());
    return programs::exit_bad_input;
  }
  return 0;
}
