#pragma once
// Readers for ground-acceleration files: PEER NGA .AT2, ESM/ITACA ASCII and plain one- or two-column text
// (DESIGN §7). Samples are converted to m/s^2; malformed input throws InputError naming the file and the line.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/acceleration_unit.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

enum class RecordFormat { automatic, peer_at2, esm_ascii, plain_text };

constexpr const char* to_string(RecordFormat format) noexcept {
  switch (format) {
    case RecordFormat::automatic: return "automatic";
    case RecordFormat::peer_at2: return "PEER NGA .AT2";
    case RecordFormat::esm_ascii: return "ESM/ITACA ASCII";
    case RecordFormat::plain_text: return "plain text";
  }
  return "?";
}

struct ReadOptions {
  /// Unit of the samples. When set it wins over the file's header (a mislabelled file can be read); when empty the
  /// header must state it.
  std::optional<AccelerationUnit> units;
  /// Time step in s for one-column text. Files that carry their own time step must agree with it (1e-6 relative).
  std::optional<double> dt;
  RecordFormat format = RecordFormat::automatic;
};

namespace detail {

struct TextLine {
  std::string_view text;
  int number;  // 1-based
};

inline std::vector<TextLine> split_lines(std::string_view text) {
  std::vector<TextLine> lines;
  int number = 1;
  while (!text.empty()) {
    const auto end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back({line, number++});
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

inline std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

/// Splits at whitespace, and also at commas and semicolons when `separators` is set.
inline std::vector<std::string_view> tokens(std::string_view line, bool separators) {
  std::vector<std::string_view> out;
  const auto is_break = [separators](char c) {
    return std::isspace(static_cast<unsigned char>(c)) || (separators && (c == ',' || c == ';'));
  };
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_break(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_break(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

/// A number in the whole token (C or Fortran notation: ".5", "-.29E-03", "+1.0", "1.0D-03"), or empty.
inline std::optional<double> to_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double value = 0.0;
  auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ec == std::errc() && result.ptr == token.data() + token.size()) return value;
  if (token.find_first_of("dD") != std::string_view::npos) {
    std::string fortran(token);
    std::replace(fortran.begin(), fortran.end(), 'D', 'E');
    std::replace(fortran.begin(), fortran.end(), 'd', 'e');
    result = std::from_chars(fortran.data(), fortran.data() + fortran.size(), value);
    if (result.ec == std::errc() && result.ptr == fortran.data() + fortran.size()) return value;
  }
  return std::nullopt;
}

/// The resolution a printed number carries: 1e-4 for "0.0033", 1e-7 for "3.3333E-03", 1 for "12".
inline double printed_resolution(std::string_view token) {
  const auto e = token.find_first_of("eEdD");
  const std::string_view mantissa = token.substr(0, e);
  const auto point = mantissa.find('.');
  const int decimals = point == std::string_view::npos ? 0 : static_cast<int>(mantissa.size() - point - 1);
  int exponent = 0;
  if (e != std::string_view::npos)  // "0d99999": a zero with any exponent is a number; beyond +-400, 10^x is 0 or inf
    exponent = static_cast<int>(std::clamp(to_number(token.substr(e + 1)).value_or(0.0), -400.0, 400.0));
  return std::pow(10.0, exponent - decimals);
}

inline std::string where(std::string_view name, int line) { return std::string(name) + ":" + std::to_string(line) + ": "; }

inline std::string show(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

/// A finite sample; throws naming the file and line otherwise.
inline double parse_sample(std::string_view token, std::string_view name, int line) {
  const auto value = to_number(token);
  if (!value) throw InputError(where(name, line) + "expected a number, found '" + std::string(token) + "'");
  if (!std::isfinite(*value))
    throw InputError(where(name, line) + "'" + std::string(token) + "' is not a finite number");
  return *value;
}

/// The number after "KEY=" (spaces allowed around '='), case-insensitive; empty when the key is absent.
/// `found` tells a present key with an unreadable value from an absent key.
inline std::optional<double> number_after_key(std::string_view line, std::string_view key, bool* found = nullptr) {
  const std::string text = upper(line);
  const std::string wanted = upper(key);
  std::size_t at = 0;
  while ((at = text.find(wanted, at)) != std::string::npos) {
    const bool word_start = at == 0 || !std::isalnum(static_cast<unsigned char>(text[at - 1]));
    std::size_t i = at + wanted.size();
    while (i < text.size() && text[i] == ' ') ++i;
    if (word_start && i < text.size() && text[i] == '=') {
      if (found) *found = true;
      ++i;
      while (i < text.size() && text[i] == ' ') ++i;
      std::size_t j = i;
      while (j < text.size() && text[j] != ' ' && text[j] != ',' && text[j] != ';') ++j;
      return to_number(std::string_view(line).substr(i, j - i));
    }
    at += wanted.size();
  }
  if (found) *found = false;
  return std::nullopt;
}

inline void check_dt(double dt, std::string_view name, int line, std::string_view field) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw InputError(where(name, line) + std::string(field) + " = " + show(dt) + " s; the time step must be > 0");
}

/// Applies ReadOptions::dt to a record whose file states its own time step.
inline void reconcile_dt(Record& record, const ReadOptions& options) {
  if (options.dt && std::abs(*options.dt - record.dt) > 1e-6 * record.dt)
    throw InvalidArgument("dt = " + show(*options.dt) + " s was given but " + record.name + " states a time step of " +
                          show(record.dt) + " s");
}

inline AccelerationUnit require_units(std::optional<AccelerationUnit> from_file, const ReadOptions& options,
                                      const std::string& missing) {
  if (options.units) return *options.units;
  if (from_file) return *from_file;
  throw InputError(missing + "; give them (--units g|m/s2|cm/s2)");
}

inline void check_kind(std::string_view text, std::string_view name, int line) {
  const std::string t = upper(text);
  for (const char* kind : {"VELOCITY", "DISPLACEMENT"})
    if (t.find(kind) != std::string::npos && t.find("ACCELERATION") == std::string::npos)
      throw InputError(where(name, line) + "this is a " + upper(kind) +
                       " time series; blockdem reads acceleration records");
}

/// The most samples that lines[first..] can hold (each takes a character and a separator): what is reserved for a
/// header's count at most (a corrupted NPTS= must not allocate gigabytes before the count check refuses it).
inline std::size_t max_samples(const std::vector<TextLine>& lines, std::size_t first) {
  std::size_t bytes = 0;
  for (std::size_t k = first; k < lines.size(); ++k) bytes += lines[k].text.size() + 1;
  return bytes / 2;
}

inline Record finish(Record record, const std::vector<double>& samples, AccelerationUnit unit) {
  const double factor = to_m_s2(unit);
  record.acceleration.resize(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    record.acceleration[i] = factor * samples[i];
    if (!std::isfinite(record.acceleration[i]))  // 1e308 g: finite as written, not in m/s^2
      throw InputError(record.name + ": sample " + std::to_string(i + 1) + " = " + show(samples[i]) + " " +
                       to_string(unit) + " is beyond the range of a double in m/s^2 (|a| <= 1.8e308 m/s^2)");
  }
  record.input_unit = unit;
  return record;
}

// PEER NGA .AT2: 4 header lines (line 3 states the units and often PGA=, line 4 NPTS= and DT=), then the samples,
// usually 5 per line. The older "3000  0.0100  NPTS, DT" form of line 4 is read as well.
inline Record parse_peer_at2(const std::vector<TextLine>& lines, std::string_view name, const ReadOptions& options) {
  if (lines.size() < 4)
    throw InputError(std::string(name) + ": a PEER .AT2 file starts with 4 header lines; found " +
                     std::to_string(lines.size()));
  const auto& units_line = lines[2];
  const auto& size_line = lines[3];
  check_kind(units_line.text, name, units_line.number);

  std::optional<AccelerationUnit> file_unit;
  const std::string units_text = upper(units_line.text);
  if (const auto at = units_text.find("UNITS OF"); at != std::string::npos) {
    const auto words = tokens(std::string_view(units_text).substr(at + 8), true);
    if (!words.empty()) file_unit = parse_acceleration_unit(words.front());
  }
  const AccelerationUnit unit = require_units(
      file_unit, options, where(name, units_line.number) + "the header does not state the units (expected 'UNITS OF G')");

  bool has_npts = false;
  bool has_dt = false;
  auto npts = number_after_key(size_line.text, "NPTS", &has_npts);
  auto dt = number_after_key(size_line.text, "DT", &has_dt);
  if (!has_npts && !has_dt && upper(size_line.text).find("NPTS") != std::string::npos) {
    const auto words = tokens(size_line.text, true);  // older form: "3000   0.0100    NPTS, DT"
    if (words.size() >= 2) {
      npts = to_number(words[0]);
      dt = to_number(words[1]);
      has_npts = has_dt = true;
    }
  }
  const std::string expected = " (expected 'NPTS=   7818, DT=   .0050 SEC')";
  if (!has_npts) throw InputError(where(name, size_line.number) + "the header has no NPTS=" + expected);
  if (!has_dt) throw InputError(where(name, size_line.number) + "the header has no DT=" + expected);
  if (!npts || *npts < 2 || *npts != std::floor(*npts) || *npts > 1e9)
    throw InputError(where(name, size_line.number) + "NPTS must be an integer >= 2" + expected);
  if (!dt) throw InputError(where(name, size_line.number) + "DT is not a number" + expected);
  check_dt(*dt, name, size_line.number, "DT");

  std::vector<double> samples;
  samples.reserve(std::min(static_cast<std::size_t>(*npts), max_samples(lines, 4)));
  for (std::size_t k = 4; k < lines.size(); ++k)
    for (auto token : tokens(lines[k].text, false)) samples.push_back(parse_sample(token, name, lines[k].number));
  const auto expected_count = static_cast<std::size_t>(*npts);
  if (samples.size() != expected_count)
    throw InputError(std::string(name) + ": header says NPTS=" + std::to_string(expected_count) + " but " +
                     std::to_string(samples.size()) + " samples were read");

  Record record;
  record.name = std::string(name);
  record.source = to_string(RecordFormat::peer_at2);
  record.dt = *dt;
  if (auto pga = number_after_key(units_line.text, "PGA")) {
    // The unit follows the number ("PGA=   .48431 G"); without one, the file's unit.
    const std::string_view after = std::string_view(units_text).substr(units_text.find("PGA"));
    const auto words = tokens(after.substr(after.find('=') + 1), true);
    const auto pga_unit = words.size() > 1 ? parse_acceleration_unit(words[1]) : std::nullopt;
    record.header_pga = std::abs(*pga) * to_m_s2(pga_unit.value_or(file_unit.value_or(unit)));
  }
  reconcile_dt(record, options);
  return finish(std::move(record), samples, unit);
}

/// "KEY: value" with an upper-case key of letters, digits and _/^.()- (ESM headers), or empty.
inline std::optional<std::pair<std::string, std::string_view>> esm_header_field(std::string_view line) {
  const auto colon = line.find(':');
  if (colon == std::string_view::npos || colon == 0) return std::nullopt;
  const std::string_view key = line.substr(0, colon);
  if (!std::isalpha(static_cast<unsigned char>(key.front()))) return std::nullopt;
  for (char c : key)
    if (!(std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) ||
          std::strchr("_/^.()-", c)))
      return std::nullopt;
  return std::pair{std::string(key), trim(line.substr(colon + 1))};
}

// ESM/ITACA ASCII: "KEY: value" header lines (NDATA, SAMPLING_INTERVAL_S, UNITS, PGA_CM/S^2, ...), then one sample
// per line.
inline Record parse_esm(const std::vector<TextLine>& lines, std::string_view name, const ReadOptions& options) {
  std::map<std::string, std::pair<std::string_view, int>> header;
  std::size_t k = 0;
  for (; k < lines.size(); ++k) {
    if (trim(lines[k].text).empty()) continue;
    const auto field = esm_header_field(trim(lines[k].text));
    if (!field) break;
    header[field->first] = {field->second, lines[k].number};
  }
  const auto value = [&](const char* key) -> std::optional<std::pair<std::string_view, int>> {
    if (auto it = header.find(key); it != header.end()) return it->second;
    return std::nullopt;
  };
  if (auto type = value("DATA_TYPE")) check_kind(type->first, name, type->second);

  const auto ndata = value("NDATA");
  const auto interval = value("SAMPLING_INTERVAL_S");
  if (!ndata) throw InputError(std::string(name) + ": the header has no NDATA");
  if (!interval) throw InputError(std::string(name) + ": the header has no SAMPLING_INTERVAL_S");
  const auto n = to_number(ndata->first);
  if (!n || *n < 2 || *n != std::floor(*n) || *n > 1e9)
    throw InputError(where(name, ndata->second) + "NDATA must be an integer >= 2, found '" +
                     std::string(ndata->first) + "'");
  const auto dt = to_number(interval->first);
  if (!dt)
    throw InputError(where(name, interval->second) + "SAMPLING_INTERVAL_S is not a number: '" +
                     std::string(interval->first) + "'");
  check_dt(*dt, name, interval->second, "SAMPLING_INTERVAL_S");

  std::optional<AccelerationUnit> file_unit;
  std::string missing = std::string(name) + ": the header has no UNITS";
  if (auto units = value("UNITS")) {
    file_unit = parse_acceleration_unit(units->first);
    if (!file_unit)
      missing = where(name, units->second) + "UNITS '" + std::string(units->first) + "' is not g, m/s^2 or cm/s^2";
  }
  const AccelerationUnit unit = require_units(file_unit, options, missing);

  std::vector<double> samples;
  samples.reserve(std::min(static_cast<std::size_t>(*n), max_samples(lines, k)));
  for (; k < lines.size(); ++k)
    for (auto token : tokens(lines[k].text, false)) samples.push_back(parse_sample(token, name, lines[k].number));
  const auto expected_count = static_cast<std::size_t>(*n);
  if (samples.size() != expected_count)
    throw InputError(std::string(name) + ": header says NDATA=" + std::to_string(expected_count) + " but " +
                     std::to_string(samples.size()) + " samples were read");

  Record record;
  record.name = std::string(name);
  record.source = to_string(RecordFormat::esm_ascii);
  record.dt = *dt;
  if (auto pga = value("PGA_CM/S^2")) {
    if (auto v = to_number(pga->first)) record.header_pga = std::abs(*v) * 0.01;
  }
  reconcile_dt(record, options);
  return finish(std::move(record), samples, unit);
}

inline bool is_comment(std::string_view line) {
  line = trim(line);
  return line.starts_with('#') || line.starts_with('%') || line.starts_with('!') || line.starts_with("//");
}

/// Unit named in a column header such as acceleration_g, acc[m/s2], a_cm_s2, "acceleration (cm/s^2)".
inline std::optional<AccelerationUnit> unit_in_column_name(std::string_view column) {
  std::string s;
  for (char c : column) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (std::string_view cm : {"cm_s2", "cm/s2", "cm/s^2", "cm/s/s", "gal"})
    if (s.find(cm) != std::string::npos) return AccelerationUnit::cm_s2;
  for (std::string_view m : {"m_s2", "m/s2", "m/s^2", "m/s/s"})
    if (s.find(m) != std::string::npos) return AccelerationUnit::m_s2;
  if (s.ends_with("_g") || s.ends_with("[g]") || s.ends_with("(g)") || s == "g") return AccelerationUnit::g;
  return std::nullopt;
}

// Plain text: one column (acceleration; the time step from ReadOptions::dt or a "# dt: 0.01" comment) or two
// columns (time, acceleration), separated by spaces, commas or semicolons. Comment lines start with # % ! or //;
// "# units: g" and "# dt: 0.005" comments are read. An optional first line of column names (as written by the
// ground_motion program: time_s,acceleration_m_s2,...) picks the time and acceleration columns and their unit.
inline Record parse_plain(const std::vector<TextLine>& lines, std::string_view name, const ReadOptions& options) {
  std::optional<AccelerationUnit> file_unit;
  std::optional<double> comment_dt;
  int comment_dt_line = 0;
  std::optional<std::size_t> time_column;
  std::size_t acceleration_column = 0;
  std::size_t columns = 0;  // expected per data line; 0 until the first data line
  bool header_seen = false;
  std::vector<double> times;
  std::vector<double> samples;
  std::vector<int> sample_lines;
  double time_resolution = std::numeric_limits<double>::infinity();  // finest digit printed in the time column
  bool synthetic = false;  // a "# SYNTHETIC" comment, as written by write_provenance

  for (const auto& line : lines) {
    const std::string_view text = trim(line.text);
    if (text.empty()) continue;
    if (is_comment(text)) {
      if (text.starts_with("# SYNTHETIC")) synthetic = true;
      const std::string lower = [&] {
        std::string s(text);
        for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return s;
      }();
      const auto key_value = [&](const char* key) -> std::optional<std::string_view> {
        const auto at = lower.find(key);
        if (at == std::string::npos) return std::nullopt;
        std::string_view rest = std::string_view(text).substr(at + std::strlen(key));
        rest = trim(rest);
        if (rest.empty() || (rest.front() != ':' && rest.front() != '=')) return std::nullopt;
        return trim(rest.substr(1));
      };
      if (auto u = key_value("units")) {
        const auto words = tokens(*u, true);
        if (!words.empty()) file_unit = parse_acceleration_unit(words.front());
      }
      if (auto d = key_value("dt")) {
        const auto words = tokens(*d, true);
        if (!words.empty()) {
          comment_dt = to_number(words.front());
          comment_dt_line = line.number;
        }
      }
      continue;
    }
    const auto words = tokens(text, true);
    if (words.empty())
      throw InputError(where(name, line.number) + "a line of separators (',' ';') only: expected 1 or 2 numbers or "
                                                  "column names");
    if (columns == 0 && !header_seen &&
        std::none_of(words.begin(), words.end(), [](std::string_view w) { return to_number(w).has_value(); })) {
      // A line of column names.
      header_seen = true;
      std::optional<std::size_t> acc;
      for (std::size_t c = 0; c < words.size(); ++c) {
        std::string w;
        for (char ch : words[c]) w += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (!time_column && (w == "t" || w.starts_with("time") || w.starts_with("t_") || w.starts_with("t[") ||
                             w.starts_with("t(")))
          time_column = c;
        else if (!acc && (w == "a" || w.starts_with("acc") || w.starts_with("a_") || w.starts_with("a[") ||
                          w.starts_with("a(")))
          acc = c;
      }
      if (!acc) {
        if (words.size() > 2)
          throw InputError(where(name, line.number) + "cannot tell the acceleration column among '" +
                           std::string(text) + "' (name it acceleration_<unit>, e.g. acceleration_m_s2)");
        acc = words.size() - 1;
        if (words.size() == 2) time_column = 0;
      }
      acceleration_column = *acc;
      if (auto u = unit_in_column_name(words[acceleration_column])) file_unit = u;
      columns = words.size();
      continue;
    }
    if (columns == 0) {
      if (words.size() > 2)
        throw InputError(where(name, line.number) + "expected 1 column (acceleration) or 2 columns (time, "
                                                     "acceleration), found " + std::to_string(words.size()));
      columns = words.size();
      if (columns == 2) {
        time_column = 0;
        acceleration_column = 1;
      }
    }
    if (words.size() != columns)
      throw InputError(where(name, line.number) + "expected " + std::to_string(columns) + " column" +
                       (columns == 1 ? "" : "s") + ", found " + std::to_string(words.size()));
    for (auto w : words) parse_sample(w, name, line.number);  // text or NaN anywhere in the row is an error
    samples.push_back(*to_number(words[acceleration_column]));
    sample_lines.push_back(line.number);
    if (time_column) {
      times.push_back(*to_number(words[*time_column]));
      time_resolution = std::min(time_resolution, printed_resolution(words[*time_column]));
    }
  }
  if (samples.size() < 2)
    throw InputError(std::string(name) + ": " + std::to_string(samples.size()) +
                     (samples.size() == 1 ? " sample was" : " samples were") + " read; a record needs at least 2");

  Record record;
  record.name = std::string(name);
  record.source = to_string(RecordFormat::plain_text);
  if (synthetic) {
    record.synthetic = true;
    record.source += " (SYNTHETIC: generated by blockdem, not a recording)";
  }
  if (time_column) {
    const std::size_t n = times.size();
    std::vector<double> steps(n - 1);
    for (std::size_t i = 1; i < n; ++i) steps[i - 1] = times[i] - times[i - 1];
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double typical = sorted[sorted.size() / 2];  // the median step: a few bad steps cannot move it
    // A step may differ from it by the rounding of the printed times, nothing more: up to one unit of the finest
    // digit the column prints (a time "0" or "0.01" among "0.015"s is exact, not rounded to whole units).
    const double tolerance = 1e-3 * std::abs(typical) + 2.0 * time_resolution;
    for (std::size_t i = 1; i < n; ++i) {
      const double step = steps[i - 1];
      if (!(step > 0.0))
        throw InputError(where(name, sample_lines[i]) + "time " + show(times[i]) + " does not increase (previous " +
                         show(times[i - 1]) + ")");
      if (std::abs(step - typical) > tolerance)
        throw InputError(where(name, sample_lines[i]) + "time step " + show(step) + " differs from " +
                         show(typical) + " (non-uniform time column)");
    }
    const double dt = (times.back() - times.front()) / static_cast<double>(n - 1);
    record.dt = dt;
    record.start_time = times.front();
    reconcile_dt(record, options);
  } else if (options.dt) {
    if (!(*options.dt > 0.0) || !std::isfinite(*options.dt))
      throw InvalidArgument("dt = " + show(*options.dt) + " s must be > 0");
    record.dt = *options.dt;
  } else if (comment_dt) {
    check_dt(*comment_dt, name, comment_dt_line, "dt");
    record.dt = *comment_dt;
  } else {
    throw InputError(std::string(name) + ": one column of samples and no time step; give it (--dt)");
  }
  const AccelerationUnit unit =
      require_units(file_unit, options, std::string(name) + ": the file does not state its units");
  return finish(std::move(record), samples, unit);
}

inline bool has_at2_extension(std::string_view name) {
  const std::string n = upper(name);
  return n.ends_with(".AT2");
}

}  // namespace detail

/// The format of a file from its name and first lines: .AT2 or a PEER header; ESM "KEY: value" header with
/// NDATA or SAMPLING_INTERVAL_S; otherwise plain text.
inline RecordFormat detect_format(std::string_view text, std::string_view name) {
  if (detail::has_at2_extension(name)) return RecordFormat::peer_at2;
  const auto lines = detail::split_lines(text.substr(0, 20000));
  if (!lines.empty()) {
    const std::string first = detail::upper(lines.front().text);
    if (first.find("PEER") != std::string::npos || first.find("PACIFIC ENGINEERING") != std::string::npos)
      return RecordFormat::peer_at2;
  }
  if (lines.size() >= 4 && detail::number_after_key(lines[3].text, "NPTS") &&
      detail::upper(lines[2].text).find("UNITS") != std::string::npos)
    return RecordFormat::peer_at2;
  for (const auto& line : lines) {
    const auto field = detail::esm_header_field(detail::trim(line.text));
    if (field && (field->first == "NDATA" || field->first == "SAMPLING_INTERVAL_S")) return RecordFormat::esm_ascii;
  }
  return RecordFormat::plain_text;
}

/// Parses the contents of a record file; `name` labels the record and the error messages.
inline Record parse_record(std::string_view text, std::string_view name, const ReadOptions& options = {}) {
  if (options.dt && !(*options.dt > 0.0 && std::isfinite(*options.dt)))
    throw InvalidArgument("dt = " + detail::show(*options.dt) + " s must be > 0");
  const auto lines = detail::split_lines(text);
  const RecordFormat format = options.format == RecordFormat::automatic ? detect_format(text, name) : options.format;
  switch (format) {
    case RecordFormat::peer_at2: return detail::parse_peer_at2(lines, name, options);
    case RecordFormat::esm_ascii: return detail::parse_esm(lines, name, options);
    default: return detail::parse_plain(lines, name, options);
  }
}

/// Reads a record file (format detected unless options.format says otherwise).
inline Record read_record(const std::filesystem::path& path, const ReadOptions& options = {}) {
  const std::string name = path.string();
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InputError(name + ": no such file");
  if (std::filesystem::is_directory(path, error)) throw InputError(name + ": is a directory, not a record file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open the file for reading");
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) throw InputError(name + ": reading the file failed");
  return parse_record(contents.str(), name, options);
}

}  // namespace blockdem::motion
