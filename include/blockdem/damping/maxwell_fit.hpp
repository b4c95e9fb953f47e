#pragma once
// Fit of N Maxwell branches to a flat damping ratio zeta* over a band [f_lb, f_ub] (paper Sect. 4.2.3, eq. 21-25):
// Levenberg-Marquardt on M log-spaced frequencies, branch centre frequencies kept ordered inside the band by a
// stick-breaking map of unconstrained variables, stiffness fractions kept positive by alpha = exp(rho). A branch's
// centre is its peak frequency (eq. 17), the frequency 3DEC takes for it: with 3 branches the optimum has all three
// peaks inside the band, whereas the top 1/tau_r lies above it.
//
// The map of eq. 23-24 as printed places centre r at w_lb^t_r w_ub^(1 - t_r) with stick-breaking pieces t_r that sum
// to less than 1: at most one centre can lie in the lower half of the band and the log-uniform start cannot be
// represented, so the fit stalls in a poor local optimum. The default map uses the cumulative positions
// s_r = t_1 + ... + t_r, strictly increasing in (0, 1), and w_r = w_lb^(1 - s_r) w_ub^s_r (DESIGN.md §5). The
// literal map is kept (OrderingMap::literal_eq23) so that the difference can be shown.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/random.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/solve/levenberg_marquardt.hpp"

namespace blockdem::damping {

inline constexpr int max_maxwell_branches = 8;

enum class OrderingMap {
  cumulative,    ///< s_r = t_1 + ... + t_r, w_r = w_lb^(1 - s_r) w_ub^s_r: ordered, covers the band (default)
  literal_eq23,  ///< t_r of eq. 23, w_r = w_lb^t_r w_ub^(1 - t_r) as eq. 24 prints it (for comparison only)
};

constexpr const char* to_string(OrderingMap map) noexcept {
  return map == OrderingMap::cumulative ? "cumulative" : "literal_eq23";
}

/// The solver settings of the paper (Sect. 4.2.3): gradient tolerance 1e-9, at most 200 iterations.
constexpr solve::Options paper_solver_options() noexcept {
  solve::Options options;
  options.gradient_tolerance = 1e-9;
  options.max_iterations = 200;
  return options;
}

struct MaxwellFitOptions {
  double damping_ratio = 0.03;  ///< target zeta*, in (0, 0.5)
  double lower_hz = 1.0;        ///< band lower bound f_lb, Hz, > 0
  double upper_hz = 40.0;       ///< band upper bound f_ub, Hz, > f_lb
  int branches = 3;             ///< N, 1..8
  int points = 500;             ///< M log-spaced evaluation frequencies (eq. 21), 10..100000
  OrderingMap ordering = OrderingMap::cumulative;
  /// The branch peak frequencies (eq. 17) are placed in [f_lb / margin, f_ub * margin], [1, 100]. A margin of 1 is
  /// eq. 25 as printed; it is enough for 3 branches but stops 4 or more from flattening the curve, because their
  /// flattest fit puts the outer peaks outside the band (4 % over 1-40 Hz: -2.8 % error at margin 1, 0.36 % at 2).
  double centre_margin = 2.0;
  int max_restarts = 3;         ///< random restarts when a solve does not converge, 0..100; the best is kept
  std::uint64_t seed = 20240;   ///< for the restarts; the fit is deterministic for a given seed
  solve::Options solver = paper_solver_options();

  /// Throws InvalidArgument naming the field and its allowed range.
  constexpr void validate() const {
    auto fail = [](const char* what) { throw InvalidArgument(std::string("maxwell fit: ") + what); };
    if (!(damping_ratio > 0.0 && damping_ratio < 0.5)) fail("damping ratio (zeta) must be in (0, 0.5)");
    if (!(lower_hz > 0.0) || !cmath::isfinite(lower_hz)) fail("band lower frequency f_lb must be > 0 Hz");
    if (!(upper_hz > lower_hz) || !cmath::isfinite(upper_hz)) fail("band must satisfy f_lb < f_ub (Hz)");
    if (!(lower_hz >= 1e-3 && upper_hz <= 1e4)) fail("band must lie within [0.001, 10000] Hz");
    if (!(upper_hz <= 1e6 * lower_hz)) fail("band must span at most 6 decades (f_ub <= 1e6 f_lb)");
    if (branches < 1 || branches > max_maxwell_branches) fail("branches (N) must be in 1..8");
    if (!(centre_margin >= 1.0 && centre_margin <= 100.0)) fail("centre margin must be in [1, 100]");
    if (points < 10 || points > 100000) fail("points (M) must be in 10..100000");
    if (max_restarts < 0 || max_restarts > 100) fail("max restarts must be in 0..100");
    if (!(solver.max_iterations >= 1)) fail("solver max iterations must be >= 1");
  }
};

/// A fitted (or given) set of branches and how well it meets the target.
struct MaxwellFitResult {
  int branches = 0;
  std::array<MaxwellBranch, max_maxwell_branches> branch{};
  double target = 0.0;         ///< zeta*
  double zeta_min = 0.0;       ///< min of zeta over the M evaluation frequencies of the band
  double zeta_max = 0.0;       ///< max of zeta over the band
  double rel_error_min = 0.0;  ///< min of (zeta - zeta*) / zeta* over the band (signed)
  double rel_error_max = 0.0;  ///< max of (zeta - zeta*) / zeta* over the band (signed)
  double max_rel_error = 0.0;  ///< max |zeta - zeta*| / zeta* over the band
  double sum_alpha = 0.0;      ///< sum alpha_i
  double dt_factor = 1.0;      ///< 1 / sqrt(1 + sum alpha) (eq. 20)
  double modulus_max = 1.0;    ///< sup over omega of |M_T| (eq. 18-19)
  int iterations = 0;          ///< LM steps of the retained solve
  int total_iterations = 0;    ///< LM steps over all attempts
  int restarts = 0;            ///< random restarts made
  bool converged = false;      ///< the retained solve met a convergence test
  solve::Status status = solve::Status::max_iterations_reached;
  double cost = 0.0;           ///< 1/2 sum (zeta_j - zeta*)^2 at the result (eq. 22 / 2)

  constexpr std::span<const MaxwellBranch> active() const noexcept {
    return {branch.data(), static_cast<std::size_t>(branches)};
  }
  /// Peak frequency of branch i alone (eq. 17), Hz.
  constexpr double peak_hz(int i) const noexcept { return frequency_hz(branch[i].peak_angular_frequency()); }
  /// Peak damping ratio of branch i alone (eq. 17).
  constexpr double peak_damping_ratio(int i) const noexcept { return branch[i].peak_damping_ratio(); }
};

/// omega_j = omega_lb (omega_ub / omega_lb)^((j - 1) / (M - 1)), j = 1..M (eq. 21), rad/s.
constexpr std::vector<double> evaluation_frequencies(double lower_hz, double upper_hz, int points) {
  std::vector<double> omega(static_cast<std::size_t>(points));
  const double log_lb = cmath::log(angular_frequency(lower_hz));
  const double log_ub = cmath::log(angular_frequency(upper_hz));
  const double log_step = (log_ub - log_lb) / (points - 1);
  for (std::size_t j = 0; j < omega.size(); ++j) omega[j] = cmath::exp(log_lb + log_step * static_cast<double>(j));
  omega[0] = angular_frequency(lower_hz);  // exact band ends
  omega[omega.size() - 1] = angular_frequency(upper_hz);
  return omega;
}

/// Fills in the band statistics of `result` from its branches.
constexpr void evaluate_fit(MaxwellFitResult& result, const std::vector<double>& omega) {
  const auto branches = result.active();
  result.zeta_min = 1e300;
  result.zeta_max = -1e300;
  for (double w : omega) {
    const double z = damping_ratio(branches, w);
    result.zeta_min = cmath::min(result.zeta_min, z);
    result.zeta_max = cmath::max(result.zeta_max, z);
  }
  result.rel_error_min = (result.zeta_min - result.target) / result.target;
  result.rel_error_max = (result.zeta_max - result.target) / result.target;
  result.max_rel_error = cmath::max(-result.rel_error_min, result.rel_error_max);
  result.sum_alpha = stiffness_factor(branches) - 1.0;
  result.dt_factor = timestep_factor(branches);
  // |M_T| tends to 1 + sum alpha as omega -> infinity; scan well beyond the band in case it overshoots on the way.
  result.modulus_max = 1.0 + result.sum_alpha;
  constexpr int scan_points = 600;
  const double ratio = cmath::exp(cmath::log(omega.back() / omega.front() * 1e6) / scan_points);
  double w = omega.front() * 1e-3;
  for (int j = 0; j <= scan_points; ++j, w *= ratio)
    result.modulus_max = cmath::max(result.modulus_max, complex_modulus(branches, w).magnitude());
}

/// The band statistics of branches that were not fitted here (for example read from a 3DEC data file).
constexpr MaxwellFitResult evaluate_branches(std::span<const MaxwellBranch> branches, double target, double lower_hz,
                                             double upper_hz, int points = 500) {
  if (branches.empty() || branches.size() > max_maxwell_branches)
    throw InvalidArgument("maxwell fit: between 1 and 8 branches can be evaluated");
  MaxwellFitResult result;
  result.branches = static_cast<int>(branches.size());
  for (std::size_t i = 0; i < branches.size(); ++i) result.branch[i] = branches[i];
  result.target = target;
  evaluate_fit(result, evaluation_frequencies(lower_hz, upper_hz, points));
  return result;
}

namespace detail {

/// The least-squares problem of eq. 22, residuals zeta(omega_j) - zeta*.
/// Parameters: x[r] = nu_r (ordering map, eq. 23), x[N + r] = rho_r = log alpha_r.
template <int N>
class MaxwellFitProblem {
 public:
  static constexpr int num_parameters = 2 * N;
  using Parameters = solve::Vector<2 * N>;

  struct State {
    std::array<double, N> alpha{};
    std::array<double, N> tau{};
    std::array<std::array<double, N>, N> dlogw{};  // d log(omega_r) / d nu_k, zero for k > r
    std::array<double, N> dlogtau_drho{};          // d log(tau_r) / d rho_r = -alpha / (2 (1 + alpha))
  };

  constexpr MaxwellFitProblem(const MaxwellFitOptions& options)
      : omega_(evaluation_frequencies(options.lower_hz, options.upper_hz, options.points)),
        target_(options.damping_ratio),
        log_lb_(cmath::log(angular_frequency(options.lower_hz / options.centre_margin))),
        log_ub_(cmath::log(angular_frequency(options.upper_hz * options.centre_margin))),
        ordering_(options.ordering) {}

  constexpr int num_residuals() const { return static_cast<int>(omega_.size()); }
  constexpr const std::vector<double>& omega() const { return omega_; }

  constexpr State prepare(const Parameters& x) const {
    State s;
    const double band = log_ub_ - log_lb_;
    double log_rest = 0.0;  // log prod_{k<r} (1 - sigma(nu_k)) = -sum_{k<r} softplus(nu_k)
    for (int r = 0; r < N; ++r) {
      const double sigma = cmath::sigmoid(x[r]);
      double log_omega = 0.0;
      if (ordering_ == OrderingMap::cumulative) {
        log_rest -= cmath::softplus(x[r]);  // now includes k = r: 1 - s_r
        const double rest = cmath::exp(log_rest);
        log_omega = log_lb_ + (1.0 - rest) * band;
        for (int k = 0; k <= r; ++k) s.dlogw[r][k] = band * rest * cmath::sigmoid(x[k]);  // ds_r/dnu_k = (1-s_r) sigma_k
      } else {
        const double t = sigma * cmath::exp(log_rest);  // eq. 23
        log_omega = log_ub_ - t * band;                  // eq. 24: w_lb^t w_ub^(1-t)
        for (int k = 0; k < r; ++k) s.dlogw[r][k] = band * t * cmath::sigmoid(x[k]);
        s.dlogw[r][r] = -band * t * (1.0 - sigma);
        log_rest -= cmath::softplus(x[r]);
      }
      // omega_r is the branch's peak frequency (eq. 17): tau_r = 1 / (omega_r sqrt(1 + alpha_r)).
      s.alpha[r] = cmath::exp(x[N + r]);
      s.tau[r] = cmath::exp(-log_omega) / cmath::sqrt(1.0 + s.alpha[r]);
      s.dlogtau_drho[r] = -0.5 * s.alpha[r] / (1.0 + s.alpha[r]);
    }
    return s;
  }

  // With d_r = 1 + x_r^2, x_r = tau_r w and e_r = prod_{k != r} d_k, multiplying M_T by P = prod d_k removes the N
  // divisions of eq. 19: Re' = P + sum alpha_r x_r^2 e_r, Im' = sum alpha_r x_r e_r, zeta = Im' / (2 Re').
  // P <= (1 + x_max^2)^8 stays far below the overflow for the bands validate() allows (6 decades within 1e-3..1e4 Hz).
  constexpr double residual(const State& s, int j) const {
    const Row row = evaluate_row(s, j);
    return 0.5 * row.im / row.re - target_;
  }

  constexpr double residual(const State& s, int j, Parameters& gradient) const {
    const Row row = evaluate_row(s, j);
    const auto& x = row.x;
    const auto& e = row.e;
    const double re = row.re;
    const double im = row.im;
    const double p = row.p;
    const double inv_re = 1.0 / re;
    const double inv_p = 1.0 / p;
    const double zeta = 0.5 * im * inv_re;
    // d residual = (dIm - 2 zeta dRe) / (2 Re) with Re, Im the parts of M_T.
    const double c = 0.5 * inv_re;
    std::array<double, N> dlogx{};  // d residual / d log(x_r)
    for (int r = 0; r < N; ++r) {
      const double ax = s.alpha[r] * x[r] * e[r] * c;  // alpha x / d_r scaled by P c
      // d/dlog alpha: alpha x / d (1 - 2 zeta x); d/dlog x: alpha x / d^2 ((1 - x^2) - 4 zeta x)
      gradient[N + r] = ax * (1.0 - 2.0 * zeta * x[r]);
      dlogx[r] = ax * e[r] * inv_p * ((1.0 - x[r] * x[r]) - 4.0 * zeta * x[r]);
      gradient[N + r] += dlogx[r] * s.dlogtau_drho[r];
    }
    for (int k = 0; k < N; ++k) {  // log x_r = log w - log omega_r - log(1 + alpha_r) / 2
      double g = 0.0;
      for (int r = k; r < N; ++r) g -= dlogx[r] * s.dlogw[r][k];
      gradient[k] = g;
    }
    return zeta - target_;
  }

 private:
  /// One row: x_r = tau_r w_j, e_r = prod_{k != r} (1 + x_k^2), P = prod (1 + x_k^2), and P Re(M_T), P Im(M_T).
  struct Row {
    std::array<double, N> x{};
    std::array<double, N> e{};
    double p = 1.0;
    double re = 1.0;
    double im = 0.0;
  };

  constexpr Row evaluate_row(const State& s, int j) const {
    Row row;
    row.p = common_denominator(s, omega_[static_cast<std::size_t>(j)], row.x, row.e);
    row.re = row.p;
    for (int r = 0; r < N; ++r) {
      const double ax = s.alpha[r] * row.x[r] * row.e[r];
      row.re += ax * row.x[r];
      row.im += ax;
    }
    return row;
  }

  /// x_r = tau_r w, e_r = prod_{k != r} (1 + x_k^2) by prefix and suffix products; returns P = prod (1 + x_k^2).
  static constexpr double common_denominator(const State& s, double w, std::array<double, N>& x,
                                             std::array<double, N>& e) {
    std::array<double, N> d{};
    for (int r = 0; r < N; ++r) {
      x[r] = s.tau[r] * w;
      d[r] = 1.0 + x[r] * x[r];
    }
    double prefix = 1.0;
    for (int r = 0; r < N; ++r) {
      e[r] = prefix;
      prefix *= d[r];
    }
    double suffix = 1.0;
    for (int r = N - 1; r >= 0; --r) {
      e[r] *= suffix;
      suffix *= d[r];
    }
    return prefix;
  }

  std::vector<double> omega_;
  double target_;  // residuals are zeta - zeta* as eq. 22 prints them, so its gradient tolerance 1e-9 means the same
  double log_lb_;
  double log_ub_;
  OrderingMap ordering_;
};

constexpr double logit(double p) noexcept { return cmath::log(p / (1.0 - p)); }

/// The start of the paper: centres uniform on the log scale (s_r = (r - 1/2)/N), each branch with a peak ratio
/// that lets the N overlapping peaks add up to about zeta*. With the literal map the nearest representable start
/// is taken (its pieces must sum below 1).
template <int N>
constexpr solve::Vector<2 * N> initial_parameters(const MaxwellFitOptions& options) {
  solve::Vector<2 * N> x{};
  double previous = 0.0;  // cumulative: s_{r-1}; literal: prod_{k<r} (1 - sigma_k)
  double remaining = 1.0;
  for (int r = 0; r < N; ++r) {
    const double s = (r + 0.5) / N;
    if (options.ordering == OrderingMap::cumulative) {
      x[r] = logit(1.0 - (1.0 - s) / (1.0 - previous));
      previous = s;
    } else {
      const double t = 1.0 - s;  // eq. 24 puts t = 1 at the lower bound
      const double sigma = cmath::min(cmath::max(t / remaining, 1e-3), 1.0 - 1e-3);
      x[r] = logit(sigma);
      remaining *= 1.0 - sigma;
    }
  }
  const double log_band = cmath::log(options.upper_hz / options.lower_hz);
  // A branch's ratio is sech-shaped on a log-frequency axis with area pi * peak: spread zeta* over the band.
  const double peak = options.damping_ratio * cmath::min(log_band / (N * pi) + 0.5, 1.0);
  const double alpha = MaxwellBranch::from_peak(peak, 1.0).alpha;
  for (int r = 0; r < N; ++r) x[N + r] = cmath::log(alpha);
  return x;
}

template <int N>
constexpr MaxwellFitResult fit_maxwell_branches(const MaxwellFitOptions& options) {
  options.validate();
  const MaxwellFitProblem<N> problem(options);
  const auto start = initial_parameters<N>(options);
  SplitMix64 rng(options.seed);

  solve::Vector<2 * N> best = start;
  solve::Summary best_summary;
  int total_iterations = 0;
  int restarts = 0;
  for (int attempt = 0; attempt <= options.max_restarts; ++attempt) {
    auto x = start;
    if (attempt > 0) {  // a small random restart around the log-uniform start
      ++restarts;
      for (int r = 0; r < N; ++r) {
        x[r] += 0.5 * rng.uniform_symmetric();
        x[N + r] += 0.3 * rng.uniform_symmetric();
      }
    }
    const auto summary = solve::levenberg_marquardt(problem, x, options.solver);
    total_iterations += summary.iterations;
    const bool better = attempt == 0 || (summary.converged() && !best_summary.converged()) ||
                        (summary.converged() == best_summary.converged() && summary.final_cost < best_summary.final_cost);
    if (better) {
      best = x;
      best_summary = summary;
    }
    if (summary.converged()) break;
  }

  MaxwellFitResult result;
  result.branches = N;
  const auto state = problem.prepare(best);
  for (int r = 0; r < N; ++r) result.branch[r] = {state.alpha[r], state.tau[r]};
  result.target = options.damping_ratio;
  result.iterations = best_summary.iterations;
  result.total_iterations = total_iterations;
  result.restarts = restarts;
  result.converged = best_summary.converged();
  result.status = best_summary.status;
  result.cost = best_summary.final_cost;
  evaluate_fit(result, problem.omega());
  return result;
}

}  // namespace detail

/// Fits options.branches Maxwell branches to options.damping_ratio over [options.lower_hz, options.upper_hz].
/// Throws InvalidArgument on options outside their ranges.
constexpr MaxwellFitResult fit_maxwell(const MaxwellFitOptions& options) {
  options.validate();
  switch (options.branches) {
    case 1: return detail::fit_maxwell_branches<1>(options);
    case 2: return detail::fit_maxwell_branches<2>(options);
    case 3: return detail::fit_maxwell_branches<3>(options);
    case 4: return detail::fit_maxwell_branches<4>(options);
    case 5: return detail::fit_maxwell_branches<5>(options);
    case 6: return detail::fit_maxwell_branches<6>(options);
    case 7: return detail::fit_maxwell_branches<7>(options);
    default: return detail::fit_maxwell_branches<8>(options);
  }
}

/// The fit with the smallest number of branches whose max relative error over the band is at most `tolerance`
/// (for example 0.01); if even 8 branches miss it, the 8-branch fit. options.branches is ignored.
constexpr MaxwellFitResult fit_maxwell_to_tolerance(MaxwellFitOptions options, double tolerance) {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw InvalidArgument("maxwell fit: tolerance must be in (0, 1) (a relative error, e.g. 0.01)");
  MaxwellFitResult result;
  for (int n = 1; n <= max_maxwell_branches; ++n) {
    options.branches = n;
    result = fit_maxwell(options);
    if (result.max_rel_error <= tolerance) break;
  }
  return result;
}

/// The compile-time policy built from a fit with exactly N branches.
template <int N>
constexpr Maxwell<N> to_policy(const MaxwellFitResult& fit) {
  if (fit.branches != N) throw InvalidArgument("maxwell fit: the fit has a different number of branches than Maxwell<N>");
  Maxwell<N> policy;
  for (int i = 0; i < N; ++i) policy.branches[static_cast<std::size_t>(i)] = fit.branch[static_cast<std::size_t>(i)];
  return policy;
}

}  // namespace blockdem::damping
