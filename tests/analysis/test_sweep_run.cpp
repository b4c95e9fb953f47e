// Running a sweep (analysis/sweep_run.hpp) on the coarse vault (bricks 0.2 x 0.7 m) over 0.1 s of the record: a case
// run by the sweep writes what the vault study writes by itself, bit for bit; a case that fails (a missing record,
// a run that leaves every bound) is recorded and the others complete; a second run skips the finished cases without
// touching their files and retries the failed one; intensity targets scale the record to the asked PGA.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "blockdem/analysis/sweep_run.hpp"
#include "../file_contents.hpp"
#include "../threads.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_sweep_run {
using namespace blockdem::analysis;

namespace {

VaultStudyOptions short_coarse_study() {
  VaultStudyOptions o;
  o.vault.unit_height = 0.2;
  o.vault.unit_length = 0.7;
  o.progress = false;
  o.rest = 0;
  o.window_start = 2.0;
  o.window_end = 2.1;
  return o;
}

/// summary.csv without its last column, the wall time.
std::string without_wall_times(const std::string& csv) {
  std::string out, line;
  std::istringstream in(csv);
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + '\n';
  return out;
}

std::filesystem::path fresh_folder(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  return dir;
}

}  // namespace

TEST_CASE("sweep run: cases that fail are recorded, the others complete, a second run skips the finished ones") {
  const test::OneThread one_thread;
  const auto dir = fresh_folder("blockdem_sweep_run");
  SweepSpec spec;
  spec.records = {"", "/nonexistent/record.AT2"};
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}, SweepScheme{DampingScheme::mass, {0.04}, {7.5}, {}, {}}};
  spec.levels = {25};
  const auto cases = expand_sweep(spec, short_coarse_study());
  REQUIRE(cases.size() == 4);
  SweepRunOptions run;
  run.study = run_vault_study;
  run.out_dir = dir.string();
  run.fingerprint = "test";
  run.progress = false;
  parallel::SerialFarm farm;
  int seen = 0;
  const auto rows = run_sweep(cases, run, farm, [&](const CaseRow&, int rank) {
    CHECK(rank == 0);
    ++seen;
  });
  CHECK(seen == 4);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0].status == CaseStatus::done);
  CHECK(rows[1].status == CaseStatus::done);
  CHECK(rows[2].status == CaseStatus::failed);
  CHECK(rows[3].status == CaseStatus::failed);
  CHECK(rows[2].message.find("/nonexistent/record.AT2") != std::string::npos);
  CHECK(rows[2].csv.find("failed") != std::string::npos);
  for (const auto& r : rows) CHECK_FALSE(r.skipped);

  // The summary: a header and a row per case, in case order; a finished case has its peaks, a failed one none.
  const std::string summary = test::file_contents(dir / "summary.csv");
  CHECK(summary.rfind(summary_header(run) + "\n", 0) == 0);
  CHECK(std::count(summary.begin(), summary.end(), '\n') == 5);
  CHECK(summary.find("\n0,rigid_aqa75_none,done,,rigid,aqa75,none,") != std::string::npos);
  CHECK(summary.find("\n3,rigid_record_mass_z0.04_f7.5,failed,") != std::string::npos);
  CHECK(test::file_contents(dir / "summary.json").find("\"failed\": 2") != std::string::npos);

  // The sweep's case is the vault study run by itself, byte for byte.
  auto alone = cases[1].options;
  alone.out_dir = (dir / "alone").string();
  run_vault_study(alone);
  const auto history = test::file_contents(dir / "cases" / cases[1].id / "history_25.csv");
  CHECK(history.size() > 1000);
  CHECK(history == test::file_contents(dir / "alone" / "history_25.csv"));

  // Again: the finished cases are skipped and their files left as they were; the failed ones run again.
  const auto written = std::filesystem::last_write_time(dir / "cases" / cases[0].id / "history_25.csv");
  const auto again = run_sweep(cases, run, farm, [](const CaseRow&, int) {});
  REQUIRE(again.size() == 4);
  CHECK(again[0].skipped);
  CHECK(again[1].skipped);
  CHECK_FALSE(again[2].skipped);
  CHECK(again[2].status == CaseStatus::failed);
  CHECK(again[0].csv == rows[0].csv);
  CHECK(std::filesystem::last_write_time(dir / "cases" / cases[0].id / "history_25.csv") == written);
  CHECK(without_wall_times(test::file_contents(dir / "summary.csv")) == without_wall_times(summary));  // the failed ones took their time again

  // Under other base options (another fingerprint) nothing is taken as finished.
  run.fingerprint = "other";
  CHECK(recorded_row(cases[0], run).status == CaseStatus::pending);
  std::filesystem::remove_all(dir);
}

TEST_CASE("sweep run: with measured channels, a row holds the biases of compare_tables, against itself they are 0") {
  const test::OneThread one_thread;
  const auto dir = fresh_folder("blockdem_sweep_measured");
  SweepSpec spec;
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}, SweepScheme{DampingScheme::mass, {0.04}, {7.5}, {}, {}}};
  spec.levels = {25};
  const auto cases = expand_sweep(spec, short_coarse_study());
  // The "measurement": the MassProp case run alone.
  auto alone = cases[1].options;
  alone.out_dir = (dir / "measured").string();
  run_vault_study(alone);
  SweepRunOptions run;
  run.study = run_vault_study;
  run.out_dir = (dir / "sweep").string();
  run.progress = false;
  run.measured = (dir / "measured" / "history_25.csv").string();
  const auto same = run_sweep_case(cases[1], run);
  const auto other = run_sweep_case(cases[0], run);
  REQUIRE(same.status == CaseStatus::done);
  REQUIRE(other.status == CaseStatus::done);
  // Fields 26-32 of the row: the peak biases of OC1-y and ACC18-y, the biases of their maxima and minima, eq. 27-28.
  auto fields = [](const std::string& csv) {
    std::vector<std::string> f(1);
    for (char ch : csv) {
      if (ch == ',') f.emplace_back();
      else f.back() += ch;
    }
    return f;
  };
  const auto s = fields(same.csv);
  const auto o = fields(other.csv);
  REQUIRE(s.size() == 34);
  for (std::size_t k = 26; k <= 32; ++k) {
    CAPTURE(k);
    CHECK(std::stod(s[k]) == 0.0);
  }
  // noDamp against MassProp: the biases compare_tables gives for the two files, whatever they are.
  const auto expected = compare_tables(read_csv_table(run.out_dir + "/cases/" + cases[0].id + "/history_25.csv"),
                                       read_csv_table(run.measured));
  for (const auto& c : expected) {
    if (c.channel == "OC1_uy") CHECK(std::stod(o[26]) == doctest::Approx(c.peak_bias_percent).epsilon(1e-12));
    if (c.channel == "ACC18_ay") CHECK(std::stod(o[27]) == doctest::Approx(c.peak_bias_percent).epsilon(1e-12));
  }
  CHECK(std::stod(o[26]) != 0.0);
  CHECK(std::stod(o[32]) == doctest::Approx(mean_rmsd_error_percent(expected, "_uy")).epsilon(1e-12));
  CHECK(other.json.find("\"compared\"") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("sweep run: a fault that is not the case's input fails the row as an internal error, a metric that cannot be computed says why") {
  const test::OneThread one_thread;
  const auto dir = fresh_folder("blockdem_sweep_internal");
  SweepSpec spec;
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}};
  spec.levels = {25};
  const auto cases = expand_sweep(spec, short_coarse_study());
  SweepRunOptions run;
  run.study = run_vault_study;
  run.out_dir = (dir / "faulty").string();
  run.progress = false;
  // A std::exception that no input explains (here thrown by the poll, as a logic error or bad_alloc would be).
  const auto faulty = run_sweep_case(cases[0], run, [] { throw std::logic_error("index out of range"); });
  CHECK(faulty.status == CaseStatus::failed);
  CHECK(faulty.message == "internal error (a fault of blockdem, not of this case's input; please report it): index out of range");
  // Measured channels without OC2 and OC4: the biases are there, eq. 27-28 is not, and the row says why.
  const auto measured = dir / "measured.csv";
  std::filesystem::create_directories(dir);
  std::ofstream(measured) << "time,OC1_uy\n0,0\n0.05,0.0001\n0.1,0\n";
  run.out_dir = (dir / "measured").string();
  run.measured = measured.string();
  const auto row = run_sweep_case(cases[0], run);
  CHECK(row.status == CaseStatus::done);
  CHECK(row.message == "eps_rmsd_uy not computed: mean RMSD error: no channel 'OC2_uy' among the compared ones (OC1_uy)");
  std::filesystem::remove_all(dir);
}

TEST_CASE("sweep run: a run that leaves every bound fails with its level, time and point, and does not stop the sweep") {
  const test::OneThread one_thread;
  const auto dir = fresh_folder("blockdem_sweep_runaway");
  SweepSpec spec;
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}};
  spec.levels = {75, 1000};
  spec.incremental = false;
  auto base = short_coarse_study();
  base.runaway_displacement = 0.001;  // 1 mm: the 1000 % level moves the crown farther than that within 0.1 s
  base.collapse_displacement = 0.001;  // at the runaway bound, which is checked first
  const auto cases = expand_sweep(spec, base);
  SweepRunOptions run;
  run.study = run_vault_study;
  run.out_dir = dir.string();
  run.progress = false;
  const auto quiet = run_sweep_case(cases[0], run);
  const auto loud = run_sweep_case(cases[1], run);
  CHECK(quiet.status == CaseStatus::done);
  CHECK(loud.status == CaseStatus::failed);
  CHECK(loud.message.find("level 1000 %") != std::string::npos);
  CHECK(loud.message.find("beyond --runaway-displacement 0.001 m") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("sweep run: a case whose vault collapses is done, and its row says at which level (an IDA's end)") {
  const test::OneThread one_thread;
  const auto dir = fresh_folder("blockdem_sweep_collapse");
  SweepSpec spec;
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}};
  spec.levels = {75, 1000};
  auto base = short_coarse_study();
  base.collapse_displacement = 0.001;  // 1 mm stands for the collapse: 1000 % moves the crown farther within 0.1 s
  const auto cases = expand_sweep(spec, base);
  REQUIRE(cases.size() == 1);  // incremental: one case, 75 % then 1000 %
  SweepRunOptions run;
  run.study = run_vault_study;
  run.out_dir = dir.string();
  run.progress = false;
  const auto row = run_sweep_case(cases[0], run);
  CHECK(row.status == CaseStatus::done);
  CHECK(row.message.find("collapsed at 1000 %") != std::string::npos);
  const auto summary = test::file_contents(dir / "cases" / cases[0].id / "case.json");
  CHECK(summary.find("\"collapsed\": true") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("sweep run: PGA targets scale the record to the asked PGA, and the row says so") {
  const test::OneThread one_thread;
  const auto dir = fresh_folder("blockdem_sweep_pga");
  SweepSpec spec;
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}};
  spec.measure = IntensityMeasure::pga;
  spec.levels = {0.05, 0.1};
  spec.incremental = false;
  auto base = short_coarse_study();
  base.window_start = 0;  // the whole 15 s record
  base.window_end = 15;
  const auto cases = expand_sweep(spec, base);
  REQUIRE(cases.size() == 2);
  CHECK(cases[1].id == "rigid_aqa75_none_pga0.1g");
  // The built-in record as the study cuts and corrects it, and its PGA counted here sample by sample (not by the
  // toolkit's peak_values, which the sweep uses).
  std::string note;
  const auto cut = analysis::detail::input_record(base, note);
  const auto largest = [](const motion::Record& r) {
    double a = 0;
    for (const double x : r.acceleration) a = std::max(a, std::abs(x));
    return a;
  };
  const auto per_percent = analysis::detail::intensity_per_percent(cases[1], cases[1].options);
  CHECK(per_percent.pga == doctest::Approx(largest(cut) / standard_gravity / base.record_level).epsilon(1e-14));
  const auto levels = resolve_intensities(cases[1], cases[1].options, per_percent);
  REQUIRE(levels.size() == 1);
  // The record the study runs at that level (vault_study.hpp scales the cut by level / record level) peaks at 0.1 g.
  const auto shaken = motion::scale(cut, levels[0] / base.record_level);
  CHECK(largest(shaken) / standard_gravity == doctest::Approx(0.1).epsilon(1e-12));
  // A target beyond 1000 % of the record is refused with the level it would need.
  auto far = cases[1];
  far.intensities = {19.0};
  CHECK_THROWS_WITH_AS(resolve_intensities(far, far.options, per_percent), doctest::Contains("beyond 1000 %"), InvalidArgument);
  std::filesystem::remove_all(dir);
}

TEST_CASE("sweep run: Sa(T) targets: a sine at the period's resonance has Sa = a0 / (2 xi), so a target of 0.5 g asks for a0 = 0.05 g") {
  // 30 s of a0 sin(2 pi t / T) at T = 0.5 s: the 5 %-damped oscillator of period T builds up to a0 / (2 xi) = 10 a0
  // (the transient is e^(-xi omega t) = e^(-18.8) of it by the end).
  constexpr double period = 0.5, a0 = 0.2 * standard_gravity, dt = 0.002;
  motion::Record sine;
  sine.name = "resonant sine";
  sine.dt = dt;
  for (int i = 0; i <= 15000; ++i) sine.acceleration.push_back(a0 * std::sin(2 * std::numbers::pi * i * dt / period));
  SweepCase c;
  c.id = "sine_sa";
  c.options = short_coarse_study();
  c.options.record = sine;
  c.options.record_level = 100;
  c.options.baseline = "none";
  c.options.window_start = 0;
  c.options.window_end = 30;
  c.measure = IntensityMeasure::sa;
  c.sa_period = period;
  c.intensities = {0.5};
  c.options.levels = {100};
  const auto per_percent = analysis::detail::intensity_per_percent(c, c.options);
  CHECK(100 * per_percent.sa == doctest::Approx(10 * a0 / standard_gravity).epsilon(5e-3));  // 2.0 g at 100 %
  CHECK(100 * per_percent.pga == doctest::Approx(a0 / standard_gravity).epsilon(1e-3));
  const auto levels = resolve_intensities(c, c.options, per_percent);
  REQUIRE(levels.size() == 1);
  CHECK(levels[0] == doctest::Approx(25.0).epsilon(5e-3));  // 25 % of the record: a0 = 0.05 g, Sa = 0.5 g
  CHECK(levels[0] * per_percent.sa == doctest::Approx(0.5).epsilon(1e-12));
}

TEST_CASE("sweep run: a row travels between processes unchanged") {
  CaseRow r;
  r.index = 7;
  r.id = "rigid_aqa75_maxwell_z0.03_b1-40_n3";
  r.status = CaseStatus::failed;
  r.message = "level 75 %: diverged, with a comma, \"quotes\"\nand a newline";
  r.csv = "7,x,failed";
  r.json = "{\n  \"a\": 1\n}";
  r.skipped = true;
  r.wall_seconds = 12.345678901234567;
  const CaseRow back = analysis::detail::decode(analysis::detail::encode(r));
  CHECK(back.index == r.index);
  CHECK(back.id == r.id);
  CHECK(back.status == r.status);
  CHECK(back.message == r.message);
  CHECK(back.csv == r.csv);
  CHECK(back.json == r.json);
  CHECK(back.skipped);
  CHECK(back.wall_seconds == r.wall_seconds);
  CHECK(analysis::detail::csv_text("a,\"b\"") == "\"a,\"\"b\"\"\"");
}

}  // namespace test_sweep_run
