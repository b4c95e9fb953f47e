#pragma once
// The seismic study as the programs run it, compiled once (study_runs.cpp) and linked into cross_vault and blockdem:
// it specializes the explicit integrator for every damping policy, minutes of compilation that each program would
// otherwise repeat. The library stays header-only; this split is the programs' own.

#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_report.hpp"

namespace blockdem::programs {

/// analysis::run_study (analysis/study.hpp).
analysis::StudyResult run_study(analysis::Structure structure, const analysis::StudyOptions& options);

}  // namespace blockdem::programs
