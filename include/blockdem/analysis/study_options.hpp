#pragma once
// What a study runs (paper Sect. 5, 6.1) on any structure (analysis/structure.hpp): the input record and its
// levels, the damping scheme, the timestep, settling and the outputs. Every field is checked by validate(), whose
// messages name the program option (--levels, ...) and the allowed range. The vault's own options (its geometry, its
// kinematics) are in vault_study_options.hpp.

#include <cmath>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/analysis/settling.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/frame.hpp"
#include "blockdem/motion/baseline.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::analysis {

/// The viscous damping of the dynamic run (paper Sect. 4): noDamp, MassProp, stiffness-proportional, Rayleigh, Maxwell.
enum class DampingScheme { none, mass, stiffness, rayleigh, maxwell };
inline constexpr const char* name(DampingScheme s) {
  switch (s) {
    case DampingScheme::none: return "none";
    case DampingScheme::mass: return "mass";
    case DampingScheme::stiffness: return "stiffness";
    case DampingScheme::rayleigh: return "rayleigh";
    case DampingScheme::maxwell: return "maxwell";
  }
  return "?";
}

/// How the record is cut before it is applied: the first seconds (Sect. 5: 15 s) or the pulse support found by the
/// wavelet truncation (Sect. 6.1.2).
enum class Truncation { window, wavelet };

/// The unit vector of axis 'x', 'y' or 'z'.
inline Vec3 axis_vector(char axis) { return axis == 'x' ? Vec3::UnitX() : axis == 'y' ? Vec3::UnitY() : Vec3::UnitZ(); }

inline constexpr int max_study_branches = 4;  // Maxwell<1> .. Maxwell<4> are compiled into the study

struct StudyOptions {
  std::string context = "study";           // what messages start with ("cross vault study")
  std::string program = "blockdem run";    // what report.json names as the program

  // Input (Sect. 2, 5).
  std::string record_path;                 // empty: the built-in synthetic AQA75 stand-in
  std::optional<motion::Record> record;    // a record given in code (overrides record_path)
  motion::ReadOptions read;                // units and dt for files that do not state them
  char axis = 'y';                         // the table moves along x, y or z (the vault's longitudinal axis is y)
  double record_level = 75;                // %, the share of the original record that the input represents
  std::vector<double> levels{25, 50, 75};  // %, run one after another on one state (damage accumulates)
  Truncation truncation = Truncation::window;
  double window_start = 0, window_end = 15;  // s, on the record's clock
  bool window_default = true;              // the window was not given: the first 15 s, or the whole record if shorter
  std::string baseline = "mean,highpass:0.1";  // motion::parse_baseline grammar
  double rest = 1.0;                       // s of free motion after each level (the table at its final velocity)

  // Damping (Sect. 4). zeta: 0 means the scheme's default (maxwell 3 %, mass 4 %, stiffness and rayleigh 3 %).
  DampingScheme damping = DampingScheme::maxwell;
  double zeta = 0;
  double frequency_hz = 7.5;               // mass: centre of MassProp; stiffness: where zeta is met
  double lower_hz = 1, upper_hz = 40;      // maxwell: the band; rayleigh: the two frequencies
  int branches = 3;                        // maxwell
  // mass, rayleigh: the frame of the mass-proportional term (damping/frame.hpp): the table's (a fixed-base model
  // under effective earthquake forces) or the ground's (3DEC's and the paper's: the moving table drags the structure).
  damping::Frame damping_frame = damping::Frame::table;

  // Timestep (eq. 1-3, 11, 20) and partial density scaling (Sect. 3.2).
  double target_dt = 0;                    // s; 0: the largest timestep whose density scaling adds at most
                                           // default_mass_increase_percent of the free mass
  double default_mass_increase_percent = 5.0;  // the paper's model: 5.92 % (Sect. 3.2)
  double max_mass_increase_percent = 20;   // a target that needs more is refused

  // Contacts (model/contact_detection.hpp): face to face (the vault study's default: the vault's joints, faces
  // within 20 degrees, enough for the small rotations of the paper's levels) or general (vertex, edge and face:
  // blocks may turn as far as a collapse takes them). General contacts also find the places where blocks of the
  // vault as built touch along an edge only (faceted groins and infill: 14,740 contact points instead of 14,290),
  // which stiffen it: OC1's peaks differ by 2-5 % (docs/vault-study.md). Past the paper's levels a run goes on to
  // the collapse (below).
  model::ContactKinds contacts = model::ContactKinds::faces;

  // Settling under gravity (static, static mass scaling; inertial relaxation or local damping).
  Settling settling = Settling::automatic;
  double settle_tolerance = 1e-5;          // unbalanced-force ratio
  long long settle_max_steps = 200000;

  // The first natural frequency and damping ratio of the settled structure, from a free decay at the first monitor
  // point (before the levels).
  bool free_vibration = false;

  // Outputs.
  std::string out_dir;                     // empty: nothing written
  double history_dt = 0.005;               // s
  double snapshots_every = 0;              // s; 0: no time series of the blocks
  bool progress = true;                    // a progress line on stderr
  std::function<void()> poll;              // if set, called about every 1024 steps of settling and of the dynamic
                                           // run (an MPI task farm's lead rank answers its workers there)

  // A run whose state is not finite, or whose monitor point moves farther than this from where it settled
  // (relative to the table), stops with RunawayError: it diverged, or a block fell off the table.
  double runaway_displacement = 10;        // m
  // A monitor point this far from where it settled (relative to the table) means the structure has collapsed: the
  // level ends there, as a result (LevelResult::collapse), and no further level runs. The paper's levels move the
  // vault's crown by millimetres; a run on past them ends here, before its fallen blocks pile up.
  double collapse_displacement = 0.3;      // m
  double max_speed = 100;                  // m/s: a block or node faster than this stops the run (RunGuard)

  // Long runs: out_dir/checkpoint.bin is written at the end of each level, every checkpoint_minutes of wall time
  // and when the run stops early (Ctrl-C, stop_after_steps); resume continues from one, bitwise as the run would
  // have gone on, with the same options (the checkpoint refuses others) and writing into the same out_dir.
  std::string resume;                      // a checkpoint to continue from; empty: start afresh
  double checkpoint_minutes = 0;           // 0: only at the end of each level and when stopped
  long long stop_after_steps = 0;          // stop (as if interrupted) once the dynamic run has taken this many
                                           // steps in total, leaving a checkpoint; 0: never

  /// The options the user gave, by their command-line names ("--zeta"), from the command line or a model file
  /// (`given_known` then true): a message that names one the user did not give says it is the default. Options set
  /// in code are not tracked (given_known false): their messages say nothing of defaults.
  std::set<std::string, std::less<>> given;
  bool given_known = false;
  /// " (the default)" if the user is known not to have given `option`, else "".
  std::string default_note(std::string_view option) const {
    return given_known && !given.contains(option) ? " (the default)" : "";
  }

  double scheme_zeta() const {
    if (zeta > 0) return zeta;
    return damping == DampingScheme::mass ? 0.04 : 0.03;
  }

  void validate() const {
    auto check = [this](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument(context + ": " + what);
    };
    check(axis == 'x' || axis == 'y' || axis == 'z', std::string("--axis must be x, y or z, got ") + axis);
    check(record_level > 0 && record_level <= 1000, "--record-level must be in (0, 1000] %, got " + num(record_level));
    check(!levels.empty(), "--levels needs at least one level");
    for (double l : levels) check(l > 0 && l <= 1000 && std::isfinite(l), "--levels: each level must be in (0, 1000] %, got " + num(l));
    if (truncation == Truncation::window)
      check(window_start >= 0 && window_end > window_start && std::isfinite(window_end),
            "--window: needs 0 <= start < end (s), got " + num(window_start) + " " + num(window_end));
    (void)motion::parse_baseline(baseline);
    check(rest >= 0 && rest <= 600, "--rest must be in [0, 600] s, got " + num(rest));
    check(zeta >= 0 && zeta < 0.5, "--zeta must be in (0, 0.5) (0: the scheme's default), got " + num(zeta));
    check(frequency_hz > 0 && frequency_hz <= 1000, "--frequency must be in (0, 1000] Hz, got " + num(frequency_hz));
    check(lower_hz > 0 && upper_hz > lower_hz && upper_hz <= 1000,
          "--band must satisfy 0 < f_lb < f_ub <= 1000 Hz, got " + num(lower_hz) + " " + num(upper_hz));
    check(branches >= 1 && branches <= max_study_branches,
          "--branches must be in 1.." + std::to_string(max_study_branches) + ", got " + std::to_string(branches));
    check(target_dt >= 0 && target_dt < 1e-2 && std::isfinite(target_dt), "--target-dt must be in [0, 0.01) s (0: automatic), got " + num(target_dt));
    check(default_mass_increase_percent >= 0 && default_mass_increase_percent <= max_mass_increase_percent,
          "--mass-increase must be in [0, --max-mass-increase " + num(max_mass_increase_percent) +
              default_note("--max-mass-increase") + "] %, got " + num(default_mass_increase_percent) +
              default_note("--mass-increase"));
    check(max_mass_increase_percent >= 0 && max_mass_increase_percent <= 1000,
          "--max-mass-increase must be in [0, 1000] %, got " + num(max_mass_increase_percent));
    check(settle_tolerance > 0 && settle_tolerance < 1, "--settle-tolerance must be in (0, 1), got " + num(settle_tolerance));
    check(settle_max_steps >= 10, "--settle-steps must be >= 10, got " + std::to_string(settle_max_steps));
    check(history_dt >= 1e-5 && history_dt <= 1, "--history-dt must be in [1e-5, 1] s, got " + num(history_dt));
    check(checkpoint_minutes >= 0 && checkpoint_minutes <= 1e6 && std::isfinite(checkpoint_minutes),
          "--checkpoint-minutes must be in [0, 1e6] (0: at the end of each level only), got " + num(checkpoint_minutes));
    check(stop_after_steps >= 0, "--stop-after-steps must be >= 0 (0: never), got " + std::to_string(stop_after_steps));
    check(resume.empty() || !out_dir.empty(), "--resume needs the output folder of the run it continues (--out)");
    check(runaway_displacement >= 0.001 && runaway_displacement <= 1e6,
          "--runaway-displacement must be in [0.001, 1e6] m, got " + num(runaway_displacement));
    check(collapse_displacement >= 0.001 && collapse_displacement <= runaway_displacement,
          "--collapse-displacement must be in [0.001, --runaway-displacement " + num(runaway_displacement) +
              default_note("--runaway-displacement") + "] m, got " + num(collapse_displacement) +
              default_note("--collapse-displacement"));
    check(max_speed >= 0.1 && max_speed <= 1e6, "--max-speed must be in [0.1, 1e6] m/s, got " + num(max_speed));
    check(snapshots_every >= 0 && snapshots_every <= 100, "--snapshots-every must be in [0, 100] s, got " + num(snapshots_every));
  }
};

}  // namespace blockdem::analysis
