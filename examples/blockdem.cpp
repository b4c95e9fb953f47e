// blockdem: the study of any block structure written as a model file (docs/model-file.md).
//
//   blockdem run MODEL.json [--out DIR] [--levels 25,50,100] [--damping none|mass|stiffness|rayleigh|maxwell] [...]
//       settles the structure under gravity and shakes it at each level of the model file's record in turn, writing
//       histories, damage maps, report.json and the run's Table 4 into DIR; every option overrides the file's;
//       with "analysis": "pushover" in the file, the equivalent-static pushover instead: the collapse multiplier;
//   blockdem check FILE [--json]
//       a model file or a geometry file alone (OBJ, 3DEC deck, COMPAS): the blocks, then each problem by block (not
//       closed, not planar, not convex, no volume, overlapping, touching nothing; inward faces turned); for a model
//       file also its contacts and the pairs of groups that touch without a joint law; exit status 2 when a block
//       cannot be used. `blockdem run` runs the same checks first;
//   blockdem generate wall|barrel-vault|arch|cross-vault [options] [--pushover] > MODEL.json
//       the model file of a common typology (docs/generators.md), run as it is by `blockdem run`;
//   blockdem export FILE OUT.obj|OUT.3ddat
//       the blocks of a model or geometry file written as Wavefront OBJ or a 3DEC deck;
//
// Exit status: 0 on success, 1 if a run is interrupted or diverges, 2 on bad input.

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/model_sweep.hpp"
#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/analysis/study.hpp"
#include "blockdem/integrate/run.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "check_cli.hpp"
#include "generate_cli.hpp"
#include "cli.hpp"
#include "study_cli.hpp"
#include "study_runs.hpp"
#include "sweep_cli.hpp"

namespace {

using namespace blockdem;

/// The checks of `blockdem check` (docs/geometry-import.md), run before a study: what makes a block unusable is
/// refused with the list; warnings go to stderr.
void refuse_unusable(const analysis::ModelFile& file, const std::string& path) {
  for (const auto& w : analysis::refuse_unusable(file.structure, file.geometry_issues, file.block_origin, path))
    std::fprintf(stderr, "blockdem: warning: %s: %s\n", path.c_str(), w.c_str());
}

/// `blockdem run`: the model file's study with the command line's overrides.
struct RunCommand {
  std::string path;
  analysis::ModelFile file;
  analysis::StudyOptions study;
  programs::StudyCommand common;
  CLI::Option* record_level = nullptr;

  void add_to(CLI::App& app) {
    // Read as soon as it is parsed, before the other options' values are stored: they override the file's.
    app.add_option("model", path, "the model file (JSON, docs/model-file.md)")
        ->required()
        ->trigger_on_parse()
        ->each([this](const std::string& p) {
          file = analysis::read_model_file(p);
          study = file.study;
          study.out_dir = std::filesystem::path(p).stem().string() + "_run";
        });
    common.add_to(app, study, "the structure");
    record_level = app.get_option("--record-level");
  }

  int run() {
    common.finish(study);
    refuse_unusable(file, path);
    if (file.pushover) return pushover();
    // The intensity target of the file, unless the command line gives the record level.
    if (file.scale.kind != analysis::RecordScale::Kind::record_level && record_level->count() == 0)
      study.record_level = analysis::record_level_for(file.scale, study, path);
    stop_on_interrupt();
    const auto r = programs::run_study(file.structure, study);
    if (common.json) {
      fmt::print("{}\n", analysis::detail::report_json(r));
      return r.interrupted ? 1 : 0;
    }
    print_summary(r);
    return r.interrupted ? 1 : 0;
  }

  /// "analysis": "pushover": the collapse multiplier by bisection (analysis/pushover.hpp).
  int pushover() {
    auto o = *file.pushover;
    o.out_dir = study.out_dir;
    o.progress = study.progress;
    stop_on_interrupt();
    const auto r = programs::run_pushover(file.structure, o, study.contacts == model::ContactKinds::general);
    if (r.falls_under_weight)
      fmt::print("'{}' does not stand under its own weight (lambda = 0 collapses)\n", file.structure.name);
    else if (r.stands_at_upper)
      fmt::print("'{}' still stands at lambda = {:g}, the largest tried (study.pushover.upper)\n", file.structure.name, r.lower);
    else
      fmt::print("collapse multiplier lambda = {:.4f} (stands at {:.4f}, collapses at {:.4f}; {} trials, {:.1f} s)\n", r.collapse_multiplier,
                 r.lower, r.upper, r.trials.size(), r.wall_seconds);
    fmt::print("outputs in {}/ (report.json, pushover.csv, pushover_*.vtu); plots: python3 scripts/plot_study.py {}\n", o.out_dir, o.out_dir);
    return interrupted() ? 1 : 0;
  }

  void print_summary(const analysis::StudyResult& r) const {
    fmt::print("input: {} ({}, baseline {}), PGA {:.3f} m/s^2 = {:.3f} g at 100 %\n", r.input.name, r.input.cut, r.input.baseline, r.input.pga * 100 / study.record_level,
               r.input.pga * 100 / study.record_level / standard_gravity);
    fmt::print("model '{}': {} blocks ({} deformable, {} nodes, {} tetrahedra), {} ties, {} contact points, {:.0f} kg free\n",
               r.model.name, r.model.blocks, r.model.deformable_blocks, r.model.nodes, r.model.tetrahedra, r.model.ties,
               r.model.contact_points, r.model.free_mass);
    fmt::print("settling: {} steps, unbalanced force ratio {:.2e}{}, {:.1f} s\n", r.settling.steps, r.settling.unbalanced_ratio,
               r.settling.converged ? "" : " (NOT converged)", r.settling.wall_seconds);
    fmt::print("damping: {}{}\ntimestep: {:.3e} s; density scaling adds {:.3f} % of the mass\n", r.damping.description,
               r.damping.frame.empty() ? std::string() : fmt::format(", in the {} frame", r.damping.frame), r.timestep.dt,
               r.timestep.scaling.mass_increase_percent);
    for (const auto& w : r.warnings) fmt::print("warning: {}\n", w);
    const char axis = study.axis;
    for (const auto& L : r.levels) {
      std::string peaks;
      for (const auto& name : r.monitor_points)
        for (const auto& p : L.peaks)
          if (p.name == name + "_u" + axis) peaks += fmt::format(" {} {:+.2f}/{:+.2f} mm", name, 1e3 * p.max, 1e3 * p.min);
      fmt::print("level {:g} %: {} steps in {:.1f} s{}; u{}:{}; damaged joints {} (cracked {}, crushed {}, slipped {}); "
                 "energy balance error {:.2e}\n",
                 L.level, L.steps, L.wall_seconds, L.interrupted ? " INTERRUPTED" : "", axis, peaks, L.damage.total.damaged,
                 L.damage.total.cracked, L.damage.total.crushed, L.damage.total.slipped, L.energy.balance_error);
      if (L.collapse.collapsed)
        fmt::print("  COLLAPSED {:.3f} s into the level: {} moved {:.3f} m from where it settled (--collapse-displacement {:g} m)\n",
                   L.collapse.time, L.collapse.point, L.collapse.displacement, study.collapse_displacement);
    }
    fmt::print("\n{}", analysis::table4(r));
    fmt::print("outputs in {}/ (report.json, history_<level>.csv, damage_<level>.vtu, contacts_<level>.vtu/.csv); plots: "
               "python3 scripts/plot_study.py {}\n", study.out_dir, study.out_dir);
    if (r.interrupted)
      fmt::print("stopped early; continue with the same options and --resume {}/{}\n", study.out_dir, analysis::study_checkpoint_file);
  }
};

/// `blockdem sweep`: the cases of a sweep file (docs/sweeps.md) over the structure of the model file it names, whose
/// study gives their base options; the study's command-line options override them, as for `run`.
struct SweepCommand {
  analysis::SweepSpec spec;
  analysis::ModelFile file;
  analysis::StudyOptions study;
  programs::StudyCommand common;
  programs::SweepCommand sweep;

  void add_to(CLI::App& app) {
    sweep.add_to(app, "the sweep file (JSON: \"model\", the model file; damping schemes and their grids, records, levels or "
                      "intensity targets; docs/sweeps.md)");
    // Read as soon as it is parsed, before the other options' values are stored: they override the model file's.
    sweep.spec_option->trigger_on_parse()->each([this](const std::string& p) {
      spec = analysis::read_sweep_file(p);
      if (spec.model.empty())
        throw InvalidArgument(p + ": names no model file: add \"model\": \"your_model.json\" (cross_vault sweep studies the vault)");
      file = analysis::read_model_file(spec.model);
      study = file.study;
      study.out_dir = std::filesystem::path(p).stem().string() + "_sweep";
    });
    common.add_to(app, study, "the structure");
    common.out->description("the sweep's folder: cases/<id>/ per case, summary.csv and summary.json");
  }

  int run(int argc, char** argv) {
    sweep.refuse_grid_options();
    common.finish(study);
    refuse_unusable(file, spec.model);
    analysis::SweepRunOptions run;
    run.out_dir = study.out_dir;
    std::ifstream model_text(spec.model, std::ios::binary);
    run.fingerprint = sweep.fingerprint(argc, argv, spec, std::string(std::istreambuf_iterator<char>(model_text), {}));
    run.program = "blockdem sweep";
    run.study = [this](const analysis::VaultStudyOptions& o) { return programs::run_study(file.structure, o); };
    const auto cases = analysis::model_sweep_cases(spec, file, study, spec.model, run);
    return programs::run_sweep_command("blockdem sweep", sweep, cases, run, argc, argv);
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"blockdem: the seismic study of a masonry block structure from its model file (docs/model-file.md)"};
  app.require_subcommand(1);
  RunCommand run;
  auto* run_app = app.add_subcommand("run", "settle the structure and shake it at each level in turn (the incremental analysis)");
  programs::CheckCommand check;
  auto* check_app = app.add_subcommand("check", "check a model file or a geometry file (OBJ, 3DEC deck, COMPAS): each block's shape, "
                                                "overlaps, blocks touching nothing; for a model file also its contacts and laws");
  check.add_to(*check_app);
  programs::GenerateCommand generate;
  auto* generate_app = app.add_subcommand("generate", "write the model file of a common typology on stdout: wall, barrel-vault, arch, "
                                                      "cross-vault (blockdem generate wall --opening 0.75,1.25,6,14 > wall.json)");
  programs::ExportCommand export_command;
  auto* export_app = app.add_subcommand("export", "write the blocks of a model file or geometry file as OBJ or a 3DEC deck");
  export_command.add_to(*export_app);
  SweepCommand sweep;
  auto* sweep_app = app.add_subcommand("sweep", "many studies of the model file a sweep file names: damping grids, records, "
                                                "levels or intensity targets (IDA), on MPI ranks when built with MPI");
  const char* command = "run";  // for messages: the subcommand typed, before it is parsed
  for (const char* name : {"check", "sweep", "export", "generate"})
    if (argc > 1 && std::string(argv[1]) == name) command = name;
  try {
    run.add_to(*run_app);
    generate.add_to(*generate_app);
    sweep.add_to(*sweep_app);
    if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;
    if (sweep_app->parsed()) return sweep.run(argc, argv);
    if (export_app->parsed()) return export_command.run();
    if (generate_app->parsed()) return generate.run();
    return check_app->parsed() ? check.run() : run.run();
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "blockdem %s: error: %s\n", command, e.what());
    return programs::exit_bad_input;
  } catch (const InputError& e) {
    std::fprintf(stderr, "blockdem %s: error: %s\n", command, e.what());
    return programs::exit_bad_input;
  } catch (const RunawayError& e) {
    std::fprintf(stderr, "blockdem %s: %s\n", command, e.what());
    return 1;
  }
}
