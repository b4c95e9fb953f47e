#pragma once
// Running the cases of a sweep (analysis/sweep.hpp) and summing them up. Each case runs its study (the vault's, or a
// model file's structure: SweepRunOptions::study) into its own folder OUT/cases/<id>/ (the outputs of `cross_vault
// run` or `blockdem run`) and ends by writing OUT/cases/<id>/case.json: how it
// ended (done, failed with its message, interrupted) and its row of the summary. A case whose case.json says done,
// under the same base options (the fingerprint), is not run again; a failed one is run afresh; an interrupted one
// continues from its checkpoint. The summary (summary.csv, summary.json in OUT) is one row per case in the order of
// the expansion, so it is the same however the cases were shared out (one process, MPI ranks, a job array).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/analysis/error_metrics.hpp"
#include "blockdem/analysis/sweep.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/io/json_reader.hpp"
#include "blockdem/motion/spectrum.hpp"
#include "blockdem/parallel/task_farm.hpp"

namespace blockdem::analysis {

enum class CaseStatus { pending, done, failed, interrupted };
inline constexpr const char* name(CaseStatus s) {
  switch (s) {
    case CaseStatus::pending: return "pending";
    case CaseStatus::done: return "done";
    case CaseStatus::failed: return "failed";
    case CaseStatus::interrupted: return "interrupted";
  }
  return "?";
}

/// How the cases of a sweep are run and where they go.
struct SweepRunOptions {
  std::string out_dir;      // OUT: OUT/cases/<id>/ per case, OUT/summary.csv and OUT/summary.json
  std::string fingerprint;  // the base options as the caller states them; a finished case is skipped only under the same
  std::string measured;     // CSV of measured channels (SweepSpec::measured); empty: no error metrics
  double measured_level = 0;  // % of the history compared (0: each case's last level)
  bool progress = true;     // each study's progress line
  /// Runs a case's study: the vault's (run_vault_study) for `cross_vault sweep`, a model file's structure for
  /// `blockdem sweep`. Must be set.
  std::function<StudyResult(const VaultStudyOptions&)> study;
  /// The two channels of the summary's peak and bias columns, and the monitor point of its residual displacement:
  /// the vault's crown drift OC1-y and its accelerometer ACC18-y (Fig. 13); for a model file, its first monitor point
  /// along the excitation's axis.
  std::string displacement_channel = "OC1_uy", acceleration_channel = "ACC18_ay", residual_point = "OC1";
  std::string program = "blockdem cross_vault sweep";  // summary.json's "program"
  bool study_is_model = false;  // a model file's (the kinematics column says "model")
};

/// A case's line in the summary: how it ended and its row (CSV and JSON).
struct CaseRow {
  std::size_t index = 0;
  std::string id;
  CaseStatus status = CaseStatus::pending;
  std::string message;     // why it failed or stopped
  bool skipped = false;    // finished in an earlier run of the sweep, not run again
  double wall_seconds = 0;
  std::string csv, json;   // the summary's row
};

/// The columns of summary.csv (units in the names; an empty field: not applicable or not measured). The peaks,
/// damage and biases are those of the case's last level (the measured level for the biases), of the run's two
/// channels (lower case in the names: oc1_uy_max_mm, acc18_ay_max_m_s2 for the vault). The wall time comes last: it
/// is the one column that differs between two runs of the same sweep.
inline std::string summary_header(const SweepRunOptions& run) {
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const std::string u = lower(run.displacement_channel), a = lower(run.acceleration_channel);
  const std::string residual = lower(run.residual_point) + u.substr(std::min(u.size(), u.find_last_of('_')));
  std::string h = "index,id,status,message,kinematics,record,scheme,zeta,frequency_hz,band_lower_hz,band_upper_hz,branches,"
                  "measure,intensity_g,level_percent,input_pga_g,input_sa_g,steps,";
  h += u + "_max_mm," + u + "_min_mm," + a + "_max_m_s2," + a + "_min_m_s2,residual_" + residual + "_mm,cracked,crushed,";
  h += "damaged,peak_bias_" + u + "_percent,peak_bias_" + a + "_percent,bias_" + u + "_max_percent,bias_" + u +
       "_min_percent,bias_" + a + "_max_percent,bias_" + a + "_min_percent,eps_rmsd_uy_percent,wall_seconds";
  return h;
}

inline std::string case_folder(const SweepRunOptions& run, const SweepCase& c) { return run.out_dir + "/cases/" + c.id; }

namespace detail {

inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// A CSV field: numbers in shortest round-trip form (empty if NaN), text quoted when it needs to be.
inline std::string csv_number(double v) { return std::isfinite(v) ? io::JsonObject::number(v) : std::string(); }
inline std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"') q += '"';
    q += ch == '\n' || ch == '\r' ? ' ' : ch;
  }
  return q + '"';
}

/// The input's intensity per % of the original record: PGA and (measure sa) Sa(T, 5 %), in g.
struct IntensityPerPercent {
  double pga = nan, sa = nan;
};

inline IntensityPerPercent intensity_per_percent(const SweepCase& c, const VaultStudyOptions& o) {
  std::string note;
  const motion::Record cut = input_record(o, note);
  IntensityPerPercent r;
  r.pga = motion::peak_values(cut).pga / standard_gravity / o.record_level;
  if (c.measure == IntensityMeasure::sa) {
    const double omega = 2 * std::numbers::pi / c.sa_period;
    r.sa = omega * omega * motion::spectral_displacement(cut, c.sa_period, 0.05) / standard_gravity / o.record_level;
  }
  return r;
}

}  // namespace detail

/// The levels (% of the original record) that scale the case's record to its intensity targets (PGA or Sa(T) in g),
/// from the record as the case cuts and corrects it. Throws InvalidArgument if the record has no such intensity or a
/// target needs more than 1000 % of it.
inline std::vector<double> resolve_intensities(const SweepCase& c, const VaultStudyOptions& o,
                                               const detail::IntensityPerPercent& per_percent) {
  if (c.measure == IntensityMeasure::level) return o.levels;
  const double unit = c.measure == IntensityMeasure::pga ? per_percent.pga : per_percent.sa;
  const std::string what = c.measure == IntensityMeasure::pga ? "PGA" : "Sa(" + detail::id_number(c.sa_period) + " s)";
  if (!(unit > 0)) throw InvalidArgument("sweep, case " + c.id + ": the record has no " + what + " to scale");
  std::vector<double> levels;
  for (double target : c.intensities) {
    const double level = target / unit;
    if (!(level <= 1000))
      throw InvalidArgument("sweep, case " + c.id + ": " + what + " = " + detail::id_number(target) + " g needs " +
                            detail::id_number(level) + " % of the record, beyond 1000 %");
    levels.push_back(level);
  }
  return levels;
}

namespace detail {

/// The row of a case from its study (r: null if it failed before it had one).
inline void fill_row(CaseRow& row, const SweepCase& c, const SweepRunOptions& run, const VaultStudyResult* r,
                     const IntensityPerPercent& im, const std::vector<ChannelComparison>& compared, double eps_uy) {
  const std::string& u_channel = run.displacement_channel;
  const std::string& a_channel = run.acceleration_channel;
  const char axis = u_channel.empty() ? 'y' : u_channel.back();
  const auto& o = c.options;
  // A model file's blocks are rigid or deformable each: its cases say "model".
  const std::string kinematics = run.study_is_model ? "model" : name(o.kinematics);
  const bool has_zeta = o.damping != DampingScheme::none;
  const bool has_frequency = o.damping == DampingScheme::mass || o.damping == DampingScheme::stiffness;
  const bool has_band = o.damping == DampingScheme::maxwell || o.damping == DampingScheme::rayleigh;
  const bool has_branches = o.damping == DampingScheme::maxwell;
  const LevelResult* L = r && !r->levels.empty() ? &r->levels.back() : nullptr;
  const double level = L ? L->level : nan;
  const std::size_t which = L ? r->levels.size() - 1 : 0;
  const double intensity = c.measure != IntensityMeasure::level && which < c.intensities.size() && L ? c.intensities[which] : nan;
  auto peak = [&](const std::string& channel, bool max) {
    if (!L) return nan;
    for (const auto& p : L->peaks)
      if (p.name == channel) return max ? p.max : p.min;
    return nan;
  };
  auto residual_uy = [&] {
    if (!L) return nan;
    for (std::size_t p = 0; p < r->monitor_points.size() && p < L->residual_displacement.size(); ++p)
      if (r->monitor_points[p] == run.residual_point) return L->residual_displacement[p][axis - 'x'];
    return nan;
  };
  auto channel = [&](const std::string& name) -> const ChannelComparison* {
    for (const auto& x : compared)
      if (x.channel == name) return &x;
    return nullptr;
  };
  const ChannelComparison* oc1 = channel(u_channel);
  const ChannelComparison* acc18 = channel(a_channel);
  auto bias = [](const ChannelComparison* x, double ChannelComparison::*field) { return x ? x->*field : nan; };
  auto peak_bias = [](const ChannelComparison* x, double PeakErrors::*field) { return x ? x->peaks.*field : nan; };
  const long long steps = r ? [&] {
    long long n = 0;
    for (const auto& l : r->levels) n += l.steps;
    return n;
  }() : 0;
  const double count_nan = L ? 0.0 : nan;
  const double values[] = {
      has_zeta ? o.scheme_zeta() : nan, has_frequency ? o.frequency_hz : nan, has_band ? o.lower_hz : nan,
      has_band ? o.upper_hz : nan, has_branches ? static_cast<double>(o.branches) : nan,
  };
  std::string csv = std::to_string(c.index) + "," + csv_text(c.id) + "," + name(row.status) + "," + csv_text(row.message) + "," +
                    kinematics + "," + csv_text(record_tag(o.record_path)) + "," + name(o.damping);
  for (double v : values) (csv += ',') += csv_number(v);  // (not "," + string: GCC 12 warns wrongly of an overlap)
  const double more[] = {intensity,
                         level,
                         L ? im.pga * level : nan,
                         L && c.measure == IntensityMeasure::sa ? im.sa * level : nan,
                         r ? static_cast<double>(steps) : nan,
                         1e3 * peak(u_channel, true),
                         1e3 * peak(u_channel, false),
                         peak(a_channel, true),
                         peak(a_channel, false),
                         1e3 * residual_uy(),
                         L ? static_cast<double>(L->damage.total.cracked) : count_nan,
                         L ? static_cast<double>(L->damage.total.crushed) : count_nan,
                         L ? static_cast<double>(L->damage.total.damaged) : count_nan,
                         bias(oc1, &ChannelComparison::peak_bias_percent),
                         bias(acc18, &ChannelComparison::peak_bias_percent),
                         peak_bias(oc1, &PeakErrors::max_signed_percent),
                         peak_bias(oc1, &PeakErrors::min_signed_percent),
                         peak_bias(acc18, &PeakErrors::max_signed_percent),
                         peak_bias(acc18, &PeakErrors::min_signed_percent),
                         eps_uy,
                         row.wall_seconds};
  (csv += ',') += name(c.measure);
  for (double v : more) (csv += ',') += csv_number(v);
  row.csv = std::move(csv);

  io::JsonObject j;
  j.add("index", static_cast<long long>(c.index)).add("id", c.id).add("status", name(row.status)).add("message", row.message)
      .add("kinematics", kinematics).add("record", o.record_path.empty() ? std::string("aqa75 (built-in)") : o.record_path)
      .add("scheme", name(o.damping));
  if (has_zeta) j.add("zeta", o.scheme_zeta());
  if (has_frequency) j.add("frequency_hz", o.frequency_hz);
  if (has_band) j.add("band_hz", std::vector<double>{o.lower_hz, o.upper_hz});
  if (has_branches) j.add("branches", o.branches);
  j.add("measure", name(c.measure));
  if (c.measure != IntensityMeasure::level) j.add("intensities_g", c.intensities);
  if (c.measure == IntensityMeasure::sa) j.add("sa_period_s", c.sa_period);
  j.add("levels_percent", o.levels).add("wall_seconds", row.wall_seconds).add("steps", steps);
  std::vector<io::JsonObject> levels;
  if (r)
    for (std::size_t k = 0; k < r->levels.size(); ++k) {
      const auto& l = r->levels[k];
      io::JsonObject q, peaks;
      for (const auto& p : l.peaks) {
        if (p.name != u_channel && p.name != a_channel && p.name != run.residual_point + "_ux") continue;
        io::JsonObject m;
        m.add("max", p.max).add("min", p.min);
        peaks.add(p.name, m);
      }
      q.add("level_percent", l.level).add("input_pga_g", im.pga * l.level);
      if (c.measure == IntensityMeasure::sa) q.add("input_sa_g", im.sa * l.level);
      q.add("steps", l.steps).add("wall_seconds", l.wall_seconds).add("peaks", peaks)
          .add("cracked", l.damage.total.cracked).add("crushed", l.damage.total.crushed).add("damaged", l.damage.total.damaged)
          .add("energy_balance_error", l.energy.balance_error).add("collapsed", l.collapse.collapsed);
      levels.push_back(q);
    }
  j.add("levels", levels);
  if (!compared.empty()) {
    io::JsonObject m;
    for (const auto& x : compared) {
      io::JsonObject q;
      q.add("peak_bias_percent", x.peak_bias_percent).add("max_signed_percent", x.peaks.max_signed_percent)
          .add("min_signed_percent", x.peaks.min_signed_percent).add("rmsd_error_percent", x.rmsd_error_percent);
      m.add(x.channel, q);
    }
    m.add("eps_rmsd_uy_percent", eps_uy);
    j.add("compared", m);
  }
  row.json = j.str();
}

/// A case's record of how it ended: its status, the fingerprint it ran under, its row.
inline void write_case_file(const std::string& dir, const CaseRow& row, const std::string& fingerprint) {
  io::JsonObject j;
  j.add("id", row.id).add("status", name(row.status)).add("message", row.message).add("fingerprint", fingerprint)
      .add("wall_seconds", row.wall_seconds).add("csv", row.csv).add_raw("row", row.json);
  io::write_atomically(dir + "/case.json", [&](std::ostream& out) { out << j.str() << '\n'; });
}

/// The case's earlier record, if it has one that reads.
struct EarlierCase {
  bool present = false;
  CaseStatus status = CaseStatus::pending;
  std::string fingerprint;
  CaseRow row;
};

inline EarlierCase read_case_file(const std::string& dir, const SweepCase& c) {
  EarlierCase e;
  const std::string path = dir + "/case.json";
  if (!std::filesystem::exists(path)) return e;
  try {
    const io::JsonValue v = io::read_json_file(path);
    const std::string status = v.find("status") ? v.find("status")->as_string() : "";
    for (const CaseStatus s : {CaseStatus::done, CaseStatus::failed, CaseStatus::interrupted})
      if (status == name(s)) e.status = s;
    e.fingerprint = v.find("fingerprint") ? v.find("fingerprint")->as_string() : "";
    e.row.index = c.index;
    e.row.id = c.id;
    e.row.status = e.status;
    e.row.message = v.find("message") ? v.find("message")->as_string() : "";
    e.row.wall_seconds = v.find("wall_seconds") ? v.find("wall_seconds")->as_number() : 0;
    e.row.csv = v.find("csv") ? v.find("csv")->as_string() : "";
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();  // the row as written, without a writer to reproduce it
    const auto at = s.find("\"row\": ");
    e.row.json = at == std::string::npos ? std::string("{}") : s.substr(at + 7, s.rfind('}') - at - 7);
    while (!e.row.json.empty() && (e.row.json.back() == '\n' || e.row.json.back() == ' ')) e.row.json.pop_back();
    e.present = e.status != CaseStatus::pending && !e.row.csv.empty();
  } catch (const InputError&) {
    e.present = false;  // a damaged record: the case runs again
  } catch (const InvalidArgument&) {
    e.present = false;
  }
  return e;
}

}  // namespace detail

/// Runs one case of a sweep into OUT/cases/<id>/ (see the top of this file), unless an earlier run finished it under
/// the same fingerprint. Never throws for the case's own failure (bad record, runaway, bad target): the row says
/// failed, with the message. `poll` (may be empty) is called about every 1024 steps.
inline CaseRow run_sweep_case(const SweepCase& c, const SweepRunOptions& run, const std::function<void()>& poll = {}) {
  const std::string dir = case_folder(run, c);
  const detail::EarlierCase earlier = detail::read_case_file(dir, c);
  if (earlier.present && earlier.status == CaseStatus::done && earlier.fingerprint == run.fingerprint &&
      std::filesystem::exists(dir + "/report.json")) {
    CaseRow row = earlier.row;
    row.skipped = true;
    return row;
  }
  CaseRow row;
  row.index = c.index;
  row.id = c.id;
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  VaultStudyOptions o = c.options;
  o.out_dir = dir;
  o.progress = run.progress;
  o.poll = poll;
  const std::string checkpoint = dir + "/" + study_checkpoint_file;
  if (earlier.present && earlier.status == CaseStatus::interrupted && earlier.fingerprint == run.fingerprint &&
      std::filesystem::exists(checkpoint))
    o.resume = checkpoint;
  VaultStudyResult result;
  bool ran = false;
  detail::IntensityPerPercent im;
  std::vector<ChannelComparison> compared;
  double eps_uy = detail::nan;
  try {
    im = detail::intensity_per_percent(c, o);
    o.levels = resolve_intensities(c, o, im);
    if (!run.study) throw std::logic_error("SweepRunOptions::study is not set");
    result = run.study(o);
    ran = true;
    row.status = result.interrupted ? CaseStatus::interrupted : CaseStatus::done;
    if (result.interrupted) row.message = "stopped; the next run of the sweep continues it from its checkpoint";
    const bool collapsed = !result.levels.empty() && result.levels.back().collapse.collapsed;
    if (collapsed)  // an IDA's end: the levels after this one were not run
      row.message = "collapsed at " + detail::level_label(result.levels.back().level) + " %, " +
                    models::detail::num(result.levels.back().collapse.time) + " s into the level";
    const double level = run.measured_level > 0 ? run.measured_level : o.levels.back();
    // After a collapse, the measured level is compared only if it ran whole, before the collapse.
    const bool level_run = std::any_of(result.levels.begin(), result.levels.end(), [&](const LevelResult& l) {
      return l.level == level && !l.collapse.collapsed;
    });
    if (!run.measured.empty() && !result.interrupted && (!collapsed || level_run)) {
      const auto simulated = read_csv_table(dir + "/history_" + detail::level_label(level) + ".csv");
      compared = compare_tables(simulated, read_csv_table(run.measured));
      if (!run.study_is_model) {  // eq. 27-28 average the vault's cameras OC1, OC2, OC4
        try {
          eps_uy = mean_rmsd_error_percent(compared, "_uy");
        } catch (const InvalidArgument& e) {  // the measurement lacks a camera of eq. 27: the row says so
          row.message += std::string(row.message.empty() ? "" : "; ") + "eps_rmsd_uy not computed: " + e.what();
        }
      }
    }
  } catch (const InvalidArgument& e) {  // the case's input: an option, a record, a target the record cannot reach
    row.status = CaseStatus::failed;
    row.message = e.what();
  } catch (const InputError& e) {
    row.status = CaseStatus::failed;
    row.message = e.what();
  } catch (const RunawayError& e) {
    row.status = CaseStatus::failed;
    row.message = e.what();
  } catch (const std::exception& e) {  // anything else is blockdem's fault, not the case's: said so, and the sweep goes on
    row.status = CaseStatus::failed;
    row.message = std::string("internal error (a fault of blockdem, not of this case's input; please report it): ") + e.what();
  }
  row.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  if (ran) row.wall_seconds = result.wall_seconds;
  SweepCase resolved = c;
  resolved.options.levels = o.levels;
  detail::fill_row(row, resolved, run, ran ? &result : nullptr, im, compared, eps_uy);
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  try {
    detail::write_case_file(dir, row, run.fingerprint);
  } catch (const std::exception& e) {
    row.status = CaseStatus::failed;
    row.message = std::string("cannot record the case: ") + e.what();
  }
  return row;
}

/// The row of a case that has not run (yet): from its case.json if it has one, else pending.
inline CaseRow recorded_row(const SweepCase& c, const SweepRunOptions& run) {
  const detail::EarlierCase earlier = detail::read_case_file(case_folder(run, c), c);
  if (earlier.present && earlier.fingerprint == run.fingerprint) return earlier.row;
  CaseRow row;
  row.index = c.index;
  row.id = c.id;
  detail::fill_row(row, c, run, nullptr, {}, {}, detail::nan);
  return row;
}

/// Writes OUT/summary.csv and OUT/summary.json (atomically) from the rows, one per case, in case order.
inline void write_summary(const SweepRunOptions& run, const std::vector<CaseRow>& rows) {
  io::write_atomically(run.out_dir + "/summary.csv", [&](std::ostream& out) {
    out << summary_header(run) << '\n';
    for (const auto& r : rows) out << r.csv << '\n';
  });
  std::size_t done = 0, failed = 0, pending = 0;
  for (const auto& r : rows) {
    done += r.status == CaseStatus::done;
    failed += r.status == CaseStatus::failed;
    pending += r.status == CaseStatus::pending || r.status == CaseStatus::interrupted;
  }
  std::string cases = "[";
  for (std::size_t i = 0; i < rows.size(); ++i) cases += (i ? ",\n" : "\n") + rows[i].json;
  cases += "\n]";
  io::JsonObject j;
  j.add("program", run.program).add("cases", static_cast<long long>(rows.size()))
      .add("done", static_cast<long long>(done)).add("failed", static_cast<long long>(failed))
      .add("not_finished", static_cast<long long>(pending)).add("measured", run.measured).add_raw("rows", cases);
  io::write_atomically(run.out_dir + "/summary.json", [&](std::ostream& out) { out << j.str() << '\n'; });
}

namespace detail {

inline constexpr char field_separator = '\x1f';  // between the fields of a row sent from one process to another

inline std::string encode(const CaseRow& r) {
  std::string s = std::to_string(r.index);
  for (const std::string* f : {&r.id, &r.message, &r.csv, &r.json}) (s += field_separator) += *f;
  s += field_separator;
  s += name(r.status);
  s += field_separator;
  s += r.skipped ? '1' : '0';
  s += field_separator;
  s += io::JsonObject::number(r.wall_seconds);
  return s;
}

inline CaseRow decode(const std::string& s) {
  std::vector<std::string> f(1);
  for (char ch : s) {
    if (ch == field_separator) f.emplace_back();
    else f.back() += ch;
  }
  if (f.size() != 8) throw InvalidArgument("sweep: a malformed case row came back from a worker");
  CaseRow r;
  try {
    r.index = std::stoull(f[0]);
    r.wall_seconds = std::stod(f[7]);
  } catch (const std::logic_error&) {  // std::invalid_argument, std::out_of_range: not numbers
    throw InvalidArgument("sweep: a malformed case row came back from a worker (index '" + f[0] + "', wall time '" +
                          f[7] + "')");
  }
  r.id = f[1];
  r.message = f[2];
  r.csv = f[3];
  r.json = f[4];
  for (const CaseStatus st : {CaseStatus::done, CaseStatus::failed, CaseStatus::interrupted, CaseStatus::pending})
    if (f[5] == name(st)) r.status = st;
  r.skipped = f[6] == "1";
  return r;
}

}  // namespace detail

/// Runs every case on the farm (each with run_sweep_case; a case that fails does not stop the others) and, on the
/// lead, writes the summary and returns the rows in case order (cases not started, after an interrupt, from their
/// folders: pending or as an earlier run left them); other processes return nothing. `on_case(row, rank)` is called
/// where each case ends (for a progress line).
template <parallel::TaskFarm Farm, class OnCase>
std::vector<CaseRow> run_sweep(const std::vector<SweepCase>& cases, const SweepRunOptions& run, Farm& farm, OnCase&& on_case) {
  std::error_code error;
  std::filesystem::create_directories(run.out_dir + "/cases", error);
  if (error) throw InvalidArgument("--out: cannot create the sweep folder '" + run.out_dir + "': " + error.message());
  const auto results = farm.run(cases.size(), [&](std::size_t k, const parallel::Poll& poll) {
    CaseRow row = run_sweep_case(cases[k], run, poll);
    on_case(row, farm.rank());
    return detail::encode(row);
  });
  if (!farm.lead()) return {};
  std::vector<CaseRow> rows;
  for (std::size_t k = 0; k < cases.size(); ++k)
    rows.push_back(results[k].empty() ? recorded_row(cases[k], run) : detail::decode(results[k]));
  write_summary(run, rows);
  return rows;
}

}  // namespace blockdem::analysis
