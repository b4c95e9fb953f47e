#pragma once
// The "excitation" and "study" of a model file (docs/model-file.md) read into StudyOptions, and the intensity target
// of the excitation (a PGA or a spectral acceleration at 100 %) resolved against the record as cut.

#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>

#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/io/json_fields.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/record.hpp"
#include "blockdem/motion/spectrum.hpp"

namespace blockdem::analysis {

/// What the 100 % level of the study is: the record as given times 100 / record_level (the vault: 75, its input
/// being AQA75), or the record scaled to a PGA or to a 5 %-damped Sa(T), in g.
struct RecordScale {
  enum class Kind { record_level, pga, sa } kind = Kind::record_level;
  double target_g = 0;  // pga, sa
  double period = 0;    // s, sa
};

/// The record level (study.record_level) at which the cut record's 100 % has the target intensity. `cut` is the
/// record as the study cuts and corrects it (at 100 % of itself). Throws InvalidArgument if it has no such intensity.
inline double record_level_for(const RecordScale& scale, const motion::Record& cut, const std::string& context) {
  if (scale.kind == RecordScale::Kind::record_level) return 0;
  double intensity = 0;  // g, of the cut as given
  std::string what = "PGA";
  if (scale.kind == RecordScale::Kind::pga) {
    intensity = motion::peak_values(cut).pga / standard_gravity;
  } else {
    const double omega = 2 * std::numbers::pi / scale.period;
    intensity = omega * omega * motion::spectral_displacement(cut, scale.period, 0.05) / standard_gravity;
    what = "Sa(" + num(scale.period) + " s)";
  }
  if (!(intensity > 0)) throw InvalidArgument(context + ": the record '" + cut.name + "' has no " + what + " to scale to " + num(scale.target_g) + " g");
  const double level = 100 * intensity / scale.target_g;  // record_level: 100 % of the study = target
  if (!(level > 0.1 && level <= 1000))
    throw InvalidArgument(context + ": scaling the record '" + cut.name + "' (" + what + " " + num(intensity) + " g) to " +
                          num(scale.target_g) + " g takes a factor of " + num(100 / level) + ", outside [0.1, 1000]");
  return level;
}

namespace detail {

/// A whole number within `range`.
inline double integer(const io::JsonFields& f, std::string_view key, double fallback, const io::Range& range) {
  const double x = f.number(key, fallback, range);
  if (x != std::floor(x)) io::field_error(*f.find(key), f.path(key), "must be a whole number, got " + num(x));
  return x;
}

inline void read_study(const io::JsonFields& top, StudyOptions& o, RecordScale& scale, std::optional<PushoverOptions>& pushover,
                       const std::string& base_dir) {
  o.program = "blockdem run";
  o.context = "study";
  o.record_level = 100;  // a user's record is the record as given
  o.levels = {100};
  o.axis = 'x';  // with or without an excitation: the model file's default axis
  if (const auto* e = top.find("excitation")) {
    const io::JsonFields f(*e, "excitation", {"record", "units", "dt", "axis", "baseline", "window_s", "truncation",
                                              "record_level_percent", "pga_g", "sa_g", "sa_period_s"});
    if (const auto* r = f.find("record")) {
      const std::string& path = io::string_value(*r, "excitation.record");
      o.record_path = path.empty() || base_dir.empty() || std::filesystem::path(path).is_absolute()
                          ? path : (std::filesystem::path(base_dir) / path).string();
    }
    if (const auto* u = f.find("units"))
      o.read.units = io::JsonFields::choice_value<motion::AccelerationUnit>(
          *u, "excitation.units", {{"g", motion::AccelerationUnit::g}, {"m/s2", motion::AccelerationUnit::m_s2},
                                   {"cm/s2", motion::AccelerationUnit::cm_s2}});
    if (f.has("dt")) o.read.dt = f.required_number("dt", {0, 1, true, false, "s"});
    o.axis = f.choice<char>("axis", 'x', {{"x", 'x'}, {"y", 'y'}, {"z", 'z'}});
    o.baseline = f.string("baseline", o.baseline);
    try {
      (void)motion::parse_baseline(o.baseline);
    } catch (const InvalidArgument& error) {
      io::field_error(*f.find("baseline"), "excitation.baseline", error.what());
    }
    o.truncation = f.choice<Truncation>("truncation", Truncation::window, {{"window", Truncation::window}, {"wavelet", Truncation::wavelet}});
    if (const auto* w = f.find("window_s")) {
      if (o.truncation == Truncation::wavelet) io::field_error(*w, "excitation.window_s", "a window goes with \"truncation\": \"window\", not wavelet");
      const auto& pair = io::array_value(*w, "excitation.window_s", 2, 2);
      o.window_start = io::number_value(pair[0], "excitation.window_s[0]", {0, 1e5, false, false, "s"});
      o.window_end = io::number_value(pair[1], "excitation.window_s[1]", {o.window_start, 1e5, true, false, "s"});
      o.window_default = false;
    }
    int targets = 0;
    for (const char* key : {"record_level_percent", "pga_g", "sa_g"}) targets += f.has(key);
    if (targets > 1) io::field_error(*e, "excitation", "give one of record_level_percent, pga_g and sa_g");
    o.record_level = f.number("record_level_percent", o.record_level, {0, 1000, true, false, "%"});
    if (f.has("pga_g")) scale = {RecordScale::Kind::pga, f.required_number("pga_g", {0, 10, true, false, "g"}), 0};
    if (f.has("sa_g")) scale = {RecordScale::Kind::sa, f.required_number("sa_g", {0, 20, true, false, "g"}),
                                f.required_number("sa_period_s", {0.01, 10, false, false, "s"})};
    else if (const auto* p = f.find("sa_period_s")) io::field_error(*p, "excitation.sa_period_s", "goes with sa_g only");
  }
  if (const auto* st = top.find("study")) {
    const io::JsonFields f(*st, "study", {"analysis", "levels_percent", "rest_s", "damping", "timestep", "settle", "outputs",
                                          "collapse_displacement_m", "runaway_displacement_m", "max_speed_m_s", "free_vibration",
                                          "pushover"});
    const bool push = f.choice<bool>("analysis", false, {{"levels", false}, {"pushover", true}});
    if (const auto* p = f.find("pushover")) {
      if (!push) io::field_error(*p, "study.pushover", "goes with \"analysis\": \"pushover\"");
    }
    if (push) {
      PushoverOptions& q = pushover.emplace();
      if (const auto* p = f.find("pushover")) {
        const io::JsonFields g(*p, "study.pushover", {"axis", "upper", "resolution", "collapse_displacement_m", "tolerance", "max_steps"});
        const int axis = g.choice<int>("axis", 1, {{"x", 1}, {"-x", -1}, {"y", 2}, {"-y", -2}});
        q.axis = std::abs(axis) == 1 ? 'x' : 'y';
        q.sign = axis > 0 ? 1 : -1;
        q.upper = g.number("upper", q.upper, {0, 10, true, false, ""});
        q.resolution = g.number("resolution", q.resolution, {1e-5, q.upper, false, true, ""});
        q.collapse_displacement = g.number("collapse_displacement_m", q.collapse_displacement, {0, 100, false, false, "m"});
        q.tolerance = g.number("tolerance", q.tolerance, {0, 0.1, true, false, ""});
        q.max_steps = static_cast<long long>(integer(g, "max_steps", static_cast<double>(q.max_steps), {100, 1e12, false, false, "steps"}));
      }
    }
    if (const auto* levels = f.find("levels_percent")) {
      o.levels.clear();
      for (std::size_t i = 0; const auto& v : io::array_value(*levels, "study.levels_percent", 1))
        o.levels.push_back(io::number_value(v, "study.levels_percent[" + std::to_string(i++) + "]", {0, 1000, true, false, "%"}));
    }
    o.rest = f.number("rest_s", o.rest, {0, 600, false, false, "s"});
    if (const auto* d = f.find("damping")) {
      const io::JsonFields g(*d, "study.damping", {"scheme", "zeta", "frequency_hz", "band_hz", "branches", "frame"});
      o.damping = g.choice<DampingScheme>("scheme", o.damping, {{"none", DampingScheme::none}, {"mass", DampingScheme::mass},
                                                                {"stiffness", DampingScheme::stiffness}, {"rayleigh", DampingScheme::rayleigh},
                                                                {"maxwell", DampingScheme::maxwell}});
      o.zeta = g.number("zeta", 0, {0, 0.5, false, true, ""});
      o.frequency_hz = g.number("frequency_hz", o.frequency_hz, {0, 1000, true, false, "Hz"});
      if (const auto* band = g.find("band_hz")) {
        const auto& pair = io::array_value(*band, "study.damping.band_hz", 2, 2);
        o.lower_hz = io::number_value(pair[0], "study.damping.band_hz[0]", {0, 1000, true, false, "Hz"});
        o.upper_hz = io::number_value(pair[1], "study.damping.band_hz[1]", {o.lower_hz, 1000, true, false, "Hz"});
      }
      o.branches = static_cast<int>(integer(g, "branches", o.branches, {1, max_study_branches, false, false, ""}));
      for (const auto& [key, option] : {std::pair{"zeta", "--zeta"}, {"band_hz", "--band"}, {"branches", "--branches"}})
        if (g.find(key)) o.given.insert(option);
      o.damping_frame = g.choice<damping::Frame>("frame", o.damping_frame,
                                                 {{"table", damping::Frame::table}, {"absolute", damping::Frame::absolute}});
    }
    if (const auto* t = f.find("timestep")) {
      const io::JsonFields g(*t, "study.timestep", {"target_dt_s", "mass_increase_percent", "max_mass_increase_percent"});
      o.target_dt = g.number("target_dt_s", o.target_dt, {0, 0.01, false, true, "s"});
      o.max_mass_increase_percent = g.number("max_mass_increase_percent", o.max_mass_increase_percent, {0, 1000, false, false, "%"});
      for (const auto& [key, option] : {std::pair{"mass_increase_percent", "--mass-increase"},
                                        {"max_mass_increase_percent", "--max-mass-increase"}})
        if (g.find(key)) o.given.insert(option);
      o.default_mass_increase_percent = g.number("mass_increase_percent", o.default_mass_increase_percent,
                                                 {0, o.max_mass_increase_percent, false, false, "%"});
    }
    if (const auto* t = f.find("settle")) {
      const io::JsonFields g(*t, "study.settle", {"method", "tolerance", "max_steps"});
      o.settling = g.choice<Settling>("method", o.settling, {{"auto", Settling::automatic}, {"inertial", Settling::inertial},
                                                             {"local", Settling::local}});
      o.settle_tolerance = g.number("tolerance", o.settle_tolerance, {0, 1, true, true, ""});
      o.settle_max_steps = static_cast<long long>(integer(g, "max_steps", static_cast<double>(o.settle_max_steps), {10, 1e12, false, false, "steps"}));
    }
    if (const auto* t = f.find("outputs")) {
      const io::JsonFields g(*t, "study.outputs", {"history_dt_s", "snapshots_every_s"});
      o.history_dt = g.number("history_dt_s", o.history_dt, {1e-5, 1, false, false, "s"});
      o.snapshots_every = g.number("snapshots_every_s", o.snapshots_every, {0, 100, false, false, "s"});
    }
    o.runaway_displacement = f.number("runaway_displacement_m", o.runaway_displacement, {0.001, 1e6, false, false, "m"});
    o.collapse_displacement = f.number("collapse_displacement_m", o.collapse_displacement, {0.001, o.runaway_displacement, false, false, "m"});
    o.max_speed = f.number("max_speed_m_s", o.max_speed, {0.1, 1e6, false, false, "m/s"});
    // What the file gives, under the names messages use (StudyOptions::given).
    o.given_known = true;
    for (const auto& [key, option] : {std::pair{"runaway_displacement_m", "--runaway-displacement"},
                                      {"collapse_displacement_m", "--collapse-displacement"}, {"max_speed_m_s", "--max-speed"}})
      if (f.find(key)) o.given.insert(option);
    o.free_vibration = f.boolean("free_vibration", o.free_vibration);
  }
}

}  // namespace detail
}  // namespace blockdem::analysis
