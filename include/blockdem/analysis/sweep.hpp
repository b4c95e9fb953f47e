#pragma once
// Many vault analyses from one description (paper Sect. 5, Table 3: the sensitivity of the response to the damping
// scheme and its parameters; an incremental dynamic analysis over many records): a grid of damping schemes with
// their parameters, records, levels and kinematics, expanded into cases in a fixed, documented order with stable
// ids, each case the options of one vault study (analysis/vault_study.hpp).

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <charconv>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "blockdem/analysis/vault_study_options.hpp"
#include "blockdem/core/error.hpp"

namespace blockdem::analysis {

/// One damping scheme of a sweep and the values of its parameters to try: every combination of the lists that the
/// scheme uses is a case. An empty list means the scheme's default (VaultStudyOptions). Which lists a scheme uses:
/// zetas for every scheme but none; frequencies_hz for mass (the centre of MassProp) and stiffness (where zeta is
/// met); bands_hz for maxwell (the band of the fit) and rayleigh (its two frequencies); branches for maxwell.
struct SweepScheme {
  DampingScheme scheme = DampingScheme::maxwell;
  std::vector<double> zetas;
  std::vector<double> frequencies_hz;
  std::vector<std::array<double, 2>> bands_hz;
  std::vector<int> branches;
};

/// How the levels of a sweep are given: as % of the original record (the paper's 25, 50, 75 %), or as targets of an
/// intensity measure of the input that each record is scaled to: its peak ground acceleration, or its 5 %-damped
/// pseudo-spectral acceleration at a period (motion/spectrum.hpp), both in g.
enum class IntensityMeasure { level, pga, sa };
inline constexpr const char* name(IntensityMeasure m) {
  switch (m) {
    case IntensityMeasure::level: return "level";
    case IntensityMeasure::pga: return "pga";
    case IntensityMeasure::sa: return "sa";
  }
  return "?";
}

/// A sweep: every kinematics x record x scheme (with its parameter grid) x level is a case. `levels`: % of the
/// original record (measure level) or targets in g (pga, sa); with `incremental`, each case runs all of them one
/// after another on one state (the paper's incremental analysis); otherwise each level is a case of its own,
/// starting from the undamaged vault (an incremental dynamic analysis, IDA). Records: file paths; an empty string is
/// the built-in synthetic AQA75 stand-in. `measured`: optional CSV of measured channels (analysis/error_metrics.hpp)
/// that every case's history of the level `measured_level` (%, as its history file is labelled) is compared with.
struct SweepSpec {
  std::string model;  // a model file (docs/model-file.md) whose structure every case studies; empty: the vault
  std::vector<VaultKinematics> kinematics{VaultKinematics::rigid};  // the vault's only: a model file's blocks say theirs
  std::vector<std::string> records{""};
  std::vector<SweepScheme> schemes;
  std::vector<double> levels{25, 50, 75};
  IntensityMeasure measure = IntensityMeasure::level;
  double sa_period = 0;  // s, of the spectral acceleration (measure sa)
  bool incremental = true;
  std::string measured;
  double measured_level = 0;  // 0: the last level of each case
};

/// One case of a sweep: its id (stable: from its parameters, not from its position), its position in the expansion,
/// and the options of its vault study. With an intensity measure other than level, `intensities` holds the targets
/// (g) and options.levels is set from them once the record is read (resolve_intensities, analysis/sweep_run.hpp).
struct SweepCase {
  std::size_t index = 0;
  std::string id;
  VaultStudyOptions options;
  IntensityMeasure measure = IntensityMeasure::level;
  double sa_period = 0;
  std::vector<double> intensities;
};

namespace detail {
/// A number for an id: the shortest text that reads back exactly (7.5, 0.02, 20, 1e-05).
inline std::string id_number(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

/// The record's part of an id: the file name without folders and extension, or "aqa75" for the built-in one.
inline std::string record_tag(const std::string& path) {
  if (path.empty()) return "aqa75";
  std::string name = path.substr(path.find_last_of("/\\") + 1);
  if (const auto dot = name.find_last_of('.'); dot != std::string::npos && dot > 0) name.resize(dot);
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.')) c = '_';
  return name;
}
}  // namespace detail

/// The cases of `spec`, each from the options `base` with its own values set, in this order (the outermost first):
/// kinematics, record, scheme (in the order given), zeta, frequency or band, branches, level (not incremental).
/// Ids read like `rigid_aqa75_maxwell_z0.03_b1-40_n3_L25` (kinematics or the model file's name, record, scheme, its parameters, level: `_L25`
/// for 25 %, `_pga0.3g` or `_sa0.3g` for a target; incremental cases with targets end in `_pga` or `_sa`; the
/// parameters a scheme does not use are left out, defaults marked `z-default` and so on). Throws InvalidArgument
/// naming the field and its range if a list is empty, a value is out of range (VaultStudyOptions::validate on every
/// case), a scheme is given a list it does not use, or two cases would get the same id.
inline std::vector<SweepCase> expand_sweep(const SweepSpec& spec, const VaultStudyOptions& base) {
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw InvalidArgument("sweep: " + what);
  };
  check(!spec.kinematics.empty(), "kinematics: give at least one (rigid, mixed, deformable)");
  check(!spec.records.empty(), "records: give at least one (an empty name is the built-in AQA75 stand-in)");
  check(!spec.schemes.empty(), "schemes: give at least one damping scheme (none, mass, stiffness, rayleigh, maxwell)");
  check(!spec.levels.empty(), "levels: give at least one level in (0, 1000] % (or a target in g with pga, sa)");
  if (spec.measure != IntensityMeasure::level)
    for (double v : spec.levels)
      check(v > 0 && v <= 20 && std::isfinite(v), std::string(name(spec.measure)) + ": each target must be in (0, 20] g, got " +
                                                      detail::id_number(v));
  check(spec.measure != IntensityMeasure::sa || (spec.sa_period >= 0.01 && spec.sa_period <= 10),
        "sa_period_s: the period of the spectral acceleration must be in [0.01, 10] s, got " + detail::id_number(spec.sa_period));
  check(spec.measured_level >= 0 && spec.measured_level <= 1000, "measured_level must be in [0, 1000] % (0: the last level)");
  for (const auto& s : spec.schemes) {
    const std::string scheme = name(s.scheme);
    const bool uses_zeta = s.scheme != DampingScheme::none;
    const bool uses_frequency = s.scheme == DampingScheme::mass || s.scheme == DampingScheme::stiffness;
    const bool uses_band = s.scheme == DampingScheme::maxwell || s.scheme == DampingScheme::rayleigh;
    const bool uses_branches = s.scheme == DampingScheme::maxwell;
    check(uses_zeta || s.zetas.empty(), scheme + ": takes no damping ratio (zetas)");
    check(uses_frequency || s.frequencies_hz.empty(), scheme + ": takes no frequency (frequencies_hz: mass and stiffness only)");
    check(uses_band || s.bands_hz.empty(), scheme + ": takes no band (bands_hz: maxwell and rayleigh only)");
    check(uses_branches || s.branches.empty(), scheme + ": takes no number of branches (branches: maxwell only)");
  }
  // The lists of a scheme with "the default" in place of an empty one.
  const auto or_default = []<class T>(const std::vector<T>& v) {
    std::vector<std::optional<T>> out(v.begin(), v.end());
    if (out.empty()) out.emplace_back(std::nullopt);
    return out;
  };
  std::vector<SweepCase> cases;
  std::set<std::string> ids;
  const std::vector<std::optional<double>> levels = spec.incremental ? std::vector<std::optional<double>>{std::nullopt}
                                                                      : or_default(spec.levels);
  check(spec.model.empty() || spec.kinematics == std::vector<VaultKinematics>{VaultKinematics::rigid},
        "kinematics: a model file's blocks say whether they are rigid or deformable; leave kinematics out");
  // A model file's cases are named after its file, the vault's after their kinematics.
  const std::string model_tag = spec.model.empty() ? "" : detail::record_tag(spec.model);
  for (const VaultKinematics kinematics : spec.kinematics)
    for (const std::string& given_record : spec.records)
      for (const SweepScheme& s : spec.schemes)
        for (const auto& zeta : or_default(s.zetas))
          for (const auto& frequency : or_default(s.frequencies_hz))
            for (const auto& band : or_default(s.bands_hz))
              for (const auto& branches : or_default(s.branches))
                for (const auto& level : levels) {
                  SweepCase c;
                  c.index = cases.size();
                  VaultStudyOptions& o = c.options;
                  o = base;
                  o.kinematics = kinematics;
                  // "" is the base's record: a model file's own, or the vault's built-in stand-in.
                  const std::string& record = given_record.empty() ? base.record_path : given_record;
                  o.record_path = record;
                  o.record.reset();
                  o.damping = s.scheme;
                  std::string id = (model_tag.empty() ? std::string(name(kinematics)) : model_tag) + "_" +
                                   detail::record_tag(record) + "_" + name(s.scheme);
                  if (s.scheme != DampingScheme::none) {
                    o.zeta = zeta ? *zeta : 0.0;
                    id += zeta ? "_z" + detail::id_number(*zeta) : "_z-default";
                  }
                  if (s.scheme == DampingScheme::mass || s.scheme == DampingScheme::stiffness) {
                    if (frequency) o.frequency_hz = *frequency;
                    id += "_f" + detail::id_number(o.frequency_hz);
                  }
                  if (s.scheme == DampingScheme::maxwell || s.scheme == DampingScheme::rayleigh) {
                    if (band) {
                      o.lower_hz = (*band)[0];
                      o.upper_hz = (*band)[1];
                    }
                    id += "_b" + detail::id_number(o.lower_hz) + "-" + detail::id_number(o.upper_hz);
                  }
                  if (s.scheme == DampingScheme::maxwell) {
                    if (branches) o.branches = *branches;
                    id += "_n" + std::to_string(o.branches);
                  }
                  const std::string level_tag = spec.measure == IntensityMeasure::level ? "_L"
                                                : spec.measure == IntensityMeasure::pga ? "_pga"
                                                                                        : "_sa";
                  const std::string unit = spec.measure == IntensityMeasure::level ? "" : "g";
                  const std::vector<double> targets = level ? std::vector<double>{*level} : spec.levels;
                  if (level) id += level_tag + detail::id_number(*level) + unit;
                  if (spec.measure == IntensityMeasure::level) {
                    o.levels = targets;
                  } else {
                    c.measure = spec.measure;
                    c.sa_period = spec.sa_period;
                    c.intensities = targets;
                    o.levels = std::vector<double>(targets.size(), 100.0);  // placeholders until resolved
                    if (!level) id += level_tag;
                  }
                  try {
                    o.validate();
                  } catch (const InvalidArgument& e) {
                    throw InvalidArgument("sweep, case " + id + ": " + e.what());
                  }
                  check(ids.insert(id).second, "two cases would both be " + id + " (a value repeated in a list?)");
                  c.id = std::move(id);
                  cases.push_back(std::move(c));
                }
  return cases;
}

}  // namespace blockdem::analysis
