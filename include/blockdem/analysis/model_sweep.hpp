#pragma once
// A sweep over a model file's structure (`blockdem sweep`, and blockdem.sweep from Python): the cases of the sweep
// file expanded over the model's study, each case's record scaled to the model's intensity target, and the
// summary's channels taken from its first monitor point.

#include <string>
#include <vector>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/study.hpp"
#include "blockdem/analysis/sweep.hpp"
#include "blockdem/analysis/sweep_run.hpp"

namespace blockdem::analysis {

/// The cases of `spec` over the structure of `file`, whose study `study` (the file's, with a caller's overrides)
/// gives their base options; fills `run`'s channels, measurement and program, not its study, folder or fingerprint.
/// `source` names the model file in messages. Throws InvalidArgument for a model that cannot be swept.
inline std::vector<SweepCase> model_sweep_cases(const SweepSpec& spec, const ModelFile& file, const StudyOptions& study,
                                                const std::string& source, SweepRunOptions& run) {
  if (file.pushover)
    throw InvalidArgument(source + ": study.analysis: a pushover; a sweep runs the seismic study's levels (\"levels\")");
  if (file.structure.monitors.empty())
    throw InvalidArgument(source + ": monitor_points: a sweep's summary gives the peaks of the first monitor point; add one");
  VaultStudyOptions base;
  static_cast<StudyOptions&>(base) = study;
  run.measured = spec.measured;
  run.measured_level = spec.measured_level;
  run.progress = study.progress;
  const std::string& first = file.structure.monitors.front().name;
  run.displacement_channel = first + "_u" + study.axis;
  run.acceleration_channel = first + "_a" + study.axis;
  run.residual_point = first;
  run.study_is_model = true;
  auto cases = expand_sweep(spec, base);
  // A model file's intensity target (a PGA or Sa(T) at 100 %) scales each case's record as it scales the file's own,
  // unless the sweep gives targets of its own; a record that cannot be read fails its case when it runs.
  if (file.scale.kind != RecordScale::Kind::record_level && spec.measure == IntensityMeasure::level)
    for (auto& c : cases) {
      try {
        c.options.record_level = record_level_for(file.scale, c.options, source);
      } catch (const InvalidArgument&) {
      } catch (const InputError&) {
      }
    }
  return cases;
}

}  // namespace blockdem::analysis
