#pragma once
// The sweep description file: a JSON object read into a SweepSpec (analysis/sweep.hpp), with errors that name the
// file, line, column and key.
//
// The format (plain JSON: no comments, no trailing commas; every key optional but "schemes"):
//
//   {
//     "model": "wall.json",                            blockdem sweep: the model file (docs/model-file.md) every case
//                                                      studies, relative to the sweep file's folder; its study gives
//                                                      the base options; cross_vault sweep: leave it out (the vault)
//     "kinematics": ["rigid", "mixed", "deformable"],  the vault's: rigid | mixed | deformable; default ["rigid"]; not
//                                                      with a model file (its blocks say whether they deform)
//     "records": ["", "records/RSN1_EW.AT2"],          record files (PEER .AT2, ESM ASCII, text); "" is the model
//                                                      file's record, or for the vault the built-in synthetic AQA75
//                                                      stand-in; a relative path is taken relative to the folder of
//                                                      the sweep file; default [""]
//     "levels": [25, 50, 75],                          % of each record; default [25, 50, 75]
//     "pga_g": [0.1, 0.2, 0.4],                        or: targets of peak ground acceleration, g
//     "sa_g": [0.1, 0.2], "sa_period_s": 0.3,          or: targets of the 5 %-damped Sa(T), g, and T in s
//                                                      (at most one of levels, pga_g, sa_g; sa_period_s goes with
//                                                      sa_g only)
//     "incremental": true,                             true: the levels run one after another on one vault (the
//                                                      paper's incremental analysis); false: a case per level, each
//                                                      from the undamaged vault (an IDA); default true
//     "measured": "measured.csv",                      optional CSV of measured channels to compare with, relative
//                                                      to the sweep file's folder
//     "measured_level": 75,                            the level (%) compared with; default 0: the last one
//     "schemes": [                                     at least one; each scheme times its lists is a set of cases
//       {"scheme": "mass", "zeta": [0.02, 0.03], "frequency_hz": [3, 7.5, 15]},
//       {"scheme": "maxwell", "zeta": [0.03], "band_hz": [[1, 40]], "branches": [3]},
//       {"scheme": "rayleigh", "zeta": 0.03, "band_hz": [2, 20]},
//       {"scheme": "none"}
//     ]
//   }
//
// A scheme is none | mass | stiffness | rayleigh | maxwell. Its lists: "zeta" (damping ratio, every scheme but
// none), "frequency_hz" (mass: the centre of the proportional band; stiffness: where zeta is met), "band_hz"
// (maxwell: the band of the fit; rayleigh: its two frequencies), "branches" (maxwell: an integer). A list left out
// is the default of the vault study. A single value where a list is expected is a list of one ("zeta": 0.03,
// "records": "x.AT2", "schemes": {...}), and one band may be given as a single pair [1, 40]. The values' ranges are
// checked by expand_sweep, which also orders the cases and names them (e.g. rigid_aqa75_maxwell_z0.03_b1-40_n3).

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/analysis/sweep.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/io/json_reader.hpp"

namespace blockdem::analysis {

namespace detail {

[[noreturn]] inline void sweep_error(const io::JsonValue& at, const std::string& key, const std::string& what) {
  throw InvalidArgument(at.where() + ": " + key + ": " + what);
}

inline std::string sweep_join(const std::vector<std::string_view>& words) {
  std::string out;
  for (const auto word : words) out += (out.empty() ? "" : ", ") + std::string(word);
  return out;
}

inline void check_sweep_keys(const io::JsonValue& object, const std::string& where_in,
                             const std::vector<std::string_view>& allowed) {
  for (const auto& [key, value] : object.as_object())
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      throw InvalidArgument(value.where() + ": unknown key \"" + key + "\"" + where_in + " (allowed keys: " +
                            sweep_join(allowed) + ")");
}

/// Elements to read, each with its key for messages.
using SweepItems = std::vector<std::pair<const io::JsonValue*, std::string>>;

/// A value or a list of values: the elements, keyed `key` for a single value and `key[i]` in a list.
inline SweepItems sweep_items(const io::JsonValue& value, const std::string& key) {
  SweepItems items;
  if (!value.is_array()) return {{&value, key}};
  for (std::size_t i = 0; i < value.as_array().size(); ++i)
    items.emplace_back(&value.as_array()[i], key + "[" + std::to_string(i) + "]");
  return items;
}

inline double sweep_number(const io::JsonValue& value, const std::string& key) {
  if (!value.is_number())
    sweep_error(value, key, std::string("expected a number, got ") + value.kind_name(value.kind()));
  return value.as_number();
}

inline std::vector<double> sweep_numbers(const io::JsonValue& value, const std::string& key, bool allow_empty) {
  if (!value.is_number() && !value.is_array())
    sweep_error(value, key, std::string("expected a number or a list of numbers, got ") +
                                value.kind_name(value.kind()));
  if (!allow_empty && value.is_array() && value.as_array().empty()) sweep_error(value, key, "give at least one number");
  std::vector<double> numbers;
  for (const auto& [item, item_key] : sweep_items(value, key)) numbers.push_back(sweep_number(*item, item_key));
  return numbers;
}

/// The enumerator of `options` whose name() is the string `value`.
template <class Enum, std::size_t n>
Enum sweep_choice(const io::JsonValue& value, const std::string& key, const std::array<Enum, n>& options,
                  std::string_view what) {
  std::vector<std::string_view> names;
  for (const Enum option : options) names.push_back(name(option));
  if (!value.is_string())
    sweep_error(value, key, "expected the name of the " + std::string(what) + " (" + sweep_join(names) + "), got " +
                                value.kind_name(value.kind()));
  for (const Enum option : options)
    if (value.as_string() == name(option)) return option;
  sweep_error(value, key, "unknown " + std::string(what) + " \"" + value.as_string() + "\" (allowed: " +
                              sweep_join(names) + ")");
}

/// A path as written in the file: relative ones are taken relative to the sweep file's folder.
inline std::string sweep_path(const io::JsonValue& value, const std::string& key, const std::string& base_dir) {
  if (!value.is_string())
    sweep_error(value, key, std::string("expected a file path (a string), got ") + value.kind_name(value.kind()));
  const std::string& path = value.as_string();
  if (path.empty() || base_dir.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(base_dir) / path).string();
}

inline SweepScheme sweep_scheme(const io::JsonValue& value, const std::string& key) {
  if (!value.is_object())
    sweep_error(value, key, std::string("expected a scheme such as {\"scheme\": \"maxwell\", \"zeta\": 0.03}, got ") +
                                value.kind_name(value.kind()));
  check_sweep_keys(value, " in " + key, {"scheme", "zeta", "frequency_hz", "band_hz", "branches"});
  constexpr std::array schemes{DampingScheme::none, DampingScheme::mass, DampingScheme::stiffness,
                               DampingScheme::rayleigh, DampingScheme::maxwell};
  const io::JsonValue* scheme = value.find("scheme");
  if (!scheme) sweep_error(value, key, "\"scheme\" is missing (none, mass, stiffness, rayleigh, maxwell)");
  SweepScheme s;
  s.scheme = sweep_choice(*scheme, key + ".scheme", schemes, "damping scheme");
  // Which lists a scheme uses (as expand_sweep), checked here too so that the message can point at the line.
  const auto uses = [&](const char* list, bool used, const char* who) -> const io::JsonValue* {
    const io::JsonValue* v = value.find(list);
    if (v && !used)
      sweep_error(*v, key + "." + list, std::string("the scheme ") + name(s.scheme) + " takes no " + list + " (" +
                                            list + ": " + who + " only)");
    return v;
  };
  const DampingScheme d = s.scheme;
  if (const auto* v = uses("zeta", d != DampingScheme::none, "mass, stiffness, rayleigh, maxwell"))
    s.zetas = sweep_numbers(*v, key + ".zeta", true);
  const bool mass_or_stiffness = d == DampingScheme::mass || d == DampingScheme::stiffness;
  if (const auto* v = uses("frequency_hz", mass_or_stiffness, "mass, stiffness"))
    s.frequencies_hz = sweep_numbers(*v, key + ".frequency_hz", true);
  const bool maxwell_or_rayleigh = d == DampingScheme::maxwell || d == DampingScheme::rayleigh;
  if (const auto* v = uses("band_hz", maxwell_or_rayleigh, "maxwell, rayleigh")) {
    const auto is_pair = [](const io::JsonValue& b) {
      return b.is_array() && b.as_array().size() == 2 && b.as_array()[0].is_number() && b.as_array()[1].is_number();
    };
    const std::string band_key = key + ".band_hz";
    if (!v->is_array())
      sweep_error(*v, band_key, std::string("expected a band [lower, upper] in Hz or a list of bands, got ") +
                                    v->kind_name(v->kind()));
    const auto& list = v->as_array();
    const auto is_number = [](const io::JsonValue& x) { return x.is_number(); };
    const bool flat = !list.empty() && std::all_of(list.begin(), list.end(), is_number);
    const SweepItems items = flat ? SweepItems{{v, band_key}} : sweep_items(*v, band_key);  // one band or a list
    for (const auto& [band, band_item_key] : items) {
      if (!is_pair(*band))
        sweep_error(*band, band_item_key, "a band is two numbers [lower, upper] in Hz, got " +
                                              (band->is_array() ? "a list of " + std::to_string(band->as_array().size())
                                                                : std::string(band->kind_name(band->kind()))));
      s.bands_hz.push_back({band->as_array()[0].as_number(), band->as_array()[1].as_number()});
    }
  }
  if (const auto* v = uses("branches", d == DampingScheme::maxwell, "maxwell"))
    for (const auto& [item, item_key] : sweep_items(*v, key + ".branches")) {
      if (!item->is_number())
        sweep_error(*item, item_key, std::string("expected an integer number of Maxwell branches (such as 3), got ") +
                                         item->kind_name(item->kind()));
      const double n = item->as_number();
      if (n != std::floor(n) || std::abs(n) > 1e6)
        sweep_error(*item, item_key, "expected an integer number of Maxwell branches (such as 3), got " + id_number(n));
      s.branches.push_back(static_cast<int>(n));
    }
  return s;
}

/// The sweep of a parsed file.
inline SweepSpec sweep_from_json(const io::JsonValue& root, const std::string& base_dir) {
  if (!root.is_object())
    throw InvalidArgument(root.where() + ": a sweep file holds one JSON object {\"schemes\": [...], ...}, got " +
                          root.kind_name(root.kind()));
  check_sweep_keys(root, "", {"model", "kinematics", "records", "levels", "pga_g", "sa_g", "sa_period_s", "incremental",
                              "measured", "measured_level", "schemes"});
  SweepSpec spec;
  if (const auto* v = root.find("model")) {
    spec.model = sweep_path(*v, "model", base_dir);
    if (spec.model.empty()) sweep_error(*v, "model", "give the model file's path, or leave \"model\" out for the vault");
    if (const auto* k = root.find("kinematics"))
      sweep_error(*k, "kinematics", "a model file's blocks say whether they are rigid or deformable; leave kinematics out");
  }
  if (const auto* v = root.find("kinematics")) {
    constexpr std::array all{VaultKinematics::rigid, VaultKinematics::mixed, VaultKinematics::deformable};
    if (v->is_array() && v->as_array().empty())
      sweep_error(*v, "kinematics", "give at least one (rigid, mixed, deformable)");
    spec.kinematics.clear();
    for (const auto& [item, key] : sweep_items(*v, "kinematics"))
      spec.kinematics.push_back(sweep_choice(*item, key, all, "kinematics"));
  }
  if (const auto* v = root.find("records")) {
    if (v->is_array() && v->as_array().empty())
      sweep_error(*v, "records", "give at least one record (\"\" is the built-in AQA75 stand-in)");
    spec.records.clear();
    for (const auto& [item, key] : sweep_items(*v, "records"))
      spec.records.push_back(sweep_path(*item, key, base_dir));
  }
  // The levels: at most one of the three ways of giving them.
  const io::JsonValue* given = nullptr;
  std::string given_key;
  for (const auto& [key, value] : root.as_object()) {
    const bool is_level = key == "levels" || key == "pga_g" || key == "sa_g";
    if (!is_level) continue;
    if (given)
      sweep_error(value, key, "give only one of levels, pga_g, sa_g (" + given_key + " is given at " +
                                  std::to_string(given->line()) + ":" + std::to_string(given->column()) + ")");
    given = &value;
    given_key = key;
    spec.levels = sweep_numbers(value, key, false);
    spec.measure = key == "levels" ? IntensityMeasure::level
                   : key == "pga_g" ? IntensityMeasure::pga
                                    : IntensityMeasure::sa;
  }
  const io::JsonValue* period = root.find("sa_period_s");
  if (period && spec.measure != IntensityMeasure::sa)
    sweep_error(*period, "sa_period_s", "only allowed with sa_g (the period of the spectral acceleration, s)");
  if (spec.measure == IntensityMeasure::sa) {
    if (!period)
      sweep_error(*given, "sa_g", "needs \"sa_period_s\", the period T in s of the spectral acceleration Sa(T)");
    spec.sa_period = sweep_number(*period, "sa_period_s");
  }
  if (const auto* v = root.find("incremental")) {
    if (!v->is_bool())
      sweep_error(*v, "incremental", std::string("expected true or false, got ") + v->kind_name(v->kind()));
    spec.incremental = v->as_bool();
  }
  if (const auto* v = root.find("measured")) spec.measured = sweep_path(*v, "measured", base_dir);
  if (const auto* v = root.find("measured_level")) spec.measured_level = sweep_number(*v, "measured_level");
  const io::JsonValue* schemes = root.find("schemes");
  if (!schemes)
    throw InvalidArgument(root.where() + ": schemes: missing; give a list of damping schemes such as "
                                         "[{\"scheme\": \"maxwell\", \"zeta\": 0.03}]");
  if (schemes->is_array() && schemes->as_array().empty())
    sweep_error(*schemes, "schemes", "give at least one damping scheme (none, mass, stiffness, rayleigh, maxwell)");
  for (const auto& [item, key] : sweep_items(*schemes, "schemes")) spec.schemes.push_back(sweep_scheme(*item, key));
  return spec;
}

}  // namespace detail

/// The sweep described by the JSON `text`; `source` names it in messages (the file's path), and relative record and
/// measured paths are taken relative to `base_dir`. Throws InvalidArgument "<source>:<line>:<column>: <key>: ..."
/// for malformed JSON, unknown keys (listing the allowed ones), wrong types and unknown names. The values' ranges
/// are checked by expand_sweep.
inline SweepSpec parse_sweep(std::string_view text, const std::string& source, const std::string& base_dir = "") {
  return detail::sweep_from_json(io::parse_json(text, source), base_dir);
}

/// Reads a sweep file; relative paths in it are taken relative to its folder.
inline SweepSpec read_sweep_file(const std::string& path) {
  return detail::sweep_from_json(io::read_json_file(path), std::filesystem::path(path).parent_path().string());
}

}  // namespace blockdem::analysis
