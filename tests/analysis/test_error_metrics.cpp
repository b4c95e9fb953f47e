// The Sect. 5 error metrics (eq. 26-30, NRMSE, peak errors) against hand-computed values, the resampling and the
// CSV table reader with its error messages, and the channel-by-channel comparison of two tables.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../approx.hpp"

#include "blockdem/analysis/error_metrics.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_error_metrics {

namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::temp_directory_path() / ("blockdem_error_metrics_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

/// The message of the InvalidArgument that `f` throws, or "" when it throws none.
template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("error metrics: RMSD (eq. 26) of a sine over whole periods is A / sqrt(2), of a constant its magnitude") {
  const double amplitude = 0.012;  // m
  const int n = 400;               // samples over 3 periods: sum sin^2 = n/2 exactly when 2*3 is not a multiple of n
  std::vector<double> u(n);
  for (int i = 0; i < n; ++i) u[static_cast<std::size_t>(i)] = amplitude * std::sin(2 * std::numbers::pi * 3 * i / n + 0.3);
  CHECK(analysis::rmsd(u) == test::approx(amplitude / std::sqrt(2.0)).epsilon(1e-12));
  const std::vector<double> constant(7, -0.25);
  CHECK(analysis::rmsd(constant) == test::approx(0.25));
  CHECK_THROWS_AS(analysis::rmsd(std::span<const double>{}), InvalidArgument);
}

TEST_CASE("error metrics: eq. 27 averages the channels' RMSD, not the RMSD of all samples together") {
  const std::vector<double> a(5, 1.0), b(10, -2.0), c(4, 3.0);
  const std::array<std::span<const double>, 3> channels{a, b, c};
  CHECK(analysis::mean_rmsd(channels) == test::approx(2.0));  // (1 + 2 + 3) / 3; pooled samples would give 2.21
  CHECK_THROWS_AS(analysis::mean_rmsd({}), InvalidArgument);
}

TEST_CASE("error metrics: eq. 28 is |num - exp| / exp in percent, for over- and under-prediction alike") {
  CHECK(analysis::rmsd_relative_error_percent(12.0, 10.0) == test::approx(20.0));
  CHECK(analysis::rmsd_relative_error_percent(8.0, 10.0) == test::approx(20.0));
  CHECK(analysis::rmsd_relative_error_percent(0.0035, 0.005) == test::approx(30.0));
  CHECK_THROWS_WITH_AS(analysis::rmsd_relative_error_percent(1.0, 0.0), doctest::Contains("must be > 0"), InvalidArgument);
}

TEST_CASE("error metrics: NRMSE of exp + c is 100 c / (max - min) of exp") {
  const std::vector<double> exp{0.0, 1.0, 3.0, -1.0, 2.0};  // range 4, max |exp| 3, mean 1
  std::vector<double> num = exp;
  for (double& x : num) x += 0.5;
  CHECK(analysis::nrmse_percent(num, exp) == test::approx(12.5));  // 100 * 0.5 / 4
  // One sample off by d: RMS = d / sqrt(N).
  num = exp;
  num[3] += 2.0;
  CHECK(analysis::nrmse_percent(num, exp) == test::approx(100 * 2.0 / std::sqrt(5.0) / 4));
  CHECK(analysis::nrmse_percent(exp, exp) == 0.0);
  CHECK_THROWS_AS(analysis::nrmse_percent(std::span<const double>{}, std::span<const double>{}), InvalidArgument);
  CHECK_THROWS_WITH_AS(analysis::nrmse_percent(std::vector<double>{1, 2}, exp), doctest::Contains("resample first"), InvalidArgument);
  CHECK_THROWS_WITH_AS(analysis::nrmse_percent(exp, std::vector<double>(5, 2.0)), doctest::Contains("range 0"), InvalidArgument);
}

TEST_CASE("error metrics: peak errors (Fig. 15a) are signed towards a larger excursion at both peaks") {
  const std::vector<double> exp{0.0, 2.0, -1.0, 0.5, -3.0, 1.0};  // max 2, min -3, absolute peak 3
  std::vector<double> scaled = exp;
  for (double& x : scaled) x *= 1.2;
  const auto s = analysis::peak_errors(scaled, exp);
  CHECK(s.max_signed_percent == test::approx(20.0));
  CHECK(s.min_signed_percent == test::approx(20.0));
  CHECK(s.max_percent == test::approx(20.0));
  CHECK(s.min_percent == test::approx(20.0));
  CHECK(s.absolute_peak_percent == test::approx(20.0));

  // Over at the positive peak (2.5 vs 2), under at the negative one (-2.4 vs -3), at other times and lengths.
  const std::vector<double> num{0.0, -2.4, 1.0, 2.5, 0.0};
  const auto p = analysis::peak_errors(num, exp);
  CHECK(p.max_signed_percent == test::approx(25.0));
  CHECK(p.min_signed_percent == test::approx(-20.0));
  CHECK(p.max_percent == test::approx(25.0));
  CHECK(p.min_percent == test::approx(20.0));
  CHECK(p.absolute_peak_percent == test::approx(100.0 * 0.5 / 3.0));  // |2.5 - 3| / 3
  CHECK_THROWS_WITH_AS(analysis::peak_errors(num, std::vector<double>{0.0, 1.0}), doctest::Contains("minimum is 0"),
                       InvalidArgument);
}

TEST_CASE("error metrics: acceleration extremes (eq. 29) and RE_max, RE_min (eq. 30) relative to |a^EXP|") {
  const std::vector<double> a_exp{0.1, 2.0, -4.0, 1.0, -0.5};  // m/s^2
  const std::vector<double> a_num{3.0, -3.0, 0.2};
  const auto e = analysis::extremes(a_exp);
  const auto n = analysis::extremes(a_num);
  CHECK(e.max == 2.0);
  CHECK(e.min == -4.0);
  CHECK(analysis::re_max_percent(n, e) == test::approx(50.0));  // |3 - 2| / 2
  CHECK(analysis::re_min_percent(n, e) == test::approx(25.0));  // |-3 + 4| / 4
  // A signal that stays negative: the denominator is |a_max^EXP|, so the error is still positive.
  CHECK(analysis::re_max_percent({-1.5, -3.0}, {-1.0, -2.0}) == test::approx(50.0));
  CHECK(analysis::re_min_percent({-1.5, -3.0}, {-1.0, -2.0}) == test::approx(50.0));
  CHECK_THROWS_AS(analysis::re_max_percent(n, {0.0, -1.0}), InvalidArgument);
  CHECK_THROWS_AS(analysis::re_min_percent(n, {1.0, 0.0}), InvalidArgument);
  CHECK_THROWS_AS(analysis::extremes(std::span<const double>{}), InvalidArgument);
}

TEST_CASE("error metrics: linear resampling reproduces a linear function exactly, times outside the span throw") {
  const std::vector<double> t_from{0.0, 0.1, 0.25, 0.3, 0.7, 1.0};  // s, non-uniform
  std::vector<double> u_from;
  for (const double t : t_from) u_from.push_back(3.0 - 2.0 * t);
  const std::vector<double> t_to{0.0, 0.05, 0.26, 0.3, 0.95, 1.0, 0.5};
  const auto u = analysis::resample(t_from, u_from, t_to);
  REQUIRE(u.size() == t_to.size());
  for (std::size_t k = 0; k < t_to.size(); ++k) CHECK(u[k] == test::approx(3.0 - 2.0 * t_to[k]).epsilon(1e-14));

  // Between the nodes of t^2 the chord is taken: 2.5 at t = 1.5, not 2.25 (nor a neighbour's 1 or 4).
  CHECK(analysis::resample(std::vector<double>{0.0, 1.0, 2.0}, std::vector<double>{0.0, 1.0, 4.0}, std::vector<double>{1.5})[0] ==
        test::approx(2.5));

  const std::vector<double> late{0.5, 1.25};
  CHECK_THROWS_WITH_AS(analysis::resample(t_from, u_from, late), doctest::Contains("time 1.25 s is outside"), InvalidArgument);
  const std::vector<double> early{-0.01};
  CHECK_THROWS_WITH_AS(analysis::resample(t_from, u_from, early), doctest::Contains("time -0.01 s"), InvalidArgument);
  const std::vector<double> repeated{0.0, 0.1, 0.1, 0.2};
  CHECK_THROWS_WITH_AS(analysis::resample(repeated, std::vector<double>(4, 0.0), std::vector<double>{0.05}),
                       doctest::Contains("strictly increasing"), InvalidArgument);
}

TEST_CASE("error metrics: zero_at_first_sample subtracts the first value from all of them") {
  std::vector<double> u{0.003, 0.004, 0.001, -0.002};
  analysis::zero_at_first_sample(u);
  CHECK(u[0] == 0.0);
  CHECK(u[1] == test::approx(0.001));
  CHECK(u[2] == test::approx(-0.002));
  CHECK(u[3] == test::approx(-0.005));
}

TEST_CASE("error metrics: a CSV table with comments, blanks and CRLF reads column-major, a missing column is named") {
  const auto path = write_temp("good.csv",
                               "# exported by the shake-table DAQ\r\n"
                               "time_s, OC1_uy ,ACC18_ay\r\n"
                               "\r\n"
                               "0.0,0.001,-0.5\r\n"
                               "# a comment between rows\r\n"
                               "0.01,+2e-3,1.5\r\n"
                               "0.02,-0.003,  0.25\r\n");
  const auto t = analysis::read_csv_table(path);
  REQUIRE(t.columns == std::vector<std::string>{"time_s", "OC1_uy", "ACC18_ay"});
  REQUIRE(t.rows() == 3);
  CHECK(t.source == path);
  CHECK(t.values[t.column("OC1_uy")][1] == 0.002);
  CHECK(t.values[t.column("ACC18_ay")][2] == 0.25);
  CHECK(t.values[0][2] == 0.02);
  const auto missing = message_of([&] { (void)t.column("OC2_uy"); });
  CHECK(contains(missing, path));
  CHECK(contains(missing, "'OC2_uy'"));
  CHECK(contains(missing, "time_s, OC1_uy, ACC18_ay"));
}

TEST_CASE("error metrics: every CSV error names the file and the line (and the column of a bad field)") {
  const auto bad_field = write_temp("bad_field.csv", "# c\ntime,OC1_ux,OC1_uy\n0,0,0\n0.1,0.2,abc\n");
  const auto m = message_of([&] { (void)analysis::read_csv_table(bad_field); });
  CHECK(contains(m, bad_field + ":4:"));
  CHECK(contains(m, "column 'OC1_uy'"));
  CHECK(contains(m, "'abc' is not a finite number"));

  const auto nan_field = write_temp("nan_field.csv", "time,OC1_ux\n0,nan\n");
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(nan_field); }), nan_field + ":2: column 'OC1_ux': 'nan'"));
  const auto empty_field = write_temp("empty_field.csv", "time,a,b\n0,,1\n");
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(empty_field); }), empty_field + ":2: column 'a'"));

  const auto short_row = write_temp("short_row.csv", "time,a,b\n0,1,2\n\n0.1,1\n");
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(short_row); }), short_row + ":4: 2 fields, expected 3"));

  const auto backwards = write_temp("backwards.csv", "time_s,a\n0,1\n0.2,1\n0.2,1\n");
  const auto b = message_of([&] { (void)analysis::read_csv_table(backwards); });
  CHECK(contains(b, backwards + ":4:"));
  CHECK(contains(b, "strictly increasing"));

  const auto no_time = write_temp("no_time.csv", "t,a\n0,1\n");
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(no_time); }), no_time + ":1: the first column must be the time"));

  const auto only_comments = write_temp("only_comments.csv", "# nothing\n\n");
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(only_comments); }), only_comments + ": no header line"));
  const auto header_only = write_temp("header_only.csv", "time,a\n# no rows\n");
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(header_only); }), header_only + ": no data rows"));

  const std::string absent = (std::filesystem::temp_directory_path() / "blockdem_no_such_table.csv").string();
  CHECK(contains(message_of([&] { (void)analysis::read_csv_table(absent); }), absent + ": cannot open"));
}

namespace {

/// A table of time and the given channels, each a function of time.
template <class... F>
analysis::Table make_table(double dt, int steps, std::vector<std::string> names, F... channels) {
  analysis::Table t;
  t.columns = std::move(names);
  t.values.resize(t.columns.size());
  for (int k = 0; k <= steps; ++k) {
    const double time = k * dt;
    t.values[0].push_back(time);
    std::size_t c = 1;
    ((t.values[c++].push_back(channels(time))), ...);
  }
  return t;
}

double displacement(double t) { return 0.01 * std::sin(2 * std::numbers::pi * 2 * t) + 0.002 * t; }            // m
double acceleration(double t) { return 3.0 * std::sin(2 * std::numbers::pi * 5 * t) + 1.0 * std::cos(7 * t); }  // m/s^2

}  // namespace

TEST_CASE("error metrics: compare_tables zeroes the measured displacement, resamples the overlap, ignores unshared columns") {
  constexpr double offset = 0.003;  // m, the measured displacement at t = 0
  // Simulated at dt = 0.005 s over 0.8 s (its nodes hold every measured time), measured at 0.01 s over 1 s.
  const auto simulated = make_table(0.005, 160, {"time_s", "OC1_uy", "ACC18_ay", "OC9_ux"}, displacement,
                                    [](double t) { return 1.2 * acceleration(t); }, displacement);
  const auto measured = make_table(0.01, 100, {"time", "ACC1_ax", "ACC18_ay", "OC1_uy"}, acceleration, acceleration,
                                   [](double t) { return displacement(t) + offset; });
  const auto r = analysis::compare_tables(simulated, measured);
  REQUIRE(r.size() == 2);  // ACC1_ax only measured, OC9_ux only simulated

  const auto& acc = r[0];
  CHECK(acc.channel == "ACC18_ay");
  CHECK(acc.samples == 81);  // 0, 0.01, ..., 0.8 s
  CHECK(acc.peaks.max_signed_percent == test::approx(20.0));
  CHECK(acc.peaks.min_signed_percent == test::approx(20.0));
  CHECK(acc.re_max_percent == test::approx(20.0));
  CHECK(acc.re_min_percent == test::approx(20.0));
  CHECK(acc.rmsd_error_percent == test::approx(20.0));
  CHECK(acc.peak_bias_percent == test::approx(20.0));  // Table 3's signed peak bias: 1.2 times the measured peak
  CHECK(acc.rmsd_num == test::approx(1.2 * acc.rmsd_exp));
  const std::vector<double> acc_window(measured.values[2].begin(), measured.values[2].begin() + 81);
  const auto [acc_lo, acc_hi] = std::minmax_element(acc_window.begin(), acc_window.end());
  CHECK(acc.nrmse_percent == test::approx(100 * 0.2 * acc.rmsd_exp / (*acc_hi - *acc_lo)).epsilon(1e-12));

  const auto& u = r[1];
  CHECK(u.channel == "OC1_uy");
  CHECK(u.nrmse_percent < 1e-9);
  CHECK(u.rmsd_error_percent < 1e-9);
  CHECK(u.peaks.absolute_peak_percent < 1e-9);
  CHECK(std::abs(u.peak_bias_percent) < 1e-9);
  CHECK(u.re_max_percent < 1e-9);

  // Without the zeroing, the offset is the whole error: NRMSE = 100 offset / range.
  const auto raw = analysis::compare_tables(simulated, measured, false);
  const std::vector<double> window(measured.values[3].begin(), measured.values[3].begin() + 81);
  const auto [lo, hi] = std::minmax_element(window.begin(), window.end());
  CHECK(raw[1].nrmse_percent == test::approx(100 * offset / (*hi - *lo)).epsilon(1e-9));
  CHECK(raw[0].nrmse_percent == test::approx(acc.nrmse_percent));  // accelerations are never zeroed
}

TEST_CASE("error metrics: compare_tables reads files, and refuses tables with no shared channel or no overlap") {
  const auto sim = write_temp("sim.csv", "time_s,OC1_uy\n0,0\n0.5,0.01\n1,0\n");
  // Measured 2 mm at rest, then the simulated triangle (0 -> 10 mm at 0.5 s -> 0) on top of it; t = 2 s is beyond
  // the simulation, t = 0.25 and 0.75 s fall between its nodes.
  const auto exp = write_temp("exp.csv", "# measured\ntime,OC1_uy\n0,0.002\n0.25,0.007\n0.75,0.007\n1,0.002\n2,0\n");
  const auto r = analysis::compare_tables(analysis::read_csv_table(sim), analysis::read_csv_table(exp));
  REQUIRE(r.size() == 1);
  CHECK(r[0].samples == 4);
  CHECK(r[0].nrmse_percent < 1e-9);
  CHECK(r[0].rmsd_num == test::approx(std::sqrt(2 * 0.005 * 0.005 / 4)));
  CHECK(r[0].rmsd_exp == test::approx(std::sqrt(2 * 0.005 * 0.005 / 4)).epsilon(1e-12));

  const auto other = write_temp("other.csv", "time,ACC1_ax\n0,1\n1,2\n");
  const auto m = message_of([&] { (void)analysis::compare_tables(analysis::read_csv_table(sim), analysis::read_csv_table(other)); });
  CHECK(contains(m, "share no channel"));
  CHECK(contains(m, "simulated: OC1_uy; measured: ACC1_ax"));
  const auto late = write_temp("late.csv", "time,OC1_uy\n0.9,1\n1.5,2\n2,3\n");
  CHECK_THROWS_WITH_AS(analysis::compare_tables(analysis::read_csv_table(sim), analysis::read_csv_table(late)),
                       doctest::Contains("fewer than 2 measured samples"), InvalidArgument);
}

TEST_CASE("error metrics: the mean RMSD error (eq. 27-28) is the error of the means over OC1, OC2, OC4") {
  const auto channel = [](std::string name, double rmsd_num, double rmsd_exp) {
    analysis::ChannelComparison c;
    c.channel = std::move(name);
    c.rmsd_num = rmsd_num;
    c.rmsd_exp = rmsd_exp;
    return c;
  };
  const std::vector<analysis::ChannelComparison> r{
      channel("OC1_uy", 2.0, 1.0),  // 100 % alone
      channel("OC2_uy", 1.0, 3.0),  // 66.7 % alone
      channel("OC4_uy", 3.0, 2.5),  // 20 % alone
      channel("OC3_uy", 9.0, 1.0),  // not among the defaults
      channel("OC1_ux", 5.0, 1.0)};
  // Means 2 and 6.5/3: |2 - 2.1667| / 2.1667 = 7.69 %, while the mean of the errors would be 62.2 %.
  CHECK(analysis::mean_rmsd_error_percent(r, "_uy") == test::approx(100 * (6.5 / 3 - 2.0) / (6.5 / 3)));
  const std::array<std::string_view, 2> two{"OC1", "OC3"};
  CHECK(analysis::mean_rmsd_error_percent(r, "_uy", two) == test::approx(100 * (5.5 - 1.0) / 1.0));
  CHECK_THROWS_WITH_AS(analysis::mean_rmsd_error_percent(r, "_ux"), doctest::Contains("no channel 'OC2_ux'"), InvalidArgument);
}

}  // namespace test_error_metrics
