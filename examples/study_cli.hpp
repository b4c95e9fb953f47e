#pragma once
// The options of a study on the command line (analysis::StudyOptions), shared by `cross_vault run` and
// `blockdem run`: each given option overrides the study's value (the vault's defaults, or a model file's), the
// others leave it as it is.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "blockdem/analysis/study_options.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/motion/acceleration_unit.hpp"
#include "blockdem/motion/baseline.hpp"

namespace blockdem::programs {

struct StudyCommand {
  std::string units, truncation = "window", axis = "y";
  std::vector<double> window{0, 15}, band{1, 40};
  bool quiet = false, json = false;
  CLI::App* command_app = nullptr;  // the (sub)command the options belong to
  CLI::Option* out = nullptr;
  CLI::Option *units_option = nullptr, *truncation_option = nullptr, *axis_option = nullptr, *window_option = nullptr,
              *band_option = nullptr;

  /// Binds the options to `o`, which must outlive the parsing. `subject` names what is studied in the help ("the
  /// vault", "the structure").
  void add_to(CLI::App& app, analysis::StudyOptions& o, const std::string& subject) {
    using analysis::DampingScheme;
    command_app = &app;
    out = app.add_option("--out", o.out_dir, "output folder (created if missing; with --resume: the checkpoint's folder)")
              ->capture_default_str();
    app.add_option("--record", o.record_path, "acceleration record (PEER .AT2, ESM ASCII, text)");
    units_option = app.add_option("--units", units, "units of the record's samples: g, m/s2 or cm/s2 (default: from its header)")
                       ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}));
    axis_option = app.add_option("--axis", axis, "the table moves along x, y or z")->check(CLI::IsMember({"x", "y", "z"}));
    app.add_option("--record-level", o.record_level, "the share of the original record that the input represents, % (0, 1000]");
    app.add_option("--levels", o.levels, "levels to run one after another, % of the original record, (0, 1000]")->delimiter(',');
    truncation_option = app.add_option("--truncate", truncation, "cut of the record: window (--window) or wavelet (the pulse support, Sect. 6.1.2)")
                            ->check(CLI::IsMember({"window", "wavelet"}));
    window_option = app.add_option("--window", window, "start and end of the window on the record's clock, s (default: the first 15 s, "
                                                       "or the whole record if shorter)")->expected(2);
    app.add_option("--baseline", o.baseline, std::string("baseline correction: ") + motion::baseline_grammar);
    app.add_option("--rest", o.rest, "free motion after each level, the table going on at the velocity its record ends with "
                                     "(report.json: final_table_velocity_m_s), s [0, 600]");
    app.add_option("--damping", o.damping, "viscous damping of the dynamic run")
        ->transform(CLI::CheckedTransformer(std::map<std::string, DampingScheme>{{"none", DampingScheme::none},
                                                                                   {"mass", DampingScheme::mass},
                                                                                   {"stiffness", DampingScheme::stiffness},
                                                                                   {"rayleigh", DampingScheme::rayleigh},
                                                                                   {"maxwell", DampingScheme::maxwell}}));
    app.add_option("--zeta", o.zeta, "target damping ratio (default: maxwell 0.03, mass 0.04, stiffness and rayleigh 0.03)");
    app.add_option("--frequency", o.frequency_hz, "mass: centre frequency; stiffness: frequency of --zeta, Hz");
    band_option = app.add_option("--band", band, "maxwell: the band of the fit; rayleigh: its two frequencies, Hz")->expected(2);
    app.add_option("--branches", o.branches, "maxwell: number of branches, 1..4");
    app.add_option("--damping-frame", o.damping_frame,
                   "mass, rayleigh: damp velocities relative to the table (a fixed-base model, the default) or to the ground "
                   "(absolute: 3DEC's and the paper's, where the moving table drags the structure)")
        ->transform(CLI::CheckedTransformer(std::map<std::string, damping::Frame>{{"table", damping::Frame::table},
                                                                                  {"absolute", damping::Frame::absolute}}));
    app.add_option("--target-dt", o.target_dt, "timestep of the dynamic run, s: above the unscaled one by partial density scaling, "
                                               "below it as given (0: the largest whose density scaling adds at most --mass-increase % of the mass)");
    app.add_option("--mass-increase", o.default_mass_increase_percent, "mass that the automatic timestep may add by density scaling, %");
    app.add_option("--max-mass-increase", o.max_mass_increase_percent, "refuse a --target-dt that adds more mass than this, %");
    app.add_option("--settling", o.settling,
                   "how the structure comes to rest under gravity: inertial (relaxation without damping, stopped when it "
                   "starts uphill), local (local damping: 3DEC's, the paper's) or auto (inertial with deformable blocks, "
                   "local for rigid ones)")
        ->transform(CLI::CheckedTransformer(std::map<std::string, analysis::Settling>{{"auto", analysis::Settling::automatic},
                                                                                      {"inertial", analysis::Settling::inertial},
                                                                                      {"local", analysis::Settling::local}}));
    app.add_option("--settle-tolerance", o.settle_tolerance, "unbalanced-force ratio that ends settling");
    app.add_option("--settle-steps", o.settle_max_steps, "most steps of settling");
    app.add_option("--contacts", o.contacts,
                   "general (vertex, edge and face: blocks may turn as far as a collapse takes them) or faces (face to "
                   "face within 20 degrees only)")
        ->transform(CLI::CheckedTransformer(std::map<std::string, model::ContactKinds>{
                                                {"general", model::ContactKinds::general}, {"faces", model::ContactKinds::faces}},
                                            CLI::ignore_case));
    app.add_option("--collapse-displacement", o.collapse_displacement,
                   "a monitor point this far from where it settled means " + subject + " collapsed: the level ends there and no "
                   "further level runs (report.json: collapse), m [0.001, --runaway-displacement]");
    app.add_option("--runaway-displacement", o.runaway_displacement,
                   "stop with an error when a monitor point moves farther than this from where it settled, m [0.001, 1e6]");
    app.add_option("--max-speed", o.max_speed, "stop with an error when a block or node moves faster than this, m/s [0.1, 1e6]");
    app.add_option("--history-dt", o.history_dt, "sampling interval of the histories, s");
    app.add_option("--snapshots-every", o.snapshots_every, "write the blocks every DT s of simulated time (snapshots.pvd for ParaView; 0: none)");
    app.add_flag("--free-vibration", o.free_vibration,
                 "first measure the first frequency and damping ratio of " + subject + " settled, in free decay at the first "
                 "monitor point (into report.json)");
    app.add_option("--checkpoint-minutes", o.checkpoint_minutes,
                   "also write OUT/checkpoint.bin every this many minutes of wall time (it is always written at the end of "
                   "each level and when the run is stopped), [0, 1e6]");
    app.add_option("--resume", o.resume, "continue the run that wrote this checkpoint, with the same options; the result is "
                                         "bitwise that of the run not stopped");
    app.add_option("--stop-after-steps", o.stop_after_steps,
                   "stop with a checkpoint once the dynamic run has taken this many steps in all (to split a run over batch jobs; 0: never)");
    app.add_flag("--quiet", quiet, "no progress line");
    app.add_flag("--json", json, "print report.json at the end");
  }

  /// The options given through local variables, onto `o`; the output folder of a resumed run.
  void finish(analysis::StudyOptions& o) const {
    if (units_option->count() > 0) o.read.units = motion::parse_acceleration_unit(units);
    if (axis_option->count() > 0) o.axis = axis[0];
    if (truncation_option->count() > 0) o.truncation = truncation == "wavelet" ? analysis::Truncation::wavelet : analysis::Truncation::window;
    if (window_option->count() > 0) {
      o.window_start = window[0];
      o.window_end = window[1];
      o.window_default = false;
    }
    if (band_option->count() > 0) {
      o.lower_hz = band[0];
      o.upper_hz = band[1];
    }
    o.progress = !quiet;
    o.given_known = true;
    for (const CLI::Option* option : command_app->get_options())
      if (option->count() > 0 && option->get_name().starts_with("--")) o.given.insert(option->get_name());
    if (!o.resume.empty() && out->count() == 0) {
      const auto folder = std::filesystem::path(o.resume).parent_path();
      o.out_dir = folder.empty() ? std::string(".") : folder.string();
    }
  }
};

}  // namespace blockdem::programs
