#pragma once
// The sweep commands, `cross_vault sweep` (the vault) and `blockdem sweep` (a model file): many studies from a sweep
// file (analysis/sweep_file.hpp), under MPI when the program was built with it (every rank computes, rank 0
// included), else one after another; the logic is in analysis/sweep_run.hpp and parallel/.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/analysis/sweep_file.hpp"
#include "blockdem/analysis/sweep_run.hpp"
#include "blockdem/parallel/task_farm.hpp"
#include "cli.hpp"
#if defined(BLOCKDEM_WITH_MPI)
#include "blockdem/parallel/mpi_farm.hpp"
#endif
#if defined(_OPENMP)
#include <omp.h>
#endif

namespace blockdem::programs {

/// The options of a sweep command besides the base options of every case (those of the program's `run`): the sweep
/// file and what to run.
struct SweepCommand {
  std::string spec;
  long long single_case = -1;
  bool list = false, summarize = false;
  CLI::App* app = nullptr;
  CLI::Option* spec_option = nullptr;

  void add_to(CLI::App& sweep, const std::string& spec_help) {
    app = &sweep;
    spec_option = sweep.add_option("spec", spec, spec_help)->required();
    sweep.add_option("--case", single_case, "run only case K of the expansion (0-based, see --list), e.g. as one task of a job array");
    sweep.add_flag("--list", list, "print the cases (index and id) and stop");
    sweep.add_flag("--summarize", summarize, "write the summary from the case folders as they are, running nothing");
  }

  /// The options of `run` that the sweep file sets per case, or that a sweep handles itself: refused, so that none
  /// is silently overridden.
  void refuse_grid_options() const {
    for (const char* option : {"--levels", "--record", "--damping", "--zeta", "--frequency", "--band", "--branches",
                               "--kinematics", "--resume", "--stop-after-steps"})
      if (app->get_option_no_throw(option) && app->count(option) > 0)
        throw InvalidArgument(std::string("sweep: ") + option +
                              " is not a base option: the sweep file gives the records, levels (or pga_g, sa_g), "
                              "schemes with their parameters (and the vault's kinematics) of each case, and a sweep run "
                              "again continues its interrupted cases by itself");
  }

  /// What must match for a finished case to be taken as it is: the command line less what only steers the sweep,
  /// the sweep file's comparison and `more` (a model file's text).
  std::string fingerprint(int argc, char** argv, const analysis::SweepSpec& s, const std::string& more = "") const {
    static const std::set<std::string> flags{"--quiet", "--list", "--summarize", "--json"};
    static const std::set<std::string> with_value{"--out", "--case"};
    std::string f;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (flags.contains(a) || a == spec || a.starts_with("--out=") || a.starts_with("--case=")) continue;
      if (with_value.contains(a)) {
        ++i;
        continue;
      }
      (f += a) += ' ';
    }
    f += "| measured " + s.measured + " at " + io::JsonObject::number(s.measured_level);
    if (!more.empty()) f += " | model " + std::to_string(std::hash<std::string>{}(more));
    return f;
  }
};

inline void print_sweep_rows(const std::vector<analysis::CaseRow>& rows) {
  using namespace analysis;
  fmt::print("{:>5}  {:<44} {:<11} {:>9}  {}\n", "case", "id", "status", "wall s", "message");
  for (const auto& r : rows)
    fmt::print("{:>5}  {:<44} {:<11} {:>9.1f}  {}\n", r.index, r.id, std::string(name(r.status)) + (r.skipped ? "*" : ""),
               r.wall_seconds, r.message);
}

/// Runs a sweep command: lists, summarizes, runs one case (--case) or all of them on the farm. `program` names the
/// program in messages ("cross_vault sweep").
inline int run_sweep_command(const char* program, const SweepCommand& command, const std::vector<analysis::SweepCase>& cases,
                             analysis::SweepRunOptions run, int argc, char** argv) {
  if (command.list) {
    for (const auto& c : cases) fmt::print("{:>5}  {}\n", c.index, c.id);
    return 0;
  }
  if (command.summarize) {
    std::vector<analysis::CaseRow> rows;
    for (const auto& c : cases) rows.push_back(analysis::recorded_row(c, run));
    analysis::write_summary(run, rows);
    print_sweep_rows(rows);
    fmt::print("summary of {} cases in {}/summary.csv and summary.json\n", rows.size(), run.out_dir);
    return 0;
  }
  stop_on_interrupt();
  if (command.app->count("--case") > 0) {
    if (command.single_case < 0 || static_cast<std::size_t>(command.single_case) >= cases.size())
      throw InvalidArgument("--case must be in [0, " + std::to_string(cases.size() - 1) + "] (the sweep has " +
                            std::to_string(cases.size()) + " cases), got " + std::to_string(command.single_case));
    std::error_code error;  // as run_sweep: a folder that cannot be made is bad input, not a failed case
    std::filesystem::create_directories(run.out_dir + "/cases", error);
    if (error) throw InvalidArgument("--out: cannot create the sweep folder '" + run.out_dir + "': " + error.message());
    const auto row = analysis::run_sweep_case(cases[static_cast<std::size_t>(command.single_case)], run);
    print_sweep_rows({row});
    return row.status == analysis::CaseStatus::done ? 0 : 1;
  }

#if defined(BLOCKDEM_WITH_MPI)
  MPI_Init(&argc, &argv);
  parallel::MpiFarm farm;
#else
  (void)argc;
  (void)argv;
  parallel::SerialFarm farm;
#endif
  if (farm.size() > 1) {
    run.progress = false;  // one line per case instead of interleaved progress lines
#if defined(_OPENMP)
    if (!std::getenv("OMP_NUM_THREADS")) omp_set_num_threads(1);  // one core per rank
#endif
  }
  if (farm.lead())
    fmt::print("sweep: {} cases on {} process{} into {}/\n", cases.size(), farm.size(), farm.size() > 1 ? "es" : "", run.out_dir);
  std::fflush(stdout);
  int status = 0;
  try {
    const auto rows = analysis::run_sweep(cases, run, farm, [&](const analysis::CaseRow& row, int rank) {
      fmt::print("[rank {}] case {} {}: {}{} in {:.1f} s{}\n", rank, row.index, row.id, analysis::name(row.status),
                 row.skipped ? " (finished earlier, not run again)" : "", row.wall_seconds,
                 row.message.empty() ? std::string() : ": " + row.message);
      std::fflush(stdout);
    });
    if (farm.lead()) {
      std::size_t failed = 0, unfinished = 0;
      for (const auto& r : rows) {
        failed += r.status == analysis::CaseStatus::failed;
        unfinished += r.status != analysis::CaseStatus::done && r.status != analysis::CaseStatus::failed;
      }
      fmt::print("\n");
      print_sweep_rows(rows);
      fmt::print("{} done, {} failed, {} not finished (* finished in an earlier run); lead's time serving workers {:.3f} s\n",
                 rows.size() - failed - unfinished, failed, unfinished, farm.serve_seconds());
      fmt::print("summary in {}/summary.csv and summary.json; plots: python3 scripts/plot_sweep.py {}\n", run.out_dir, run.out_dir);
      if (unfinished > 0) fmt::print("run the same command again to finish the sweep\n");
      status = failed + unfinished > 0 ? 1 : 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error on rank %d: %s\n", program, farm.rank(), e.what());
#if defined(BLOCKDEM_WITH_MPI)
    if (farm.size() > 1) MPI_Abort(MPI_COMM_WORLD, 2);
#endif
    status = 2;
  }
#if defined(BLOCKDEM_WITH_MPI)
  MPI_Finalize();
#endif
  return status;
}

}  // namespace blockdem::programs
