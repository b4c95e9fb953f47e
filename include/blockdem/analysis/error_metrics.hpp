#pragma once
// Error metrics of a simulated response against a measured one (Sect. 5.1 and 5.3): RMSD, NRMSE, peak errors and
// acceleration extremes, with the resampling and CSV reading needed to put both on one time grid.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/readers.hpp"

namespace blockdem::analysis {

namespace detail {

inline std::string show(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

inline void require_samples(std::span<const double> u, const char* what) {
  if (u.empty()) throw InvalidArgument(std::string(what) + ": the signal has no samples");
}

inline void require_same_size(std::span<const double> num, std::span<const double> exp, const char* what) {
  require_samples(exp, what);
  if (num.size() != exp.size())
    throw InvalidArgument(std::string(what) + ": the numerical signal has " + std::to_string(num.size()) +
                          " samples and the experimental one " + std::to_string(exp.size()) + "; resample first");
}

/// 100 (value / reference - 1), NaN when the reference is 0.
inline double signed_percent(double value, double reference) {
  return reference == 0 ? std::numeric_limits<double>::quiet_NaN() : 100 * (value - reference) / reference;
}

/// 100 |value - reference| / |reference|, NaN when the reference is 0.
inline double absolute_percent(double value, double reference) {
  return reference == 0 ? std::numeric_limits<double>::quiet_NaN() : 100 * std::abs(value - reference) / std::abs(reference);
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------------------------
// Metrics of sampled signals (any unit; the percentages are unitless)

/// Root mean square of the samples u(t_i), in the unit of u. Throws on an empty signal.
inline double rmsd(std::span<const double> u) {
  detail::require_samples(u, "RMSD");
  double sum = 0;
  for (const double x : u) sum += x * x;
  return std::sqrt(sum / static_cast<double>(u.size()));  // eq. 26
}

/// Mean of the channels' RMSD (the paper averages OC1, OC2 and OC4 of one direction). Throws when there is no
/// channel or a channel is empty.
inline double mean_rmsd(std::span<const std::span<const double>> channels) {
  if (channels.empty()) throw InvalidArgument("mean RMSD: no channel");
  double sum = 0;
  for (const auto u : channels) sum += rmsd(u);
  return sum / static_cast<double>(channels.size());  // eq. 27
}

/// 100 |RMSD_num - RMSD_exp| / RMSD_exp, percent. Throws unless RMSD_exp > 0.
inline double rmsd_relative_error_percent(double rmsd_num, double rmsd_exp) {
  if (!(rmsd_exp > 0) || !std::isfinite(rmsd_exp))
    throw InvalidArgument("RMSD relative error: the experimental RMSD must be > 0, got " + detail::show(rmsd_exp));
  return 100 * std::abs(rmsd_num - rmsd_exp) / rmsd_exp;  // eq. 28
}

/// Normalised root mean square error, percent:
///   NRMSE = 100 sqrt( (1/N) sum_i (num_i - exp_i)^2 ) / (max_i exp_i - min_i exp_i).
/// The paper reports NRMSE (Fig. 15b) without printing its formula; this is the common range-normalised form.
/// Both signals are on the same N sample times. Throws on empty input, different sizes or a constant `exp`.
inline double nrmse_percent(std::span<const double> num, std::span<const double> exp) {
  detail::require_same_size(num, exp, "NRMSE");
  const auto [lo, hi] = std::minmax_element(exp.begin(), exp.end());
  const double range = *hi - *lo;
  if (!(range > 0))
    throw InvalidArgument("NRMSE: the experimental signal is constant (range 0), so it cannot normalise the error");
  double sum = 0;
  for (std::size_t i = 0; i < exp.size(); ++i) sum += (num[i] - exp[i]) * (num[i] - exp[i]);
  return 100 * std::sqrt(sum / static_cast<double>(exp.size())) / range;
}

/// Errors of the peaks of a response (Fig. 15a), percent. The signed errors are 100 (P_num / P_exp - 1) for the
/// maximum (positive peak) and for the minimum (negative peak): positive when the simulation goes further than the
/// experiment in that direction, so 1.2 u_exp gives +20 at both peaks.
struct PeakErrors {
  double max_signed_percent = 0;     // 100 (max u_num - max u_exp) / max u_exp
  double max_percent = 0;            // its magnitude
  double min_signed_percent = 0;     // 100 (min u_num - min u_exp) / min u_exp
  double min_percent = 0;            // its magnitude
  double absolute_peak_percent = 0;  // 100 |max|u_num| - max|u_exp|| / max|u_exp|
};

/// The maxima and minima of the two signals (their lengths may differ). Throws on an empty signal or when an
/// experimental peak is 0 (its relative error is undefined).
inline PeakErrors peak_errors(std::span<const double> num, std::span<const double> exp);

/// The extremes of a signal over the analysis window J (all its samples), in the unit of the signal.
struct Extremes {
  double max = 0;
  double min = 0;
};

inline Extremes extremes(std::span<const double> a) {
  detail::require_samples(a, "extremes");
  const auto [lo, hi] = std::minmax_element(a.begin(), a.end());
  return {*hi, *lo};  // eq. 29
}

/// RE_max = 100 |a_max^NUM - a_max^EXP| / |a_max^EXP|, percent. Throws when a_max^EXP is 0.
inline double re_max_percent(const Extremes& num, const Extremes& exp) {
  if (exp.max == 0) throw InvalidArgument("RE_max: the experimental maximum is 0, so its relative error is undefined");
  return detail::absolute_percent(num.max, exp.max);  // eq. 30
}

/// RE_min = 100 |a_min^NUM - a_min^EXP| / |a_min^EXP|, percent. Throws when a_min^EXP is 0.
inline double re_min_percent(const Extremes& num, const Extremes& exp) {
  if (exp.min == 0) throw InvalidArgument("RE_min: the experimental minimum is 0, so its relative error is undefined");
  return detail::absolute_percent(num.min, exp.min);  // eq. 30
}

namespace detail {

inline PeakErrors peak_errors_or_nan(const Extremes& n, const Extremes& e) {
  const double peak_n = std::max(std::abs(n.max), std::abs(n.min));
  const double peak_e = std::max(std::abs(e.max), std::abs(e.min));
  const double max_signed = signed_percent(n.max, e.max);
  const double min_signed = signed_percent(n.min, e.min);
  return {max_signed, std::abs(max_signed), min_signed, std::abs(min_signed), absolute_percent(peak_n, peak_e)};
}

}  // namespace detail

inline PeakErrors peak_errors(std::span<const double> num, std::span<const double> exp) {
  const Extremes n = extremes(num);
  const Extremes e = extremes(exp);
  if (e.max == 0 || e.min == 0)
    throw InvalidArgument("peak errors: the experimental " + std::string(e.max == 0 ? "maximum" : "minimum") +
                          " is 0, so its relative error is undefined");
  return detail::peak_errors_or_nan(n, e);
}

// ---------------------------------------------------------------------------------------------------------------
// Signals on different time grids

namespace detail {

inline void check_grid(std::span<const double> t_from, std::span<const double> u_from) {
  if (t_from.size() != u_from.size())
    throw InvalidArgument("resample: " + std::to_string(t_from.size()) + " times but " + std::to_string(u_from.size()) +
                          " values");
  if (t_from.size() < 2) throw InvalidArgument("resample: the source signal needs at least 2 samples");
  for (std::size_t i = 1; i < t_from.size(); ++i)
    if (!(t_from[i] > t_from[i - 1]))
      throw InvalidArgument("resample: the source times must be strictly increasing; t[" + std::to_string(i) +
                            "] = " + show(t_from[i]) + " s follows " + show(t_from[i - 1]) + " s");
}

/// Linear interpolation of (t_from, u_from) at t_to into out (out.size() == t_to.size()); the grid is checked.
inline void resample_into(std::span<const double> t_from, std::span<const double> u_from, std::span<const double> t_to,
                          std::span<double> out) {
  for (std::size_t k = 0; k < t_to.size(); ++k) {
    const double t = t_to[k];
    if (!(t >= t_from.front() && t <= t_from.back()))
      throw InvalidArgument("resample: time " + show(t) + " s is outside the source span [" + show(t_from.front()) + ", " +
                            show(t_from.back()) + "] s");
    auto j = static_cast<std::size_t>(std::upper_bound(t_from.begin(), t_from.end(), t) - t_from.begin());
    if (j == t_from.size()) j = t_from.size() - 1;  // t == t_from.back()
    const std::size_t i = j - 1;
    const double w = (t - t_from[i]) / (t_from[j] - t_from[i]);
    out[k] = (1 - w) * u_from[i] + w * u_from[j];  // exact at both nodes
  }
}

}  // namespace detail

/// u_from(t_from) linearly interpolated at the times t_to (s; any order). t_from must be strictly increasing and
/// every t_to inside [t_from.front(), t_from.back()]; otherwise throws naming the offending time.
inline std::vector<double> resample(std::span<const double> t_from, std::span<const double> u_from,
                                    std::span<const double> t_to) {
  detail::check_grid(t_from, u_from);
  std::vector<double> out(t_to.size());
  detail::resample_into(t_from, u_from, t_to, out);
  return out;
}

/// Subtracts the first sample from every sample, in place: the paper zeroes the measured displacement at its
/// first entry, since the simulation starts at rest from zero displacement.
inline void zero_at_first_sample(std::span<double> u) {
  if (u.empty()) return;
  const double first = u.front();
  for (double& x : u) x -= first;
}

// ---------------------------------------------------------------------------------------------------------------
// Tables of channels

/// A numeric CSV table. Column 0 is the time (s), named `time` or `time_s`, strictly increasing; displacement
/// channels are named <POINT>_ux/_uy/_uz (m), acceleration channels <POINT>_ax/_ay/_az (m/s^2).
struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> values;  // column-major: values[c][row]
  std::string source;                       // the file it was read from, for messages

  std::size_t rows() const { return values.empty() ? 0 : values.front().size(); }
  bool has_column(std::string_view name) const { return std::find(columns.begin(), columns.end(), name) != columns.end(); }

  /// The index of the column `name`; throws naming the source, the missing column and the columns present.
  std::size_t column(std::string_view name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it != columns.end()) return static_cast<std::size_t>(it - columns.begin());
    std::string present;
    for (const auto& c : columns) present += (present.empty() ? "" : ", ") + c;
    throw InvalidArgument((source.empty() ? std::string("table") : source) + ": no column '" + std::string(name) +
                          "'; the columns are: " + present);
  }
};

namespace detail {

using motion::detail::trim;  // the record readers' tokenising serves the tables too

/// The comma-separated fields of a line, trimmed, into `out` (reused between lines).
inline void split_fields(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  for (std::size_t start = 0;;) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return;
    start = comma + 1;
  }
}

inline bool is_time_column(std::string_view name) { return name == "time" || name == "time_s"; }

/// Shape, time column and time order of a table that may have been built by hand.
inline void check_table(const Table& t, const char* role) {
  const std::string name = t.source.empty() ? std::string(role) + " table" : t.source;
  if (t.columns.empty() || t.values.size() != t.columns.size())
    throw InvalidArgument(name + ": " + std::to_string(t.columns.size()) + " column names but " +
                          std::to_string(t.values.size()) + " columns of values");
  if (!is_time_column(t.columns.front()))
    throw InvalidArgument(name + ": the first column must be the time, named 'time' or 'time_s', not '" +
                          t.columns.front() + "'");
  for (std::size_t c = 0; c < t.columns.size(); ++c)
    if (t.values[c].size() != t.rows())
      throw InvalidArgument(name + ": column '" + t.columns[c] + "' has " + std::to_string(t.values[c].size()) +
                            " rows, the time has " + std::to_string(t.rows()));
  const auto& time = t.values.front();
  for (std::size_t i = 1; i < time.size(); ++i)
    if (!(time[i] > time[i - 1]))
      throw InvalidArgument(name + ": the time must be strictly increasing; row " + std::to_string(i) + " has " +
                            show(time[i]) + " s after " + show(time[i - 1]) + " s");
}

}  // namespace detail

/// Reads a CSV table: lines whose first non-blank character is '#' and blank lines are skipped anywhere; the first
/// other line is the header of comma-separated names, then one row of finite numbers per line. Every error throws
/// InvalidArgument naming the file and the line (and the column for a bad field).
inline Table read_csv_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InvalidArgument(path + ": cannot open the file");
  Table table;
  table.source = path;
  std::vector<std::string_view> fields;
  std::string text;
  int line = 0;
  int previous_line = 0;
  const auto where = [&](int l) { return path + ":" + std::to_string(l) + ": "; };
  while (std::getline(in, text)) {
    ++line;
    const std::string_view content = detail::trim(text);
    if (content.empty() || content.front() == '#') continue;
    detail::split_fields(content, fields);
    if (table.columns.empty()) {
      for (const auto f : fields) {
        if (f.empty()) throw InvalidArgument(where(line) + "the header has an empty column name");
        if (table.has_column(f))
          throw InvalidArgument(where(line) + "the header names column '" + std::string(f) + "' twice");
        table.columns.emplace_back(f);
      }
      if (!detail::is_time_column(table.columns.front()))
        throw InvalidArgument(where(line) + "the first column must be the time, named 'time' or 'time_s', not '" +
                              table.columns.front() + "'");
      table.values.resize(table.columns.size());
      continue;
    }
    if (fields.size() != table.columns.size())
      throw InvalidArgument(where(line) + std::to_string(fields.size()) + " fields, expected " +
                            std::to_string(table.columns.size()) + " (one per header column)");
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto value = motion::detail::to_number(fields[c]);
      if (!value || !std::isfinite(*value))
        throw InvalidArgument(where(line) + "column '" + table.columns[c] + "': '" + std::string(fields[c]) +
                              "' is not a finite number");
      table.values[c].push_back(*value);
    }
    const auto& time = table.values.front();
    if (time.size() > 1 && !(time.back() > time[time.size() - 2]))
      throw InvalidArgument(where(line) + "the first column (" + table.columns.front() + ") must be strictly increasing; " +
                            detail::show(time.back()) + " s follows " + detail::show(time[time.size() - 2]) +
                            " s on line " + std::to_string(previous_line));
    previous_line = line;
  }
  if (table.columns.empty()) throw InvalidArgument(path + ": no header line (the file is empty or holds only comments)");
  if (table.rows() == 0) throw InvalidArgument(path + ": no data rows after the header");
  return table;
}

// ---------------------------------------------------------------------------------------------------------------
// Channel-by-channel comparison

/// The metrics of one channel. A metric whose reference is 0 in the measurement (a dead channel, a displacement
/// that never changes sign) is NaN here rather than an exception, so that one channel does not stop the others.
struct ChannelComparison {
  std::string channel;
  double rmsd_num = 0;            // eq. 26, unit of the channel
  double rmsd_exp = 0;            // eq. 26
  double rmsd_error_percent = 0;  // eq. 28 for this channel alone
  double nrmse_percent = 0;
  PeakErrors peaks;
  double re_max_percent = 0;  // eq. 30
  double re_min_percent = 0;  // eq. 30
  double peak_bias_percent = 0;  // 100 (max|u_num| / max|u_exp| - 1): the signed peak bias of Table 3
  std::size_t samples = 0;    // measured samples in the overlap of the two time spans
};

inline bool is_displacement_channel(std::string_view name) {
  return name.ends_with("_ux") || name.ends_with("_uy") || name.ends_with("_uz");
}

/// Every channel present in both tables (except the time), in the measured table's order: the simulated channel
/// is interpolated linearly onto the measured times inside the simulated time span, and, when
/// `zero_measured_displacements`, each measured displacement channel (_ux, _uy, _uz) has its value at the first of
/// those times subtracted (the paper's zeroing, as the simulation starts from zero displacement). Throws when the
/// tables share no channel or the overlap holds fewer than 2 measured samples.
inline std::vector<ChannelComparison> compare_tables(const Table& simulated, const Table& measured,
                                                     bool zero_measured_displacements = true) {
  detail::check_table(simulated, "simulated");
  detail::check_table(measured, "measured");
  const std::string sim_name = simulated.source.empty() ? "the simulated table" : simulated.source;
  const std::string exp_name = measured.source.empty() ? "the measured table" : measured.source;
  const std::span<const double> t_sim = simulated.values.front();
  const std::span<const double> t_all = measured.values.front();
  if (t_sim.size() < 2) throw InvalidArgument("compare: " + sim_name + " needs at least 2 samples");

  const auto first = static_cast<std::size_t>(std::lower_bound(t_all.begin(), t_all.end(), t_sim.front()) - t_all.begin());
  const auto last = static_cast<std::size_t>(std::upper_bound(t_all.begin(), t_all.end(), t_sim.back()) - t_all.begin());
  if (last < first + 2)
    throw InvalidArgument("compare: the measured times [" + detail::show(t_all.front()) + ", " + detail::show(t_all.back()) +
                          "] s and the simulated times [" + detail::show(t_sim.front()) + ", " + detail::show(t_sim.back()) +
                          "] s overlap in fewer than 2 measured samples");
  const std::span<const double> t_exp = t_all.subspan(first, last - first);

  std::vector<ChannelComparison> result;
  std::vector<double> num(t_exp.size()), exp(t_exp.size());  // scratch, reused for every channel
  for (std::size_t c = 1; c < measured.columns.size(); ++c) {
    const std::string& name = measured.columns[c];
    if (detail::is_time_column(name) || !simulated.has_column(name)) continue;
    detail::resample_into(t_sim, simulated.values[simulated.column(name)], t_exp, num);
    std::copy_n(measured.values[c].begin() + static_cast<std::ptrdiff_t>(first), exp.size(), exp.begin());
    if (zero_measured_displacements && is_displacement_channel(name)) zero_at_first_sample(exp);

    ChannelComparison r;
    r.channel = name;
    r.samples = exp.size();
    r.rmsd_num = rmsd(num);
    r.rmsd_exp = rmsd(exp);
    r.rmsd_error_percent = detail::absolute_percent(r.rmsd_num, r.rmsd_exp);  // eq. 28
    const Extremes n = extremes(num);
    const Extremes e = extremes(exp);
    r.nrmse_percent = e.max > e.min ? nrmse_percent(num, exp) : std::numeric_limits<double>::quiet_NaN();
    r.peaks = detail::peak_errors_or_nan(n, e);
    r.re_max_percent = detail::absolute_percent(n.max, e.max);  // eq. 30
    r.re_min_percent = detail::absolute_percent(n.min, e.min);  // eq. 30
    r.peak_bias_percent = detail::signed_percent(std::max(std::abs(n.max), std::abs(n.min)), std::max(std::abs(e.max), std::abs(e.min)));
    result.push_back(std::move(r));
  }
  if (result.empty()) {
    const auto list = [](const Table& t) {
      std::string s;
      for (std::size_t c = 1; c < t.columns.size(); ++c) s += (s.empty() ? "" : ", ") + t.columns[c];
      return s.empty() ? std::string("none") : s;
    };
    throw InvalidArgument("compare: " + sim_name + " and " + exp_name + " share no channel besides the time; simulated: " +
                          list(simulated) + "; measured: " + list(measured));
  }
  return result;
}

/// The optical cameras whose displacements the paper averages (eq. 27).
inline constexpr std::array<std::string_view, 3> optical_cameras{"OC1", "OC2", "OC4"};

/// Eq. 27-28 over a set of points for one direction: the channels <point><suffix> (e.g. "OC1" + "_uy") have their
/// numerical and experimental RMSD averaged separately, then the relative error of the means is returned, percent.
/// Throws when a channel is missing or the mean experimental RMSD is 0.
inline double mean_rmsd_error_percent(std::span<const ChannelComparison> comparisons, std::string_view suffix,
                                      std::span<const std::string_view> points = optical_cameras) {
  if (points.empty()) throw InvalidArgument("mean RMSD error: no point given");
  double sum_num = 0, sum_exp = 0;
  for (const auto point : points) {
    const std::string channel = std::string(point) + std::string(suffix);
    const auto it = std::find_if(comparisons.begin(), comparisons.end(),
                                 [&](const ChannelComparison& r) { return r.channel == channel; });
    if (it == comparisons.end()) {
      std::string present;
      for (const auto& r : comparisons) present += (present.empty() ? "" : ", ") + r.channel;
      throw InvalidArgument("mean RMSD error: no channel '" + channel + "' among the compared ones (" +
                            (present.empty() ? std::string("none") : present) + ")");
    }
    sum_num += it->rmsd_num;
    sum_exp += it->rmsd_exp;
  }
  const auto n = static_cast<double>(points.size());
  return rmsd_relative_error_percent(sum_num / n, sum_exp / n);  // eq. 27, eq. 28
}

}  // namespace blockdem::analysis
