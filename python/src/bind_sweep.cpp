// blockdem.sweep: the cases of a sweep file over a model's structure, as `blockdem sweep` runs them in one process
// (analysis/model_sweep.hpp, analysis/sweep_run.hpp): each into its own folder, finished cases skipped when the
// sweep runs again, the summary written; Ctrl-C stops after the current step, leaving that case to be continued.

#include <cstdio>

#include "bindings.hpp"

#include "blockdem/analysis/model_sweep.hpp"
#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/analysis/sweep_file.hpp"
#include "blockdem/parallel/task_farm.hpp"
#include "study_runs.hpp"

namespace blockdem::python {

namespace {

/// The options of blockdem.run that a sweep file sets per case, or that a sweep handles itself.
void refuse_grid_options(const py::dict& options) {
  for (const char* key : {"levels", "record", "damping", "zeta", "frequency", "band", "branches", "resume", "stop_after_steps"})
    if (options.contains(key))
      throw py::type_error(std::string("sweep: ") + key +
                           " is not a base option: the sweep gives the records, levels (or pga_g, sa_g) and schemes with their "
                           "parameters of each case, and a sweep run again continues its interrupted cases by itself");
}

}  // namespace

void bind_sweep(py::module_& m) {
  m.def(
      "run_sweep",
      [](const std::string& spec_text, const std::string& spec_source, const std::string& spec_dir, const analysis::ModelFile& file,
         const std::string& model_source, const py::dict& options, const std::string& out, const std::string& fingerprint) {
        refuse_grid_options(options);
        const auto spec = analysis::parse_sweep(spec_text, spec_source, spec_dir);
        analysis::StudyOptions study = file.study;
        study.program = "blockdem.sweep (Python)";
        apply_study_options(study, options);
        try {
          study.validate();
        } catch (const InvalidArgument& e) {
          throw py::value_error(python_option_names(e.what()));
        }
        for (const auto& w : analysis::refuse_unusable(file.structure, file.geometry_issues, file.block_origin, model_source))
          std::fprintf(stderr, "blockdem: warning: %s: %s\n", model_source.c_str(), w.c_str());
        analysis::SweepRunOptions run;
        run.out_dir = out;
        run.fingerprint = fingerprint;
        run.program = "blockdem.sweep (Python)";
        run.study = [&file](const analysis::VaultStudyOptions& o) { return programs::run_study(file.structure, o); };
        const auto cases = analysis::model_sweep_cases(spec, file, study, model_source, run);
        const bool progress = study.progress;
        const auto rows = run_without_gil([&](std::function<void()> poll) {
          parallel::SerialFarm farm(std::move(poll));
          return analysis::run_sweep(cases, run, farm, [&](const analysis::CaseRow& row, int) {
            if (!progress) return;
            std::fprintf(stderr, "case %zu %s: %s%s in %.1f s%s%s\n", row.index, row.id.c_str(), analysis::name(row.status),
                         row.skipped ? " (finished earlier, not run again)" : "", row.wall_seconds, row.message.empty() ? "" : ": ",
                         row.message.c_str());
          });
        });
        return rows.size();
      },
      py::arg("spec_text"), py::arg("spec_source"), py::arg("spec_dir"), py::arg("file"), py::arg("model_source"), py::arg("options"),
      py::arg("out"), py::arg("fingerprint"), "Runs a sweep (internal: blockdem.sweep calls it); returns the number of cases.");
}

}  // namespace blockdem::python
