// maxwell_fit: fits N Maxwell damping branches to a flat damping ratio over a frequency band (paper Sect. 4.2.3)
// and prints them as a table, JSON, CSV or the 3DEC command line; --curve writes the damping curves to plot.
//
//   maxwell_fit --zeta 0.03 --band 1 40 --branches 3 [--points 500] [--tolerance 0.01]
//               [--format table|json|csv|3dec] [--curve FILE.csv]
//
// Exit status: 0 on success, 1 if the fit did not converge (what it prints is then not a fit), 2 on bad input (the
// message names the option and its allowed range).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/core/units.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/json.hpp"
#include "cli.hpp"

namespace {

using namespace blockdem;
using damping::MaxwellFitResult;

using programs::exit_bad_input;

std::vector<double> column(const MaxwellFitResult& fit, double (*get)(const MaxwellFitResult&, int)) {
  std::vector<double> values;
  for (int i = 0; i < fit.branches; ++i) values.push_back(get(fit, i));
  return values;
}

std::string to_json(const MaxwellFitResult& fit, double solve_seconds, const damping::MaxwellFitOptions& options,
                    double tolerance) {
  io::JsonObject json;
  json.add("zeta_target", fit.target)
      .add("band_hz", std::vector<double>{options.lower_hz, options.upper_hz})
      .add("branches", fit.branches)
      .add("points", options.points)
      .add("ordering", damping::to_string(options.ordering))
      .add("alpha", column(fit, [](const MaxwellFitResult& f, int i) { return f.branch[i].alpha; }))
      .add("tau_s", column(fit, [](const MaxwellFitResult& f, int i) { return f.branch[i].tau; }))
      .add("peak_hz", column(fit, [](const MaxwellFitResult& f, int i) { return f.peak_hz(i); }))
      .add("peak_zeta", column(fit, [](const MaxwellFitResult& f, int i) { return f.peak_damping_ratio(i); }))
      .add("sum_alpha", fit.sum_alpha)
      .add("dt_factor", fit.dt_factor)
      .add("modulus_max", fit.modulus_max)
      .add("zeta_min", fit.zeta_min)
      .add("zeta_max", fit.zeta_max)
      .add("rel_error_min", fit.rel_error_min)
      .add("rel_error_max", fit.rel_error_max)
      .add("max_rel_error", fit.max_rel_error)
      .add("iterations", fit.iterations)
      .add("restarts", fit.restarts)
      .add("status", solve::to_string(fit.status))
      .add("solve_seconds", solve_seconds)
      .add("converged", fit.converged);
  if (tolerance > 0) json.add("tolerance", tolerance).add("meets_tolerance", fit.max_rel_error <= tolerance);
  return json.str();
}

void print_table(const MaxwellFitResult& fit, double solve_seconds, const damping::MaxwellFitOptions& options) {
  fmt::print("Maxwell damping fit: zeta* = {:.2f} % over {:g}-{:g} Hz, {} branches, {} points ({} ordering map)\n\n",
             100 * fit.target, options.lower_hz, options.upper_hz, fit.branches, options.points,
             damping::to_string(options.ordering));
  fmt::print("{:>6}  {:>10}  {:>12}  {:>10}  {:>13}\n", "branch", "alpha", "tau [s]", "peak [Hz]", "peak zeta [%]");
  for (int i = 0; i < fit.branches; ++i)
    fmt::print("{:>6}  {:>10.6f}  {:>12.6e}  {:>10.4f}  {:>13.4f}\n", i + 1, fit.branch[i].alpha, fit.branch[i].tau,
               fit.peak_hz(i), 100 * fit.peak_damping_ratio(i));
  fmt::print("\nwithin the band: zeta from {:.4f} % to {:.4f} % (relative error {:+.3f} % / {:+.3f} %)\n",
             100 * fit.zeta_min, 100 * fit.zeta_max, 100 * fit.rel_error_min, 100 * fit.rel_error_max);
  fmt::print("1 + sum alpha = {:.4f}, |M_T| max = {:.4f}, timestep factor 1/sqrt(1 + sum alpha) = {:.4f} (eq. 20)\n",
             1 + fit.sum_alpha, fit.modulus_max, fit.dt_factor);
  fmt::print("Levenberg-Marquardt: {} iterations, {} restarts, {} ({}), {:.1f} us\n", fit.iterations, fit.restarts,
             fit.converged ? "converged" : "NOT converged", solve::to_string(fit.status), 1e6 * solve_seconds);
}

void print_csv(const MaxwellFitResult& fit) {
  fmt::print("branch,alpha,tau_s,peak_hz,peak_zeta\n");
  for (int i = 0; i < fit.branches; ++i)
    fmt::print("{},{},{},{},{}\n", i + 1, fit.branch[i].alpha, fit.branch[i].tau, fit.peak_hz(i),
               fit.peak_damping_ratio(i));
}

/// 3DEC v9 takes the peak damping ratio and peak frequency of each branch.
void print_3dec(const MaxwellFitResult& fit) {
  std::string line = "block mechanical damping maxwell";
  for (int i = 0; i < fit.branches; ++i) line += fmt::format(" {:.6g} {:.6g}", fit.peak_damping_ratio(i), fit.peak_hz(i));
  fmt::print("{}\n", line);
}

/// Frequency, target, Maxwell, mass-proportional and Rayleigh damping ratios and |M_T| over a decade beyond the band.
void write_curve(const std::string& path, const MaxwellFitResult& fit, const damping::MaxwellFitOptions& options,
                 double mass_centre_hz, const std::vector<double>& rayleigh_hz) {
  const auto mass = damping::MassProportional::from_damping_ratio(fit.target, mass_centre_hz);
  const auto rayleigh =
      damping::Rayleigh::from_two_frequencies(fit.target, rayleigh_hz[0], fit.target, rayleigh_hz[1]);
  io::write_atomically(path, [&](std::ostream& out) {
    out << "frequency_hz,target,maxwell,mass_proportional,rayleigh,modulus\n";
    const double lo = std::log(options.lower_hz / 10.0);
    const double hi = std::log(options.upper_hz * 10.0);
    constexpr int n = 400;
    for (int j = 0; j <= n; ++j) {
      const double f = std::exp(lo + (hi - lo) * j / n);
      const double w = angular_frequency(f);
      const auto m = damping::complex_modulus(fit.active(), w);
      out << fmt::format("{},{},{},{},{},{}\n", f, fit.target, m.damping_ratio(), mass.damping_ratio(w),
                         rayleigh.damping_ratio(w), m.magnitude());
    }
  });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Fit Maxwell damping branches to a flat damping ratio over a frequency band (blockdem)"};
  damping::MaxwellFitOptions options;
  std::vector<double> band{options.lower_hz, options.upper_hz};
  std::string format = "table";
  std::string curve;
  std::string ordering = "cumulative";
  double tolerance = 0.0;
  double mass_centre_hz = 0.0;
  std::vector<double> rayleigh_hz;

  app.add_option("--zeta", options.damping_ratio, "target damping ratio zeta*, in (0, 0.5)")->capture_default_str();
  app.add_option("--band", band, "frequency band f_lb f_ub in Hz")->expected(2)->capture_default_str();
  auto* branches = app.add_option("--branches", options.branches, "number of Maxwell branches N, 1..8")
                       ->capture_default_str();
  app.add_option("--points", options.points, "log-spaced evaluation frequencies M (eq. 21), 10..100000")
      ->capture_default_str();
  app.add_option("--tolerance", tolerance,
                 "max relative error over the band; without --branches, the smallest N that meets it is chosen");
  app.add_option("--format", format, "output: table, json, csv or 3dec")
      ->check(CLI::IsMember({"table", "json", "csv", "3dec"}))
      ->capture_default_str();
  app.add_option("--curve", curve, "write frequency, target, Maxwell, mass-proportional and Rayleigh damping ratios "
                                   "and |M_T| to this CSV file");
  app.add_option("--ordering", ordering, "branch ordering map: cumulative, or literal (eq. 23-24 as printed)")
      ->check(CLI::IsMember({"cumulative", "literal"}))
      ->capture_default_str();
  app.add_option("--centre-margin", options.centre_margin,
                 "branch peaks are placed in [f_lb/margin, f_ub*margin], 1..100 (1 = eq. 25 as printed)")
      ->capture_default_str();
  app.add_option("--max-restarts", options.max_restarts, "random restarts when a solve does not converge, 0..100")
      ->capture_default_str();
  app.add_option("--seed", options.seed, "seed of the restarts")->capture_default_str();
  app.add_option("--mass-centre", mass_centre_hz,
                 "--curve: centre frequency (Hz) of the mass-proportional curve (default: sqrt(f_lb f_ub))");
  app.add_option("--rayleigh", rayleigh_hz, "--curve: the two frequencies (Hz) of the Rayleigh curve (default: the band)")
      ->expected(2);

  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;

  try {
    options.lower_hz = band[0];
    options.upper_hz = band[1];
    options.ordering = ordering == "literal" ? damping::OrderingMap::literal_eq23 : damping::OrderingMap::cumulative;
    options.validate();
    if (tolerance != 0.0 && !(tolerance > 0.0 && tolerance < 1.0))
      throw InvalidArgument("--tolerance must be in (0, 1) (a relative error, e.g. 0.01)");
    if (mass_centre_hz == 0.0) mass_centre_hz = std::sqrt(options.lower_hz * options.upper_hz);
    if (!(mass_centre_hz > 0.0)) throw InvalidArgument("--mass-centre must be > 0 Hz");
    if (rayleigh_hz.empty()) rayleigh_hz = {options.lower_hz, options.upper_hz};

    const auto start = std::chrono::steady_clock::now();
    const bool choose_branches = tolerance > 0.0 && branches->count() == 0;
    const auto fit = choose_branches ? damping::fit_maxwell_to_tolerance(options, tolerance) : damping::fit_maxwell(options);
    const double solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    options.branches = fit.branches;

    if (!curve.empty()) write_curve(curve, fit, options, mass_centre_hz, rayleigh_hz);
    if (format == "json") {
      fmt::print("{}\n", to_json(fit, solve_seconds, options, tolerance));
    } else if (format == "csv") {
      print_csv(fit);
    } else if (format == "3dec") {
      print_3dec(fit);
    } else {
      print_table(fit, solve_seconds, options);
      if (tolerance > 0.0 && fit.max_rel_error > tolerance)
        fmt::print("note: {} branches do not meet the tolerance {:g} (max relative error {:.4f})\n", fit.branches,
                   tolerance, fit.max_rel_error);
    }
    if (!fit.converged) {  // a fit that failed must not look like a result
      std::fprintf(stderr, "maxwell_fit: error: the fit did not converge (%s); the best point found, shown above, is "
                   "not a fit of the band: exit status 1\n", solve::to_string(fit.status));
      return 1;
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "maxwell_fit: error: %s\n", e.what());
    return exit_bad_input;
  }
  return 0;
}
