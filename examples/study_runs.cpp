// The seismic study and the pushover, compiled once for the programs and the Python module (study_runs.hpp).

#include "study_runs.hpp"

#include "blockdem/analysis/pushover.hpp"
#include "blockdem/analysis/study.hpp"

namespace blockdem::programs {

analysis::StudyResult run_study(analysis::Structure structure, const analysis::StudyOptions& options) {
  return analysis::run_study(std::move(structure), options);
}

analysis::PushoverResult run_pushover(const analysis::Structure& structure, const analysis::PushoverOptions& options, bool general_contacts) {
  return analysis::run_pushover(structure, options, general_contacts);
}

}  // namespace blockdem::programs
