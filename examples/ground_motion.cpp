// ground_motion: reads a strong-motion record (PEER .AT2, ESM/ITACA ASCII, plain text) or the built-in synthetic
// AQA75 stand-in, and measures, processes, truncates it or computes its response spectrum (paper Sect. 2, 6.1.2).
//
//   ground_motion info     FILE|--synthetic [--units g|m/s2|cm/s2] [--dt DT]
//   ground_motion spectrum FILE|--synthetic [--damping 0.05] [--periods 0.05,0.1,...] [--out spectrum.csv]
//   ground_motion truncate FILE|--synthetic --method wavelet|arias|window [...] [--out cut.csv]
//   ground_motion process  FILE|--synthetic [--scale F | --target-pga A] [--resample DT] [--baseline SPEC]
//                          [--out processed.csv]
//
// Results go to stdout as JSON (CSV files with --out). Exit status: 0 on success, 2 on bad input (the message names
// the file and line, or the option and its allowed range).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/motion/arias.hpp"
#include "blockdem/motion/baseline.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/processing.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/spectrum.hpp"
#include "blockdem/motion/synthetic.hpp"
#include "blockdem/motion/truncation.hpp"
#include "blockdem/motion/wavelet_truncation.hpp"
#include "blockdem/motion/writers.hpp"
#include "cli.hpp"

namespace {

using namespace blockdem;
using namespace blockdem::motion;

using programs::exit_bad_input;

/// The record every subcommand reads: FILE with --units and --dt, or --synthetic.
struct Input {
  std::string file;
  bool synthetic = false;
  std::string units;
  double dt = 0.0;

  void add_to(CLI::App& command) {
    auto* path = command.add_option("file", file, "record file: PEER .AT2, ESM/ITACA ASCII, or one/two-column text");
    auto* flag = command.add_flag("--synthetic", synthetic,
                                  "use the built-in SYNTHETIC stand-in for AQA75 (PGA 4.25 m/s2, PGV 26.33 cm/s, "
                                  "PGD 37.0 mm, T_p 0.526 s, 25 s), not the recorded AQA motion");
    path->excludes(flag);
    command.add_option("--units", units, "units of the samples: g, m/s2 or cm/s2 (default: from the file's header)")
        ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}));
    command.add_option("--dt", dt, "time step in s, for one-column files");
  }

  Record read() const {
    if (synthetic) {
      std::fprintf(stderr, "ground_motion: note: using the built-in SYNTHETIC stand-in for AQA75, not the recorded "
                           "AQA motion\n");
      return synthetic_aqa75();
    }
    if (file.empty()) throw InvalidArgument("give a record FILE or --synthetic");
    ReadOptions options;
    if (!units.empty()) options.units = parse_acceleration_unit(units);
    if (dt != 0.0) options.dt = dt;
    return read_record(file, options);
  }
};

void describe(io::JsonObject& json, const Record& record) {
  json.add("record", record.name).add("source", record.source).add("synthetic", record.synthetic);
}

void add_measures(io::JsonObject& json, const Record& record) {
  const auto peaks = peak_values(record);
  const auto d5_95 = significant_duration(record, 0.05, 0.95);
  const auto d10_90 = significant_duration(record, 0.10, 0.90);
  json.add("dt", record.dt)
      .add("npts", static_cast<long long>(record.size()))
      .add("start_s", record.start_time)
      .add("duration_s", record.duration())
      .add("pga_m_s2", peaks.pga)
      .add("pga_g", peaks.pga / standard_gravity)
      .add("pgv_m_s", peaks.pgv)
      .add("pgd_m", peaks.pgd)
      .add("arias_m_s", arias_intensity(record))
      .add("d5_95_s", d5_95.duration)
      .add("t5_s", d5_95.start)
      .add("t95_s", d5_95.end)
      .add("d10_90_s", d10_90.duration)
      .add("t10_s", d10_90.start)
      .add("t90_s", d10_90.end);
}

void write_record(const std::string& path, const Record& record) {
  io::write_atomically(path, [&](std::ostream& out) { write_record_csv(out, record); });
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int run_info(const Input& input) {
  const auto record = input.read();
  io::JsonObject json;
  describe(json, record);
  json.add("input_units", to_string(record.input_unit));
  add_measures(json, record);
  if (record.header_pga) json.add("header_pga_m_s2", *record.header_pga);
  const double upper = std::min(10.0, record.duration());
  if (upper > 0.05) {
    const auto dominant = dominant_period(record, 0.05, 0.05, upper);
    json.add("dominant_period_s", dominant.period).add("psv_at_dominant_m_s", dominant.psv);
  }
  fmt::print("{}\n", json.str());
  return 0;
}

int run_spectrum(const Input& input, double damping, std::vector<double> periods, const std::string& out_path) {
  const auto record = input.read();
  if (periods.empty()) periods = default_periods();
  const auto start = std::chrono::steady_clock::now();
  const auto spectrum = response_spectrum(record, periods, damping);
  const double seconds = seconds_since(start);
  if (out_path.empty()) {
    std::ostringstream csv;
    write_spectrum_csv(csv, spectrum, record);
    fmt::print("{}", csv.str());
    return 0;
  }
  io::write_atomically(out_path, [&](std::ostream& out) { write_spectrum_csv(out, spectrum, record); });
  std::size_t peak_psa = 0, peak_psv = 0;
  for (std::size_t j = 0; j < spectrum.period.size(); ++j) {
    if (spectrum.psa[j] > spectrum.psa[peak_psa]) peak_psa = j;
    if (spectrum.psv[j] > spectrum.psv[peak_psv]) peak_psv = j;
  }
  io::JsonObject json;
  describe(json, record);
  json.add("damping", damping)
      .add("periods", static_cast<long long>(spectrum.period.size()))
      .add("out", out_path)
      .add("max_psa_m_s2", spectrum.psa[peak_psa])
      .add("period_max_psa_s", spectrum.period[peak_psa])
      .add("max_psv_m_s", spectrum.psv[peak_psv])
      .add("period_max_psv_s", spectrum.period[peak_psv])
      .add("seconds", seconds);
  fmt::print("{}\n", json.str());
  return 0;
}

struct TruncateOptions {
  std::string method;
  std::optional<double> start, end;
  std::vector<double> arias_range{0.05, 0.95};
  std::string baseline = "none";
  std::string out;
  std::string pulse_out;
  WaveletTruncationOptions wavelet;
  std::optional<double> tp;
  std::vector<double> gamma_range{1.01, 10.0};
  int gamma_samples = 100;
  std::vector<double> t0_range;
  int t0_samples = 100;
  bool no_refine = false;
  std::string amplitude = "spectral";
  std::optional<double> max_pgv, max_pga, max_pgd;
};

int run_truncate(const Input& input, TruncateOptions o) {
  const auto record = correct_baseline(input.read(), parse_baseline(o.baseline));
  io::JsonObject json;
  describe(json, record);
  json.add("method", o.method).add("baseline", to_string(parse_baseline(o.baseline)));
  Truncation cut;
  if (o.method == "window") {
    if (!o.start || !o.end) throw InvalidArgument("--method window needs --start and --end (s)");
    cut = truncate_window(record, *o.start, *o.end);
  } else if (o.method == "arias") {
    if (!(o.arias_range[0] >= 0 && o.arias_range[0] < o.arias_range[1] && o.arias_range[1] <= 1))
      throw InvalidArgument(fmt::format("--arias-range must satisfy 0 <= lower < upper <= 1, got {:g} {:g}", o.arias_range[0],
                                        o.arias_range[1]));
    cut = truncate_arias(record, o.arias_range[0], o.arias_range[1]);
    json.add("arias_range", std::span<const double>(o.arias_range));
  } else {
    auto& w = o.wavelet;
    w.period = o.tp;
    w.gamma = GridRange{o.gamma_range[0], o.gamma_range[1], o.gamma_samples};
    if (!o.t0_range.empty()) w.t0 = GridRange{o.t0_range[0], o.t0_range[1], o.t0_samples};
    else if (o.t0_samples != 100) w.t0 = GridRange{record.start_time, record.end_time(), o.t0_samples};
    w.refine = !o.no_refine;
    w.amplitude = o.amplitude == "least-squares" ? PulseAmplitude::least_squares : PulseAmplitude::spectral;
    w.max_velocity = o.max_pgv;
    w.max_acceleration = o.max_pga;
    w.max_displacement = o.max_pgd;
    const auto start = std::chrono::steady_clock::now();
    const auto fit = wavelet_truncation(record, w);
    const double seconds = seconds_since(start);
    cut = fit.truncation;
    json.add("tp_s", fit.pulse.period)
        .add("tp_from_spectrum", fit.period_from_spectrum)
        .add("psv_tp_m_s", fit.psv_at_period)
        .add("gamma", fit.pulse.gamma)
        .add("t0_s", fit.pulse.t0)
        .add("phase_rad", fit.pulse.phase)
        .add("amplitude_m_s", fit.pulse.amplitude)
        .add("amplitude_rule", o.amplitude)
        .add("correlation", fit.correlation)
        .add("grid_correlation", fit.grid_correlation)
        .add("pulse_start_s", fit.pulse.start())
        .add("pulse_end_s", fit.pulse.end())
        .add("limit_pgv_m_s", fit.limits.velocity)
        .add("limit_pga_m_s2", fit.limits.acceleration)
        .add("limit_pgd_m", fit.limits.displacement)
        .add("candidates", fit.candidates)
        .add("feasible_candidates", fit.feasible_candidates)
        .add("search_seconds", seconds);
    if (!o.pulse_out.empty()) {
      const auto velocity = integrate(record).velocity;
      io::write_atomically(o.pulse_out, [&](std::ostream& out) {
        write_provenance(out, record);
        out << "# fitted M&P pulse (eq. 31) against the record's velocity\n"
            << "time_s,record_velocity_m_s,pulse_velocity_m_s\n";
        for (std::size_t i = 0; i < record.size(); ++i)
          out << fmt::format("{:.9g},{:.9g},{:.9g}\n", record.time(i), velocity[i], fit.pulse.velocity(record.time(i)));
      });
      json.add("pulse_out", o.pulse_out);
    }
  }
  json.add("start_s", cut.start)
      .add("end_s", cut.end)
      .add("duration_s", cut.end - cut.start)
      .add("arias_fraction", cut.arias_fraction)
      .add("npts", static_cast<long long>(cut.record.size()));
  if (!o.out.empty()) {
    write_record(o.out, cut.record);
    json.add("out", o.out);
  }
  fmt::print("{}\n", json.str());
  return 0;
}

struct ProcessOptions {
  std::optional<double> scale, target_pga, resample_dt;
  std::string baseline = "none";
  std::string out;
};

int run_process(const Input& input, const ProcessOptions& o) {
  // Bounds far beyond any record, that keep its measures finite (a factor of 1e308 leaves none).
  if (o.scale && !(*o.scale >= -1000 && *o.scale <= 1000 && *o.scale != 0))
    throw InvalidArgument(fmt::format("--scale must be in [-1000, 1000] and not 0, got {:g}", *o.scale));
  if (o.target_pga && !(*o.target_pga > 0 && *o.target_pga <= 20 * standard_gravity))
    throw InvalidArgument(fmt::format("--target-pga must be in (0, {:g}] m/s^2 (20 g), got {:g}", 20 * standard_gravity, *o.target_pga));
  const auto steps = parse_baseline(o.baseline);
  auto record = input.read();
  if (o.resample_dt) record = resample(std::move(record), *o.resample_dt);
  record = correct_baseline(std::move(record), steps);
  if (o.scale) record = scale(std::move(record), *o.scale);
  if (o.target_pga) record = scale_to_pga(std::move(record), *o.target_pga);
  io::JsonObject json;
  describe(json, record);
  json.add("baseline", to_string(steps));
  if (o.resample_dt) json.add("resampled_dt", *o.resample_dt);
  if (o.scale) json.add("scale", *o.scale);
  if (o.target_pga) json.add("target_pga_m_s2", *o.target_pga);
  add_measures(json, record);
  if (!o.out.empty()) {
    write_record(o.out, record);
    json.add("out", o.out);
  }
  fmt::print("{}\n", json.str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Read, measure, process and truncate strong-motion records; response spectra (blockdem)"};
  app.require_subcommand(1);

  Input info_input;
  auto* info = app.add_subcommand("info", "print dt, npts, PGA, PGV, PGD, Arias intensity and durations as JSON");
  info_input.add_to(*info);

  Input spectrum_input;
  double damping = 0.05;
  std::vector<double> periods;
  std::string spectrum_out;
  auto* spectrum = app.add_subcommand("spectrum", "SD, PSV, PSA by the exact Nigam-Jennings recursion");
  spectrum_input.add_to(*spectrum);
  spectrum->add_option("--damping", damping, "damping ratio, in [0, 1)")->capture_default_str();
  spectrum->add_option("--periods", periods, "periods in s, comma-separated (default: 100 from 0.02 to 10 s)")
      ->delimiter(',');
  spectrum->add_option("--out", spectrum_out, "CSV file: period_s,sd_m,psv_m_s,psa_m_s2,psa_g (default: stdout)");

  Input truncate_input;
  TruncateOptions t;
  auto* truncate = app.add_subcommand("truncate", "cut the record to a window, an Arias range or a fitted pulse");
  truncate_input.add_to(*truncate);
  truncate->add_option("--method", t.method, "wavelet (Sect. 6.1.2), arias or window")
      ->required()
      ->check(CLI::IsMember({"wavelet", "arias", "window"}));
  truncate->add_option("--start", t.start, "window: start time in s");
  truncate->add_option("--end", t.end, "window: end time in s");
  truncate->add_option("--arias-range", t.arias_range, "arias: lower and upper fraction of the Arias intensity")
      ->expected(2)
      ->capture_default_str();
  truncate->add_option("--baseline", t.baseline, std::string("baseline correction before the cut: ") + baseline_grammar)
      ->capture_default_str();
  truncate->add_option("--damping", t.wavelet.damping_ratio, "wavelet: damping ratio of eq. 32 and of PSV, in (0, 1)")
      ->capture_default_str();
  truncate->add_option("--tp", t.tp, "wavelet: carrier period T_p in s (default: the dominant PSV peak)");
  truncate->add_option("--gamma-range", t.gamma_range, "wavelet: gamma grid bounds, > 1")->expected(2)->capture_default_str();
  truncate->add_option("--gamma-samples", t.gamma_samples, "wavelet: gamma grid samples")->capture_default_str();
  truncate->add_option("--t0-range", t.t0_range, "wavelet: t0 grid bounds in s (default: the record's span)")
      ->expected(2);
  truncate->add_option("--t0-samples", t.t0_samples, "wavelet: t0 grid samples")->capture_default_str();
  truncate->add_option("--phase-samples", t.wavelet.phase_samples, "wavelet: phase samples over [0, 2 pi)")
      ->capture_default_str();
  truncate->add_flag("--no-refine", t.no_refine, "wavelet: keep the best grid point (no compass search)");
  truncate->add_option("--amplitude", t.amplitude, "wavelet: spectral (eq. 32 corrected) or least-squares")
      ->check(CLI::IsMember({"spectral", "least-squares"}))
      ->capture_default_str();
  truncate->add_option("--max-pgv", t.max_pgv, "wavelet: bound on |v| of the pulse, m/s (default: the record's PGV)");
  truncate->add_option("--max-pga", t.max_pga, "wavelet: bound on |a| of the pulse, m/s2 (default: the record's PGA)");
  truncate->add_option("--max-pgd", t.max_pgd, "wavelet: bound on |u| of the pulse, m (default: the record's PGD)");
  truncate->add_option("--out", t.out, "CSV file for the truncated record");
  truncate->add_option("--pulse-out", t.pulse_out, "wavelet: CSV file of the record's and the pulse's velocity");

  Input process_input;
  ProcessOptions p;
  auto* process = app.add_subcommand("process", "resample, baseline-correct and scale (in that order)");
  process_input.add_to(*process);
  auto* scale_option = process->add_option("--scale", p.scale, "multiply the acceleration by this factor");
  process->add_option("--target-pga", p.target_pga, "scale to this PGA in m/s2")->excludes(scale_option);
  process->add_option("--resample", p.resample_dt, "new time step in s");
  process->add_option("--baseline", p.baseline, std::string("baseline correction: ") + baseline_grammar)
      ->capture_default_str();
  process->add_option("--out", p.out, "CSV file for the processed record");

  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;

  try {
    if (info->parsed()) return run_info(info_input);
    if (spectrum->parsed()) return run_spectrum(spectrum_input, damping, periods, spectrum_out);
    if (truncate->parsed()) return run_truncate(truncate_input, t);
    if (process->parsed()) return run_process(process_input, p);
  } catch (const InputError& e) {
    std::fprintf(stderr, "ground_motion: error: %s\n", e.what());
    return exit_bad_input;
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "ground_motion: error: %s\n", e.what());
    return exit_bad_input;
  }
  return 0;
}
