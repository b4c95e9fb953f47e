// cross_vault: the full-scale brick cross vault of the LNEC shake-table test (paper Sect. 2, 3.2, 5).
//
//   cross_vault run [--out DIR] [--record FILE] [--levels 25,50,75] [--damping none|mass|stiffness|rayleigh|maxwell] [...]
//       settles the vault under gravity and shakes it at each level in turn (the incremental analysis of Sect. 5),
//       writing histories, damage maps, report.json and the Table 4 of the run into DIR;
//   cross_vault sweep SWEEP.json [--out DIR] [--case K] [--list] [--summarize] [the options of run]
//       runs every case of a sweep (damping schemes and their grids x records x levels or intensity targets x
//       kinematics) into DIR/cases/<id>/ and sums them up in DIR/summary.csv; under `mpirun -np N` when built with MPI;
//   cross_vault model [the options of run] > vault.json
//       writes the vault and its study as a model file (docs/model-file.md): `blockdem run vault.json` is that run;
//   cross_vault --geometry-only [--vtk vault.vtu] [--contacts-vtk cps.vtu] [--json] [--profile segmental|elliptical] [...]
//       builds and checks the blocks of every component (validity, overlaps, contacts, masses) and writes them out.
//
// Exit status: 0 on success, 1 if the assembly check fails, a run is interrupted or diverges, or a case of a sweep
// fails, 2 on bad input.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/error_metrics.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/integrate/run.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/io/vtk.hpp"
#include "blockdem/models/cross_vault.hpp"
#include "cli.hpp"
#include "study_cli.hpp"
#include "study_runs.hpp"
#include "sweep_cli.hpp"

namespace {

std::string vector_json(const blockdem::Vec3& p) {
  using blockdem::io::JsonObject;
  return "[" + JsonObject::number(p.x()) + ", " + JsonObject::number(p.y()) + ", " + JsonObject::number(p.z()) + "]";
}

/// The options of `cross_vault run`: the study's (study_cli.hpp) and the vault's kinematics.
struct RunCommand {
  blockdem::analysis::VaultStudyOptions study;
  blockdem::programs::StudyCommand common;
  CLI::Option* out = nullptr;

  void add_to(CLI::App& app) {
    auto& o = study;
    o.out_dir = "vault_run";
    common.add_to(app, o, "the vault");
    out = common.out;
    app.add_option("--kinematics", o.kinematics, "rigid blocks, mixed (steel frame rigid, the rest deformable, Sect. 6.1.1) "
                                                 "or deformable (constant-strain tetrahedra, Sect. 5)")
        ->transform(CLI::CheckedTransformer(std::map<std::string, blockdem::analysis::VaultKinematics>{
            {"rigid", blockdem::analysis::VaultKinematics::rigid},
            {"mixed", blockdem::analysis::VaultKinematics::mixed},
            {"deformable", blockdem::analysis::VaultKinematics::deformable}}))
        ->capture_default_str();
    app.add_option("--max-edge", o.max_edge, "mixed, deformable: largest tetrahedron edge in masonry and concrete, m [0.01, 10]")
        ->capture_default_str();
    app.add_option("--steel-max-edge", o.steel_max_edge,
                   "deformable: largest tetrahedron edge in the steel frame and the movable piers, m [0.01, 10]")->capture_default_str();
    app.get_option("--record")->description("acceleration record (PEER .AT2, ESM ASCII, text); default: the built-in synthetic AQA75 stand-in");
    for (CLI::Option* option : app.get_options()) option->capture_default_str();  // the vault study's defaults in --help
  }

  void finish() {
    if (common.axis_option->count() > 0 && common.axis == "z") throw blockdem::InvalidArgument("--axis must be x or y, got 'z'");
    common.finish(study);
  }
};

/// `cross_vault compare`: the Sect. 5 error metrics of a run's histories against measured channels.
struct CompareCommand {
  std::string dir, measured, level = "75";
  bool json = false;

  void add_to(CLI::App& app) {
    app.add_option("dir", dir, "output folder of a `cross_vault run`")->required();
    app.add_option("--measured", measured, "measured channels: CSV with a time column and columns named like the history's "
                                           "(OC1_uy in m, ACC18_ay in m/s^2, ...)")->required();
    app.add_option("--level", level, "the level whose history_<level>.csv is compared")->capture_default_str();
    app.add_flag("--json", json, "print JSON");
  }

  int run() const {
    using namespace blockdem;
    if (std::filesystem::is_directory(measured)) throw InvalidArgument("--measured: '" + measured + "' is a folder, not a CSV file");
    const auto simulated = analysis::read_csv_table(dir + "/history_" + level + ".csv");
    const auto measured_table = analysis::read_csv_table(measured);
    const auto comparisons = analysis::compare_tables(simulated, measured_table);
    std::vector<io::JsonObject> channels;
    if (!json)
      fmt::print("{:<10} {:>8} {:>12} {:>12} {:>10} {:>9} {:>9} {:>9} {:>9}\n", "channel", "samples", "RMSD num", "RMSD exp",
                 "eps RMSD%", "NRMSE%", "max err%", "min err%", "RE_max%");
    for (const auto& c : comparisons) {
      if (json) {
        io::JsonObject j;
        j.add("channel", c.channel).add("samples", static_cast<long long>(c.samples)).add("rmsd_num", c.rmsd_num)
            .add("rmsd_exp", c.rmsd_exp).add("rmsd_error_percent", c.rmsd_error_percent).add("nrmse_percent", c.nrmse_percent)
            .add("peak_max_signed_percent", c.peaks.max_signed_percent).add("peak_min_signed_percent", c.peaks.min_signed_percent)
            .add("absolute_peak_percent", c.peaks.absolute_peak_percent).add("re_max_percent", c.re_max_percent)
            .add("re_min_percent", c.re_min_percent);
        channels.push_back(j);
      } else {
        fmt::print("{:<10} {:>8} {:>12.4g} {:>12.4g} {:>10.2f} {:>9.2f} {:>+9.2f} {:>+9.2f} {:>9.2f}\n", c.channel, c.samples,
                   c.rmsd_num, c.rmsd_exp, c.rmsd_error_percent, c.nrmse_percent, c.peaks.max_signed_percent,
                   c.peaks.min_signed_percent, c.re_max_percent);
      }
    }
    io::JsonObject out;
    out.add("history", dir + "/history_" + level + ".csv").add("measured", measured).add("channels", channels);
    for (const char* suffix : {"_ux", "_uy"}) {
      try {
        const double e = analysis::mean_rmsd_error_percent(comparisons, suffix);  // eq. 27-28 over OC1, OC2, OC4
        if (json) out.add(std::string("mean_rmsd_error_percent") + suffix, e);
        else fmt::print("eq. 27-28 over OC1, OC2, OC4 ({}): {:.2f} %\n", suffix + 1, e);
      } catch (const InvalidArgument& e) {  // a direction or a camera the measurement does not have: say which
        if (json) out.add(std::string("mean_rmsd_error_percent") + suffix + "_not_computed", std::string(e.what()));
        else fmt::print("eq. 27-28 over OC1, OC2, OC4 ({}): not computed: {}\n", suffix + 1, e.what());
      }
    }
    if (json) fmt::print("{}\n", out.str());
    return 0;
  }
};

/// The vault's study (analysis::run_vault_study), compiled in study_runs.cpp.
blockdem::analysis::StudyResult vault_study(const blockdem::analysis::VaultStudyOptions& o) {
  o.validate();
  return blockdem::programs::run_study(blockdem::analysis::vault_structure(o), o);
}

int run_study(RunCommand& command) {
  using namespace blockdem;
  command.finish();
  stop_on_interrupt();
  const auto r = vault_study(command.study);
  if (command.common.json) {
    fmt::print("{}\n", analysis::detail::report_json(r));
    return r.interrupted ? 1 : 0;
  }
  fmt::print("input: {}{} ({}, baseline {}), PGA {:.3f} m/s^2 at {:g} %\n", r.input.name,
             r.input.synthetic ? " [SYNTHETIC stand-in, not the AQA recording]" : "", r.input.cut, r.input.baseline, r.input.pga,
             command.study.record_level);
  fmt::print("model: {} blocks ({}: {} deformable, {} nodes, {} tetrahedra), {} ties, {} contact points, {:.0f} kg free\n",
             r.model.blocks, analysis::name(command.study.kinematics), r.model.deformable_blocks, r.model.nodes,
             r.model.tetrahedra, r.model.ties, r.model.contact_points, r.model.free_mass);
  fmt::print("settling: {} steps, unbalanced force ratio {:.2e}{}, {:.1f} s; damaged joints once settled {} (cracked {}, crushed {})\n",
             r.settling.steps, r.settling.unbalanced_ratio, r.settling.converged ? "" : " (NOT converged)", r.settling.wall_seconds,
             r.settling.damaged_joints, r.settling.cracked_joints, r.settling.crushed_joints);
  fmt::print("damping: {}{}\n", r.damping.description, r.damping.frame.empty() ? std::string() : fmt::format(", in the {} frame", r.damping.frame));
  for (const auto& w : r.warnings) fmt::print("warning: {}\n", w);
  if (r.free_vibration.measured)
    fmt::print("free vibration at OC1: {:.2f} Hz, damping ratio {:.4f} (the scheme's at that frequency: {:.4f})\n",
               r.free_vibration.decay.frequency_hz, r.free_vibration.decay.damping_ratio, r.free_vibration.expected_damping_ratio);
  fmt::print("timestep: {:.3e} s (critical {:.3e} s unscaled, damping factor {:.4f}); density scaling adds {:.3f} % of the mass over {} blocks and {} nodes\n",
             r.timestep.dt, r.timestep.critical_unscaled, r.timestep.damping_factor, r.timestep.scaling.mass_increase_percent,
             r.timestep.scaling.scaled_blocks, r.timestep.scaling.scaled_nodes);
  for (const auto& L : r.levels) {
    auto peak = [&](const std::string& channel) {
      for (const auto& p : L.peaks)
        if (p.name == channel) return fmt::format("{:+.2f}/{:+.2f}", p.max, p.min);
      return std::string("-");
    };
    fmt::print("level {:g} %: {} steps in {:.1f} s ({:.0f} steps/s){}; OC1-y {} mm, ACC18-y {} m/s^2; damaged joints {} (cracked {}, "
               "crushed {}, slipped {}){}; energy balance error {:.2e}\n",
               L.level, L.steps, L.wall_seconds, L.steps_per_second(), L.interrupted ? " INTERRUPTED" : "",
               [&] {
                 for (const auto& p : L.peaks)
                   if (p.name == "OC1_uy") return fmt::format("{:+.2f}/{:+.2f}", 1e3 * p.max, 1e3 * p.min);
                 return std::string("-");
               }(),
               peak("ACC18_ay"), L.damage.total.damaged, L.damage.total.cracked, L.damage.total.crushed, L.damage.total.slipped,
               (L.damage.total.new_contacts > 0 ? fmt::format("; {} new contact points", L.damage.total.new_contacts) : std::string()) +
                   (L.damage.loose_blocks > 0 ? fmt::format("; {} blocks without contact (fallen out or in flight)", L.damage.loose_blocks) : std::string()),
               L.energy.balance_error);
    if (L.collapse.collapsed)
      fmt::print("  COLLAPSED {:.3f} s into the level: {} moved {:.3f} m from where it settled (--collapse-displacement {:g} m)\n",
                 L.collapse.time, L.collapse.point, L.collapse.displacement, command.study.collapse_displacement);
    if (L.hold.raises > 0)
      fmt::print("  new contacts held the timestep: {} times, {} nodes and {} blocks made heavier, +{:.3g} kg in all so far\n",
                 L.hold.raises, L.hold.raised_nodes, L.hold.raised_blocks, L.hold.added_mass);
  }
  fmt::print("\n{}", analysis::table4(r));
  fmt::print("outputs in {}/ (report.json, history_<level>.csv, damage_<level>.vtu, contacts_<level>.vtu/.csv); plots: "
             "python3 scripts/plot_vault.py {}\n", command.study.out_dir, command.study.out_dir);
  if (r.interrupted)
    fmt::print("stopped early; continue with the same options and --resume {}/{}\n", command.study.out_dir,
               analysis::study_checkpoint_file);
  return r.interrupted ? 1 : 0;
}

/// `cross_vault sweep`: the vault's cases, the options of `run` as their base.
struct SweepCommand {
  RunCommand base;
  blockdem::programs::SweepCommand sweep;

  void add_to(CLI::App& app) {
    base.add_to(app);
    base.study.out_dir = "vault_sweep";
    base.out->description("the sweep's folder: cases/<id>/ per case, summary.csv and summary.json")->default_str("vault_sweep");
    sweep.add_to(app, "the sweep file (JSON: damping schemes and their grids, records, levels or intensity targets, "
                      "kinematics; docs/sweeps.md)");
  }

  int run(int argc, char** argv) {
    using namespace blockdem;
    sweep.refuse_grid_options();
    base.finish();
    const analysis::SweepSpec spec = analysis::read_sweep_file(sweep.spec);
    if (!spec.model.empty())
      throw InvalidArgument(sweep.spec + ": names the model file '" + spec.model + "': run it with `blockdem sweep " +
                            sweep.spec + "` (cross_vault sweep studies the vault)");
    analysis::SweepRunOptions run;
    run.out_dir = base.study.out_dir;
    run.fingerprint = sweep.fingerprint(argc, argv, spec);
    run.measured = spec.measured;
    run.measured_level = spec.measured_level;
    run.progress = base.study.progress;
    run.study = vault_study;
    return programs::run_sweep_command("cross_vault sweep", sweep, analysis::expand_sweep(spec, base.study), run, argc, argv);
  }
};

}  // namespace

int main(int argc, char** argv) {
  using namespace blockdem;
  using models::Component;
  CLI::App app{"The LNEC masonry cross vault: geometry, components, materials and contacts (blockdem)"};
  models::CrossVaultOptions o;
  model::ContactSettings contacts;
  contacts.kinds = model::ContactKinds::faces;  // the vault's joints, as `run` detects them by default
  bool geometry_only = false, json = false;
  std::string vtk_path, contacts_vtk_path;
  app.add_flag("--geometry-only", geometry_only, "build and check the model and write it out");
  RunCommand run;
  auto* run_app = app.add_subcommand("run", "settle the vault and shake it at each level in turn (the incremental analysis of Sect. 5)");
  run.add_to(*run_app);
  run_app->fallthrough();  // the geometry options may follow `run`
  SweepCommand sweep;
  auto* sweep_app = app.add_subcommand("sweep", "many analyses from a sweep file: damping grids, records, levels or intensity "
                                                "targets (Sect. 5, Table 3; IDA), on MPI ranks when built with MPI");
  sweep.add_to(*sweep_app);
  sweep_app->fallthrough();
  RunCommand model_command;
  auto* model_app = app.add_subcommand("model", "write the vault and the study of the options of `run` as a model file "
                                                "(docs/model-file.md) on stdout: `blockdem run` on it is `cross_vault run`");
  model_command.add_to(*model_app);
  model_app->fallthrough();
  CompareCommand compare;
  auto* compare_app = app.add_subcommand("compare", "error metrics of Sect. 5 (eq. 26-30) of a run against measured channels");
  compare.add_to(*compare_app);
  app.add_option("--vtk", vtk_path, "write the blocks with their component and material as cell fields (.vtu)");
  app.add_option("--contacts-vtk", contacts_vtk_path,
                 "write the contact points with their joint kind, components, gap, area and normal (.vtu)");
  app.add_flag("--json", json, "print a JSON summary");
  app.add_option("--profile", o.profile, "profile of both barrels: segmental (circular arc, rise <= span/2) or elliptical")
      ->transform(CLI::CheckedTransformer(std::map<std::string, models::VaultProfile>{
          {"segmental", models::VaultProfile::segmental}, {"elliptical", models::VaultProfile::elliptical}}))
      ->capture_default_str();
  app.add_option("--plan", o.plan_size, "side of the square plan, m")->capture_default_str();
  app.add_option("--span", o.span, "net span of each barrel at the intrados, m")->capture_default_str();
  app.add_option("--rise", o.rise, "intrados crown above the springing, m (segmental: <= span/2)")->capture_default_str();
  app.add_option("--thickness", o.thickness, "ring thickness, m")->capture_default_str();
  app.add_option("--unit-height", o.unit_height, "brick height along the arc, m")->capture_default_str();
  app.add_option("--unit-length", o.unit_length, "brick length along the barrel axis, m")->capture_default_str();
  app.add_option("--joint", o.joint_thickness, "mortar joint thickness, m")->capture_default_str();
  app.add_option("--infill-fraction", o.infill_rise_fraction, "infill height over the rise, [0, 1)")->capture_default_str();
  app.add_option("--min-block-fraction", o.min_block_fraction,
                 "groin pieces below this fraction of a whole block merge into their neighbour, [0, 0.5)")->capture_default_str();
  app.add_option("--pier-height", o.pier_height, "slab top to the tie anchors, m (assumed)")->capture_default_str();
  app.add_option("--anchor-height", o.anchor_height, "tie anchor blocks on the piers, m (assumed)")->capture_default_str();
  app.add_option("--masonry-density", o.masonry_density, "kg/m^3 (assumed; not in the paper)")->capture_default_str();
  app.add_option("--residual-compressive-strength", o.residual_compressive_strength,
                 "f_c,r: compressive stress that a joint crushed through still carries, Pa [0, f_c); the paper's law has 0, "
                 "and then blocks that crush their joints pass through each other (runs past its levels)")
      ->capture_default_str();
  app.add_option("--contact-tolerance", contacts.tolerance, "contact detection tolerance, m")->capture_default_str();
  app.add_option("--max-cp-area", contacts.max_contact_point_area, "largest area per contact point, m^2, 0 or >= 1e-4 (0: CPs at the corners)")
      ->capture_default_str();
  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;
  if (compare_app->parsed() || run_app->parsed() || sweep_app->parsed() || model_app->parsed()) {
    const char* command = compare_app->parsed() ? "compare" : run_app->parsed() ? "run" : model_app->parsed() ? "model" : "sweep";
    run.study.vault = o;
    sweep.base.study.vault = o;
    model_command.study.vault = o;
    auto bad_input = [&](const std::exception& e) {
      std::fprintf(stderr, "cross_vault %s: error: %s\n", command, e.what());
      return programs::exit_bad_input;
    };
    try {
      if (sweep_app->parsed()) return sweep.run(argc, argv);
      if (model_app->parsed()) {
        model_command.finish();
        model_command.study.validate();
        analysis::write_model_file(std::cout, analysis::vault_description(model_command.study), model_command.study);
        return std::cout.flush() ? 0 : 1;
      }
      return compare_app->parsed() ? compare.run() : run_study(run);
    } catch (const InvalidArgument& e) {
      return bad_input(e);
    } catch (const InputError& e) {  // a malformed record or table
      return bad_input(e);
    } catch (const RunawayError& e) {
      std::fprintf(stderr, "cross_vault %s: %s\n", command, e.what());
      return 1;
    }
  }
  if (!geometry_only) {
    std::fprintf(stderr, "cross_vault: say what to do: `cross_vault run [...]` for the analysis, or --geometry-only\n");
    return programs::exit_bad_input;
  }
  try {
    contacts.validate();
    // A smaller area splits each joint into so many CPs that the check takes hours (1e-4: a second or two).
    if (contacts.max_contact_point_area != 0 && !(contacts.max_contact_point_area >= 1e-4))
      throw InvalidArgument(fmt::format("--max-cp-area must be 0 or >= 1e-4 m^2, got {:g}", contacts.max_contact_point_area));
    const auto t0 = std::chrono::steady_clock::now();
    const auto vault = models::make_cross_vault(o);
    const auto model = models::build_rigid_model(vault);
    const double generation_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto t1 = std::chrono::steady_clock::now();
    const auto check = models::check_assembly(vault, model, contacts);
    const double check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    const bool passed = check.max_penetration <= contacts.tolerance && check.vault_connected &&
                        check.vault_blocks_below_two_neighbours == 0 && check.max_mass_error() <= 0.02;

    if (!vtk_path.empty()) {
      io::BlockFields fields;
      for (const auto& b : vault.blocks) {
        fields["component"].push_back(static_cast<double>(models::index(b.component)));
        fields["material"].push_back(static_cast<double>(b.material));
      }
      io::write_blocks_vtu(vtk_path, model, fields);
    }
    if (!contacts_vtk_path.empty()) {
      std::vector<Vec3> points, normals;
      io::BlockFields fields;
      for (const auto& c : check.contacts) {
        const auto [a, b] = vault.components(c);
        points.push_back(c.position);
        normals.push_back(c.normal);
        fields["joint_kind"].push_back(static_cast<double>(vault.joint(c).kind));
        fields["component_a"].push_back(static_cast<double>(models::index(a)));
        fields["component_b"].push_back(static_cast<double>(models::index(b)));
        fields["gap"].push_back(c.gap);
        fields["area"].push_back(c.area);
      }
      io::write_points_vtu(contacts_vtk_path, points, fields, {{"normal", normals}});
    }

    const auto& opt = vault.options;
    if (json) {
      io::JsonObject blocks, mass, analytical, boxes, joints, by_joint;
      for (const auto c : models::all_components) {
        const auto i = models::index(c);
        const std::string key(models::name(c));
        blocks.add(key, static_cast<long long>(vault.count(c)));
        mass.add(key, check.mass[i]);
        analytical.add(key, check.analytical_mass[i]);
        const auto box = models::bounding_box(vault, c);
        boxes.add_raw(key, "[" + vector_json(box[0]) + ", " + vector_json(box[1]) + "]");
      }
      blocks.add("total", static_cast<long long>(vault.blocks.size()));
      for (const auto kind : {models::JointKind::Softening, models::JointKind::MohrCoulombFriction, models::JointKind::ElasticSteel}) {
        by_joint.add(models::name(kind), static_cast<long long>(check.contact_points_by_joint[static_cast<std::size_t>(kind)]));
        const auto& p = kind == models::JointKind::Softening ? vault.joint(Component::vault, Component::vault)
                        : kind == models::JointKind::MohrCoulombFriction ? vault.joint(Component::movable_pier, Component::slab)
                                                                         : vault.joint(Component::steel_frame, Component::slab);
        io::JsonObject j;
        j.add("normal_stiffness_pa_m", p.normal_stiffness).add("shear_stiffness_pa_m", p.shear_stiffness)
            .add("friction_angle_deg", p.friction_angle * 180 / pi).add("cohesion_pa", p.cohesion)
            .add("tensile_strength_pa", p.tensile_strength);
        if (kind == models::JointKind::Softening)
          j.add("compressive_strength_pa", p.compressive_strength).add("residual_compressive_strength_pa", p.residual_compressive_strength)
              .add("fracture_energy_tension_n_m", p.fracture_energy_tension)
              .add("fracture_energy_shear_n_m", p.fracture_energy_shear).add("fracture_energy_compression_n_m", p.fracture_energy_compression);
        joints.add(models::name(kind), j);
      }
      std::vector<io::JsonObject> monitors;
      for (const auto& p : vault.monitor_points) {
        io::JsonObject m;
        m.add("name", p.name).add_raw("position", vector_json(p.position)).add("block", static_cast<long long>(p.block))
            .add("block_name", vault.blocks[p.block].name).add("component", models::name(vault.blocks[p.block].component));
        monitors.push_back(m);
      }
      io::JsonObject out;
      out.add("profile", o.profile == models::VaultProfile::segmental ? "segmental" : "elliptical")
          .add("courses_per_barrel", vault.courses)
          .add("intrados_radius_m", vault.radius)
          .add("springing_level_m", vault.springing_level())
          .add("crown_extrados_m", vault.extrados_level(0, 0))
          .add("blocks", blocks)
          .add("contact_points", static_cast<long long>(check.contact_points))
          .add("open_contact_points", static_cast<long long>(check.open_contact_points))
          .add("contact_points_by_joint", by_joint)
          .add("mass_kg", mass)
          .add("analytical_mass_kg", analytical)
          .add("max_mass_error", check.max_mass_error())
          .add("bounding_box_m", boxes)
          .add("monitor_points", monitors)
          .add("ties", static_cast<long long>(vault.ties.size()))
          .add("tie_mass_kg", check.tie_mass)
          .add("joints", joints)
          .add("vault_slivers_merged", static_cast<long long>(vault.vault_slivers_merged))
          .add("infill_pieces_dropped", static_cast<long long>(vault.infill_pieces_dropped))
          .add("infill_volume_dropped_m3", vault.infill_volume_dropped)
          .add("max_penetration_m", check.max_penetration)
          .add("vault_connected", check.vault_connected)
          .add("min_vault_neighbours", static_cast<long long>(check.min_vault_neighbours))
          .add("generation_seconds", generation_seconds)
          .add("detection_seconds", check.detection_seconds)
          .add("check_seconds", check_seconds)
          .add("checks_passed", passed);
      fmt::print("{}\n", out.str());
    } else {
      fmt::print("cross vault: {} profile, span {:g} m, rise {:g} m, ring {:g} m, plan {:g} x {:g} m, {} courses per barrel{}\n",
                 o.profile == models::VaultProfile::segmental ? "segmental" : "elliptical", opt.span, opt.rise, opt.thickness,
                 opt.plan_size, opt.plan_size, vault.courses,
                 vault.radius > 0 ? fmt::format(" (intrados radius {:.4f} m)", vault.radius) : std::string());
      fmt::print("{:<14} {:>7} {:>12} {:>12} {:>9}\n", "component", "blocks", "mass kg", "analytical", "error");
      for (const auto c : models::all_components) {
        const auto i = models::index(c);
        fmt::print("{:<14} {:>7} {:>12.2f} {:>12.2f} {:>8.3f}%\n", models::name(c), vault.count(c), check.mass[i],
                   check.analytical_mass[i], 100 * (check.mass[i] / check.analytical_mass[i] - 1));
      }
      fmt::print("{} blocks; {} groin pieces merged into their neighbours; {} infill pieces dropped ({:.3g} m^3)\n",
                 vault.blocks.size(), vault.vault_slivers_merged, vault.infill_pieces_dropped, vault.infill_volume_dropped);
      fmt::print("{} contact points ({} softening, {} Mohr-Coulomb, {} elastic; {} open beyond the tolerance), deepest "
                 "overlap {:.2e} m, vault contact graph {}, every vault block touches >= {} vault blocks\n",
                 check.contact_points, check.contact_points_by_joint[0], check.contact_points_by_joint[1],
                 check.contact_points_by_joint[2], check.open_contact_points, check.max_penetration,
                 check.vault_connected ? "connected" : "NOT connected", check.min_vault_neighbours);
      fmt::print("{} ties ({:.1f} kg); monitor points:", vault.ties.size(), check.tie_mass);
      for (const auto& p : vault.monitor_points)
        fmt::print(" {} ({:.3f}, {:.3f}, {:.3f})", p.name, p.position.x(), p.position.y(), p.position.z());
      fmt::print("\ngenerated in {:.3f} s, checked in {:.3f} s (detection {:.3f} s): {}\n", generation_seconds, check_seconds,
                 check.detection_seconds, passed ? "all checks passed" : "CHECKS FAILED");
    }
    if (!passed) {
      std::fprintf(stderr, "cross_vault: the assembly check failed (overlap, connectivity or mass beyond 2 %%)\n");
      return 1;
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "cross_vault: error: %s\n", e.what());
    return programs::exit_bad_input;
  }
  return 0;
}
