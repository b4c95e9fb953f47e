#pragma once
// The study of any structure (analysis/structure.hpp) under a record (paper Sect. 5, 6.1; Table 4, Figs. 14-18): the
// structure settled under gravity, then shaken at each level of the record in turn on one state (damage
// accumulates), under one damping scheme, with the monitor histories, the damage at the end of each level, the
// energy balance and the timings. run_study() is the driver; the outputs it writes are listed in
// write_level_outputs(). The vault study (vault_study.hpp) is the vault's structure fed to it.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/analysis/damage_memory.hpp"
#include "blockdem/analysis/corner_point_warnings.hpp"
#include "blockdem/analysis/free_decay.hpp"
#include "blockdem/analysis/model_file_study.hpp"
#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_checkpoint.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_recorders.hpp"
#include "blockdem/analysis/study_report.hpp"
#include "blockdem/analysis/study_timestep.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"
#include "blockdem/integrate/inertial_relaxation.hpp"
#include "blockdem/integrate/run.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/vtk.hpp"
#include "blockdem/motion/base_motion.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/processing.hpp"
#include "blockdem/motion/synthetic.hpp"
#include "blockdem/motion/truncation.hpp"
#include "blockdem/motion/wavelet_truncation.hpp"

namespace blockdem::analysis {

/// The simulation of a study under damping policy D: the three joint laws of the paper (Sect. 3.1-3.2), in the
/// order of contact::JointLaw.
template <class D>
using StudySimulation = Simulation<D, contact::ElastoSoftening, contact::MohrCoulomb, contact::Elastic>;

namespace detail {

inline std::string level_label(double level) { return num(level); }

/// The record as the options ask for it: read or synthetic, baseline corrected as a whole (a filter on a short cut
/// would ring at its ends), then cut to the window or to the wavelet pulse support.
inline motion::Record input_record(const StudyOptions& o, std::string& cut_note) {
  motion::Record record = o.record ? *o.record
                          : o.record_path.empty() ? motion::synthetic_aqa75()
                                                  : motion::read_record(o.record_path, o.read);
  record.validate("input record");
  record = motion::correct_baseline(std::move(record), motion::parse_baseline(o.baseline));
  if (o.truncation == Truncation::wavelet) {
    const auto w = motion::wavelet_truncation(record);
    char note[128];
    std::snprintf(note, sizeof note, "wavelet truncation (Sect. 6.1.2): pulse support %.3f-%.3f s", w.truncation.start, w.truncation.end);
    cut_note = note;
    return w.truncation.record;
  }
  if (o.window_default && o.window_start == 0 && o.window_end == 15 && record.end_time() + 0.5 * record.dt < o.window_end) {
    // The default window on a record shorter than it: the whole record, and the note says why.
    cut_note = "window " + num(record.start_time) + "-" + num(record.end_time()) + " s (the default: the first 15 s, here the whole record)";
    return record;
  }
  if (o.window_start >= record.end_time() || o.window_end > record.end_time() + 0.5 * record.dt)
    throw InvalidArgument(o.context + ": --window " + num(o.window_start) + " " + num(o.window_end) +
                          " s lies outside the record '" + record.name + "', which spans [" + num(record.start_time) + ", " +
                          num(record.end_time()) + "] s");
  cut_note = "window " + num(o.window_start) + "-" + num(o.window_end) + " s";
  return motion::truncate_window(record, o.window_start, o.window_end).record;
}

}  // namespace detail

/// The record level (%) at which the record of `o`, as the study cuts and corrects it, meets a model file's intensity
/// target `scale` (a PGA or Sa(T) at 100 %); `context` names the file in messages.
inline double record_level_for(const RecordScale& scale, StudyOptions o, const std::string& context) {
  std::string note;
  o.record_level = 100;
  return record_level_for(scale, detail::input_record(o, note), context);
}

namespace detail {

/// The joint laws of a structure, for its simulation Sim (StudySimulation<D>).
template <class Sim>
typename Sim::PropertyFunction structure_properties(const Structure& s) {
  return [&s](int a, int b) {
    return std::visit([](const auto& p) { return typename Sim::Properties(p); },
                      s.laws.law(static_cast<std::size_t>(a), static_cast<std::size_t>(b)));
  };
}

/// Whether the structure settles by inertial relaxation (StudyOptions::settling), not local damping.
inline bool inertial_settling(const StudyOptions& o, const model::Model& m) {
  return resolved(o.settling, !m.deformable.blocks.empty()) == Settling::inertial;
}

/// The damping of the simulation that settles: local damping, or its coefficient 0 under inertial relaxation.
inline damping::Local settling_damping(const StudyOptions& o, const model::Model& m) {
  damping::Local d;
  if (inertial_settling(o, m)) d.coefficient = 0;
  return d;
}

/// Static equilibrium under gravity (DESIGN §4) by inertial relaxation or local damping (o.settling; `sim` built
/// with settling_damping(o, model)): static, so every block takes the mass that gives one common timestep (3DEC's
/// static mass scaling); the real masses are back when it returns.
template <class Settle>
void settle(Settle& sim, double dt, const StudyOptions& o, SettlingResult& out) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  sim.scale_masses_for_statics(dt);
  out.dt = sim.timestep();
  const bool inertial = inertial_settling(o, sim.model());
  InertialRelaxation relaxation;
  auto last = t0;
  for (long long n = 0; n < o.settle_max_steps; ++n) {
    sim.step();
    if (inertial) relaxation.after_step(sim.model(), sim.timestep());
    ++out.steps;
    if ((n & 1023) == 1023 && o.poll) o.poll();
    if (n % 10 != 9) continue;
    out.unbalanced_ratio = sim.unbalanced_force_ratio();
    if (out.unbalanced_ratio <= o.settle_tolerance) {
      out.converged = true;
      break;
    }
    if (interrupted()) break;
    if (o.progress && clock::now() - last > std::chrono::seconds(1)) {
      last = clock::now();
      std::fprintf(stderr, "\rsettling: step %lld, unbalanced force ratio %.2e (tolerance %.0e)   ", out.steps, out.unbalanced_ratio,
                   o.settle_tolerance);
      std::fflush(stderr);
    }
  }
  sim.restore_real_masses();
  out.wall_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  if (o.progress)
    std::fprintf(stderr, "\rsettling: %lld steps, unbalanced force ratio %.2e, %.1f s%s\n", out.steps, out.unbalanced_ratio,
                 out.wall_seconds, out.converged ? "" : " (NOT converged)");
}

/// Throws RunawayError if a monitor point's last sample is not finite or farther than o.runaway_displacement from
/// where it settled (relative to the table).
template <class History>
void check_runaway(const History& history, const StudyOptions& o, const std::string& level, double t_in_level) {
  for (std::size_t p = 0; p < history.points(); ++p) {
    const double d = history.last_displacement(p).norm();
    if (std::isfinite(d) && d <= o.runaway_displacement) continue;
    const auto names = history.names();
    char text[320];
    if (!std::isfinite(d))
      std::snprintf(text, sizeof text, "level %s %%: the run diverged %.4f s into the level (the displacement of %s is not finite)",
                    level.c_str(), t_in_level, names[p].c_str());
    else
      std::snprintf(text, sizeof text, "level %s %%: %s moved %.3g m from where it settled, %.4f s into the level, beyond "
                    "--runaway-displacement %.3g m%s: the run diverged or the block fell off the table", level.c_str(), names[p].c_str(), d,
                    t_in_level, o.runaway_displacement, o.default_note("--runaway-displacement").c_str());
    throw RunawayError(text);
  }
}

/// Fills `collapse` when a monitor point's last sample is farther than o.collapse_displacement from where it settled
/// (relative to the table): the structure has collapsed.
template <class History>
void check_collapse(const History& history, const StudyOptions& o, double t_in_level, LevelResult::Collapse& collapse) {
  for (std::size_t p = 0; p < history.points() && !collapse.collapsed; ++p) {
    const double d = history.last_displacement(p).norm();
    if (!(d > o.collapse_displacement)) continue;
    collapse = {true, history.names()[p], t_in_level, d};
  }
}

}  // namespace detail

/// Calls f(policy) with the damping policy of the options (the Maxwell branches fitted here, Sect. 4.2), and
/// describes it in `description`.
template <class F>
decltype(auto) with_damping_policy(const StudyOptions& o, std::string& description, F&& f) {
  const double z = o.scheme_zeta();
  char text[160];
  switch (o.damping) {
    case DampingScheme::none:
      description = "none (noDamp: hysteretic damping of the joints only)";
      return f(damping::None{});
    case DampingScheme::mass: {
      std::snprintf(text, sizeof text, "mass-proportional (MassProp), %.3g %% at %.4g Hz", 100 * z, o.frequency_hz);
      description = text;
      return f(damping::MassProportional::from_damping_ratio(z, o.frequency_hz));  // eq. 10
    }
    case DampingScheme::stiffness: {
      std::snprintf(text, sizeof text, "stiffness-proportional, %.3g %% at %.4g Hz", 100 * z, o.frequency_hz);
      description = text;
      return f(damping::StiffnessProportional::from_damping_ratio(z, o.frequency_hz));  // eq. 10
    }
    case DampingScheme::rayleigh: {
      std::snprintf(text, sizeof text, "Rayleigh, %.3g %% at %.4g and %.4g Hz", 100 * z, o.lower_hz, o.upper_hz);
      description = text;
      return f(damping::Rayleigh::from_two_frequencies(z, o.lower_hz, z, o.upper_hz));  // eq. 10
    }
    case DampingScheme::maxwell: break;
  }
  damping::MaxwellFitOptions fit_options;
  fit_options.damping_ratio = z;
  fit_options.lower_hz = o.lower_hz;
  fit_options.upper_hz = o.upper_hz;
  fit_options.branches = o.branches;
  const auto fit = damping::fit_maxwell(fit_options);
  if (!fit.converged)
    throw InvalidArgument(o.context + ": the Maxwell fit of " + num(100 * z) + " %" + o.default_note("--zeta") + " over " +
                          num(o.lower_hz) + "-" + num(o.upper_hz) + " Hz" + o.default_note("--band") + " with " +
                          std::to_string(o.branches) + " branches" + o.default_note("--branches") + " did not converge");
  std::snprintf(text, sizeof text, "Maxwell, %.3g %% over %.4g-%.4g Hz, %d branches (band error %+.2f %% / %+.2f %%)", 100 * z,
                o.lower_hz, o.upper_hz, o.branches, 100 * fit.rel_error_min, 100 * fit.rel_error_max);
  description = text;
  auto with = [&]<int N>(std::integral_constant<int, N>) -> decltype(auto) {
    std::array<damping::MaxwellBranch, N> branches{};
    std::copy_n(fit.branch.begin(), N, branches.begin());
    return f(damping::Maxwell<N>(branches));
  };
  switch (o.branches) {
    case 1: return with(std::integral_constant<int, 1>{});
    case 2: return with(std::integral_constant<int, 2>{});
    case 3: return with(std::integral_constant<int, 3>{});
    default: return with(std::integral_constant<int, 4>{});
  }
}

/// What lets blocks pass through each other, for a run guard's stop on an overlap.
namespace detail {
inline std::string pass_through_hint(std::string_view stop, const StudyOptions& o, const Structure& s) {
  if (stop.find(" overlaps by ") == std::string_view::npos) return "";
  std::string hint;
  if (o.contacts == model::ContactKinds::faces)
    hint += "; with --contacts faces, blocks that turn more than 20 degrees lose their contacts (--contacts general keeps them)";
  bool crushable = false;
  for (std::size_t a = 0; a < s.laws.groups(); ++a)
    for (std::size_t b = a; b < s.laws.groups(); ++b)
      if (s.laws.has(a, b))
        if (const auto* p = std::get_if<contact::ElastoSoftening::Parameters>(&s.laws.law(a, b)))
          crushable = crushable || p->residual_compressive_strength == 0;
  if (crushable)
    hint += "; a joint crushed through carries nothing with a residual compressive strength of 0 (the paper's law; the "
            "vault's --residual-compressive-strength): blocks that pound past the paper's levels then pass through each other";
  return hint;
}
}  // namespace detail

/// The structure `s` (its model is changed: settled, then run), settled under gravity and handed to f(sim, policy)
/// as a simulation with the options' damping policy at the dynamic timestep (after partial density scaling). Fills
/// the model, settling, damping and timestep parts of `r`; with o.out_dir set, writes report.json once settled.
/// Returns without calling f if interrupted while settling. With o.resume set, f receives the simulation unsettled
/// and unscaled, for the caller to load a checkpoint into.
template <class F>
void with_settled_structure(Structure& s, const StudyOptions& o, StudyResult& r, F&& f) {
  const bool resuming = !o.resume.empty();
  s.validate();
  model::Model& model = s.model;
  r.model.name = s.name;
  r.model.groups = s.groups();
  r.model.report = s.report;
  r.model.blocks = model.bodies.size();
  r.model.deformable_blocks = model.deformable.blocks.size();
  r.model.nodes = model.deformable.nodes.size();
  r.model.tetrahedra = model.deformable.tetrahedra.size();
  r.model.ties = model.deformable.trusses.size();
  r.model.free_mass = model.total_mass();
  r.timestep.added_by_group.assign(s.laws.groups(), {});

  std::string description;
  with_damping_policy(o, description, [&]<class D>(D policy) {
    r.damping.description = description;
    r.damping.scheme = name(o.damping);
    if constexpr (damping::damps_velocities<D>()) r.damping.frame = name(o.damping_frame);
    using Settle = StudySimulation<damping::Local>;
    using Dynamic = StudySimulation<D>;
    model::ContactSettings contacts = s.contacts;
    contacts.kinds = o.contacts;
    s.laws.fill(contacts);
    Settle settle(model, detail::settling_damping(o, model), detail::structure_properties<Settle>(s), contacts);
    r.model.contact_points = settle.contact_points();
    r.warnings = corner_point_warnings(s, contacts, settle);
    if (o.progress)
      for (const auto& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    // The timestep of the dynamic run, chosen before settling so that a bad target is refused at once.
    const auto dt = choose_dynamic_timestep(settle, settle.frequency_bound(), policy, o, r.model.free_mass, r.timestep);

    if (!resuming) {
      detail::settle(settle, std::max(dt.unscaled, dt.target), o, r.settling);
      const auto census = damage_census(settle, model, s.laws.groups());
      r.settling.damaged_joints = census.total.damaged;
      r.settling.cracked_joints = census.total.cracked;
      r.settling.crushed_joints = census.total.crushed;
      if (!o.out_dir.empty()) detail::write_report(o.out_dir, r);
      if (interrupted()) {
        r.interrupted = true;
        return;
      }
    }

    Dynamic sim(settle, policy);
    sim.set_damping_frame(o.damping_frame);
    if (!resuming) set_dynamic_timestep(sim, dt.target, s, r.timestep);

    f(sim, policy);
  });
}

/// The settled structure's first natural frequency and damping ratio under the options' damping policy: a short
/// table pulse along the axis (one sine cycle of velocity, amplitude `pulse_velocity` m/s over `pulse_duration` s,
/// small enough for the joints to stay elastic), then free decay for `duration` s, analysed at the first monitor
/// point (the vault's OC1; analyse_first_mode). Runs on its own copy of the structure: the study's state is not
/// touched.
inline FreeVibrationResult measure_free_vibration(Structure s, StudyOptions o, double duration = 1.0, double pulse_velocity = 1e-3,
                                                  double pulse_duration = 0.05) {
  o.out_dir.clear();
  o.resume.clear();
  o.free_vibration = false;
  StudyResult scratch;
  FreeVibrationResult fv;
  fv.pulse_velocity = pulse_velocity;
  fv.pulse_duration = pulse_duration;
  if (s.monitors.empty()) throw InvalidArgument(o.context + ": the free vibration is measured at a monitor point, and there is none");
  with_settled_structure(s, o, scratch, [&](auto& sim, const auto& policy) {
    model::Model& model = s.model;
    const auto& point = s.monitors.front();
    fv.point = point.name;
    const auto& b = model.bodies;
    const Vec3 body_point = b.rotation[point.block].transpose() * (point.position - b.position[point.block]);
    const bool on_node = model.deformable.is_deformable(point.block);  // then the point follows its nearest node
    const std::size_t node = on_node ? model.nearest_node(point.block, point.position) : 0;
    auto where = [&] { return on_node ? model.deformable.nodes.position[node] : b.to_world(point.block, body_point); };
    auto table = [&] { return s.table ? b.position[*s.table] : Vec3::Zero(); };
    const Vec3 reference = where(), table_reference = table();
    const Vec3 axis = axis_vector(o.axis);
    const double t0 = sim.time();
    model.base_motion = motion::BaseMotion(motion::SineVelocity{pulse_velocity, pulse_duration, 1, axis, t0});
    std::vector<double> time, response;
    const auto every = std::max<long long>(1, std::llround(2e-4 / sim.timestep()));  // uniform sampling for the filter
    const double interval = static_cast<double>(every) * sim.timestep();
    for (long long n = 1; sim.time() < t0 + pulse_duration + duration && !interrupted(); ++n) {
      sim.step();
      if (n % every != 0 || sim.time() < t0 + pulse_duration) continue;
      const Vec3 u = where() - reference - (table() - table_reference);
      time.push_back(sim.time() - t0);
      response.push_back(u.dot(axis));
    }
    model.base_motion = motion::BaseMotion::at_rest();
    fv.time = time;
    fv.response = response;
    try {
      fv.decay = analyse_first_mode(response, interval);
      fv.measured = true;
    } catch (const InvalidArgument& e) {
      fv.note = e.what();
      return;
    }
    const double omega = 2 * pi * fv.decay.frequency_hz;
    if constexpr (requires { policy.damping_ratio(omega); }) fv.expected_damping_ratio = policy.damping_ratio(omega);  // eq. 10, eq. 19
  });
  return fv;
}

/// Runs the study of structure `s` (taken by value: the run changes its model). Writes into o.out_dir (if set) as it
/// goes, with a checkpoint (study_checkpoint.hpp) at the end of each level, every o.checkpoint_minutes and when it
/// stops early; with o.resume set, continues from a checkpoint bitwise as the run that wrote it would have gone on.
/// Stops cleanly after the current step on SIGINT/SIGTERM once stop_on_interrupt() was called, or after
/// o.stop_after_steps dynamic steps (the result says so, and what was written stays complete).
inline StudyResult run_study(Structure s, const StudyOptions& o) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  o.validate();
  s.validate();
  if (!s.table)
    throw InvalidArgument(o.context + ": '" + s.name + "' has no base block for the record to move (a block moved by the "
                          "table: \"motion\": \"base\" in a model file)");
  StudyResult r;
  r.options = o;
  const bool resuming = !o.resume.empty();
  // A checkpoint that cannot be used is refused before any work: its header now, its model and checksum below.
  if (resuming) (void)io::read_checkpoint_header(o.resume);
  if (!o.out_dir.empty()) detail::prepare_output_folder(o.out_dir, resuming, o.default_note("--out"));

  const motion::Record cut = detail::input_record(o, r.input.cut);
  r.input.name = cut.name;
  r.input.synthetic = cut.synthetic;
  r.input.duration = cut.duration();
  r.input.baseline = motion::to_string(motion::parse_baseline(o.baseline));
  {
    const auto peaks = motion::peak_values(cut);
    r.input.pga = peaks.pga;
    r.input.pgv = peaks.pgv;
    r.input.pgd = peaks.pgd;
  }
  if (o.free_vibration && !resuming) {
    r.free_vibration = measure_free_vibration(s, o);
    if (!o.out_dir.empty()) detail::write_free_vibration(o.out_dir, r.free_vibration);
  }

  const std::uint64_t hash = study_hash(o, s, cut);
  model::Model& model = s.model;
  with_settled_structure(s, o, r, [&](auto& sim, const auto&) {
    sim.set_run_guard(RunGuard{o.max_speed});
    MonitorHistory history(model, s.monitors, s.table);
    // The joints bonded now, and the worst state each reaches: kept up to date before every re-detection.
    DamageMemory memory;
    if (!resuming) memory.start(sim, model);
    sim.set_detection_observer([&] { memory.update(sim, model); });
    r.monitor_points = history.names();
    SnapshotSeries snapshots(o.out_dir);
    std::vector<Vec3> settled_position = model.bodies.position;
    const Vec3 axis = axis_vector(o.axis);
    StudyCursor cursor;
    auto history_path = [&](const std::string& label) {
      return o.out_dir.empty() ? std::string() : o.out_dir + "/history_" + label + ".csv";
    };
    const std::string checkpoint = o.out_dir.empty() ? std::string() : o.out_dir + "/" + study_checkpoint_file;
    auto save = [&] {
      if (checkpoint.empty()) return;
      std::string what = o.context + ", ";
      what += r.damping.scheme;
      if (cursor.level < o.levels.size()) {
        what += cursor.in_level ? "in level " : "before level ";
        what += detail::level_label(o.levels[cursor.level]) + " %";
      } else {
        what += "after the last level";
      }
      what += ", t = ";
      what += num(sim.time());
      what += " s";
      io::save_checkpoint(checkpoint, hash, what, [&](io::CheckpointWriter& w) {
        detail::visit_study_state(w, r, cursor, sim, history, snapshots, settled_position, memory);
      });
    };
    if (resuming) {
      io::load_checkpoint(o.resume, hash, [&](io::CheckpointReader& in) {
        detail::visit_study_state(in, r, cursor, sim, history, snapshots, settled_position, memory);
      });
      if (cursor.in_level) history.resume_file(history_path(detail::level_label(o.levels[cursor.level])));
      if (o.progress)
        std::fprintf(stderr, "resuming from '%s' at t = %.4f s (%s level %s %%)\n", o.resume.c_str(), sim.time(),
                     cursor.in_level ? "in" : "before", cursor.level < o.levels.size() ? detail::level_label(o.levels[cursor.level]).c_str() : "-");
    }
    auto last_checkpoint = clock::now();
    for (; cursor.level < o.levels.size(); ++cursor.level) {
      if (!r.levels.empty() && r.levels.back().collapse.collapsed) break;  // resumed after the collapse: nothing left
      const double level = o.levels[cursor.level];
      const std::string label = detail::level_label(level);
      LevelResult L;
      L.level = level;
      if (!cursor.in_level) {
        cursor.level_start = sim.time();
        cursor.start_velocity = cursor.table_velocity;  // each level starts where the last left the table
      }
      const motion::RecordMotion table_motion(motion::scale(cut, level / o.record_level), {}, axis, cursor.level_start,
                                              cursor.start_velocity);
      model.base_motion = motion::BaseMotion(table_motion);
      L.final_table_velocity = table_motion.final_velocity();
      L.duration = table_motion.duration() + o.rest;
      auto record = [&] {
        if (sim.time() >= cursor.next_sample - 0.5 * sim.timestep()) {
          history.sample(model, sim.time());
          cursor.next_sample += o.history_dt;
          detail::check_runaway(history, o, label, sim.time() - cursor.level_start);
          detail::check_collapse(history, o, sim.time() - cursor.level_start, L.collapse);
        }
        if (o.snapshots_every > 0 && !o.out_dir.empty() && sim.time() >= cursor.next_snapshot - 0.5 * sim.timestep()) {
          snapshots.write(label, sim.time(), model, s, settled_position);
          cursor.next_snapshot += o.snapshots_every;
        }
      };
      if (!cursor.in_level) {
        history.begin_level(model, sim.time(), history_path(label));
        cursor.energy_at_level_start = sim.energy();
        cursor.next_sample = cursor.next_snapshot = sim.time();
        cursor.level_steps = 0;
        cursor.level_wall_seconds = 0;
        cursor.in_level = true;
        record();
      }
      const double wall_before = cursor.level_wall_seconds;
      const auto run_start = clock::now();
      auto step = [&] {
        record();
        ++cursor.level_steps;
        ++cursor.dynamic_steps;
        if ((cursor.level_steps & 1023) == 0 && o.poll) o.poll();
        if ((cursor.level_steps & 1023) == 0 && o.checkpoint_minutes > 0 &&
            clock::now() - last_checkpoint > std::chrono::duration<double>(60 * o.checkpoint_minutes)) {
          cursor.level_wall_seconds = wall_before + std::chrono::duration<double>(clock::now() - run_start).count();
          save();
          last_checkpoint = clock::now();
        }
        if (L.collapse.collapsed) return false;  // the level ends at the collapse (not an interruption)
        return o.stop_after_steps == 0 || cursor.dynamic_steps < o.stop_after_steps;
      };
      RunOptions run_options;
      run_options.progress = o.progress;
      const std::string progress_label = "level " + label + " %";
      run_options.label = progress_label.c_str();
      const auto summary = [&] {
        try {
          return run_until(sim, cursor.level_start + L.duration, step, run_options);
        } catch (const RunawayError& e) {
          history.end_level();  // the history up to the stop is whole: it keeps its name, for the plots
          if (std::string_view(e.what()).starts_with("level ")) throw;  // check_runaway's, which names it already
          throw RunawayError("level " + label + " %: " + e.what() + detail::pass_through_hint(e.what(), o, s));
        }
      }();
      cursor.level_wall_seconds = wall_before + summary.wall_seconds;
      L.steps = cursor.level_steps;
      L.wall_seconds = cursor.level_wall_seconds;
      L.interrupted = summary.interrupted && !L.collapse.collapsed;
      L.simulated = sim.time() - cursor.level_start;
      L.peaks = history.peaks();
      for (std::size_t p = 0; p < history.points(); ++p) L.residual_displacement.push_back(history.last_displacement(p));
      memory.update(sim, model);
      L.damage = memory.census(sim, model, s.laws.groups());
      L.detections = sim.detections();
      L.detection_seconds = sim.detection_seconds();
      L.energy = sim.energy();
      L.energy_at_start = cursor.energy_at_level_start;
      L.hold = sim.timestep_hold();
      if (L.interrupted) {
        save();  // the level stays open in the checkpoint, which holds the finished levels only
        r.levels.push_back(L);  // the report shows this one as far as it went
        r.interrupted = true;
        break;
      }
      history.end_level();
      cursor.table_velocity = table_motion.final_velocity();
      model.base_motion = motion::BaseMotion::constant(cursor.table_velocity * axis);  // where this level left it
      cursor.in_level = false;
      r.levels.push_back(L);
      if (!o.out_dir.empty()) {
        detail::write_level_outputs(o.out_dir, label, sim, model, s, settled_position, memory);
        detail::write_report(o.out_dir, r);
        ++cursor.level;
        save();
        --cursor.level;
        last_checkpoint = clock::now();
      }
      if (L.collapse.collapsed) {
        if (o.progress)
          std::fprintf(stderr, "level %s %%: the structure collapsed %.3f s into the level (%s moved %.3g m, beyond "
                       "--collapse-displacement %.3g m%s); no further level runs\n", label.c_str(), L.collapse.time,
                       L.collapse.point.c_str(), L.collapse.displacement, o.collapse_displacement,
                       o.default_note("--collapse-displacement").c_str());
        break;
      }
    }
  });
  r.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  if (!o.out_dir.empty()) detail::write_report(o.out_dir, r);
  return r;
}

}  // namespace blockdem::analysis
