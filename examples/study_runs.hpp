#pragma once
// The seismic study and the pushover as the programs run them, compiled once (study_runs.cpp) and linked into
// cross_vault, blockdem and the Python module: the study specializes the explicit integrator for every damping
// policy, minutes of compilation that each would otherwise repeat. The library stays header-only; this split is the programs' own.

#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_report.hpp"

namespace blockdem::programs {

/// analysis::run_study (analysis/study.hpp).
analysis::StudyResult run_study(analysis::Structure structure, const analysis::StudyOptions& options);

/// analysis::run_pushover (analysis/pushover.hpp).
analysis::PushoverResult run_pushover(const analysis::Structure& structure, const analysis::PushoverOptions& options, bool general_contacts);

}  // namespace blockdem::programs
