// The seismic study, compiled once for the programs (study_runs.hpp).

#include "study_runs.hpp"

#include "blockdem/analysis/study.hpp"

namespace blockdem::programs {

analysis::StudyResult run_study(analysis::Structure structure, const analysis::StudyOptions& options) {
  return analysis::run_study(std::move(structure), options);
}

}  // namespace blockdem::programs
