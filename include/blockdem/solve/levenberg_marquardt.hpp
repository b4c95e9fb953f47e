#pragma once
// A small fixed-size Levenberg-Marquardt solver for nonlinear least squares, min 1/2 sum_i r_i(x)^2, that allocates
// nothing and runs in constant expressions. The number of parameters N is a compile-time constant; residuals are
// evaluated row by row and folded straight into the N x N normal equations, so the memory is O(N^2) whatever the
// number of residuals. The algorithm is the one of Ceres' tiny_solver (Jacobi column scaling fixed at the start,
// Marquardt's diagonal regularisation, Nielsen's update of the damping parameter), with MINPACK's relative
// cost-change test added.

#include <array>
#include <concepts>
#include <cstddef>
#include <limits>
#include <utility>

#include "blockdem/core/constexpr_math.hpp"

namespace blockdem::solve {

template <int N>
using Vector = std::array<double, static_cast<std::size_t>(N)>;

/// A least-squares problem with a compile-time number of parameters, evaluated row by row:
/// - `static constexpr int num_parameters` (N >= 1);
/// - `int num_residuals() const` (>= 1);
/// - `State prepare(const Vector<N>& x) const`: whatever the rows share at x (for example mapped parameters),
///   computed once per point; it may simply be x itself;
/// - `double residual(const State&, int i) const`: the residual r_i(x), i in [0, num_residuals()).
/// A problem that also provides `double residual(const State&, int i, Vector<N>& gradient) const`, writing row i of
/// the Jacobian dr_i/dx into `gradient`, gets the analytic Jacobian; otherwise central differences are used.
/// Every member may be constexpr; then so is the whole solve.
template <class P>
concept LeastSquaresProblem = requires(const P& problem, const Vector<P::num_parameters>& x, int i) {
  requires P::num_parameters >= 1;
  { problem.num_residuals() } -> std::convertible_to<int>;
  { problem.residual(problem.prepare(x), i) } -> std::convertible_to<double>;
};

template <class P>
concept HasAnalyticJacobian =
    LeastSquaresProblem<P> &&
    requires(const P& problem, const Vector<P::num_parameters>& x, Vector<P::num_parameters>& gradient, int i) {
      { problem.residual(problem.prepare(x), i, gradient) } -> std::convertible_to<double>;
    };

/// Why the solve stopped. Below, cost = 1/2 ||r(x)||^2, g = D J^T r the column-scaled gradient (D fixed at the
/// start, D_k = 1 / (1 + ||J_k||) with J_k column k of the first Jacobian) and dx the step in x.
enum class Status {
  gradient_too_small,       ///< converged: max_k |g_k| <= gradient_tolerance
  relative_step_too_small,  ///< converged: ||dx|| <= parameter_tolerance * (||x|| + parameter_tolerance)
  cost_change_too_small,    ///< converged: an accepted step had actual and predicted cost reductions both
                            ///< <= function_tolerance * cost (MINPACK's ftol test)
  cost_too_small,           ///< converged: cost <= cost_threshold
  max_iterations_reached,   ///< not converged: max_iterations steps were tried
  damping_too_large,        ///< not converged: every step was rejected until mu > 1e32 (no descent is possible
                            ///< in floating point, e.g. the cost is not finite around x)
  non_finite_start,         ///< failed: the residuals or the Jacobian at the starting point are not finite
};

/// True for the statuses that mean a (local) minimum was reached.
constexpr bool converged(Status status) noexcept {
  return status == Status::gradient_too_small || status == Status::relative_step_too_small ||
         status == Status::cost_change_too_small || status == Status::cost_too_small;
}

constexpr const char* to_string(Status status) noexcept {
  switch (status) {
    case Status::gradient_too_small: return "gradient_too_small";
    case Status::relative_step_too_small: return "relative_step_too_small";
    case Status::cost_change_too_small: return "cost_change_too_small";
    case Status::cost_too_small: return "cost_too_small";
    case Status::max_iterations_reached: return "max_iterations_reached";
    case Status::damping_too_large: return "damping_too_large";
    case Status::non_finite_start: return "non_finite_start";
  }
  return "unknown";
}

struct Options {
  double gradient_tolerance = 1e-10;          ///< on max_k |g_k|, see Status::gradient_too_small
  double parameter_tolerance = 1e-12;         ///< see Status::relative_step_too_small
  double function_tolerance = 1e-14;          ///< see Status::cost_change_too_small
  double cost_threshold = 0.0;                ///< see Status::cost_too_small
  double initial_trust_region_radius = 1e4;   ///< mu_0 = 1 / radius (tiny_solver's default)
  int max_iterations = 200;                   ///< steps tried, accepted or not
  double numeric_relative_step = 6.0554544523933395e-06;  ///< central differences: h_k = step * max(|x_k|, 1)
                                                           ///< (cube root of the machine epsilon)
};

struct Summary {
  double initial_cost = -1.0;       ///< 1/2 ||r(x0)||^2
  double final_cost = -1.0;         ///< 1/2 ||r(x)||^2 at the returned x
  double gradient_max_norm = -1.0;  ///< max_k |g_k| at the returned x
  int iterations = 0;               ///< steps tried (accepted and rejected)
  int accepted_steps = 0;
  int residual_evaluations = 0;     ///< passes over all residuals without the Jacobian
  int jacobian_evaluations = 0;     ///< passes over all residuals with the Jacobian
  Status status = Status::max_iterations_reached;

  constexpr bool converged() const noexcept { return solve::converged(status); }
};

namespace detail {

template <int N>
using Matrix = std::array<Vector<N>, static_cast<std::size_t>(N)>;

/// Solves A y = b for symmetric positive definite A by Cholesky; false if A is not numerically positive definite.
template <int N>
constexpr bool cholesky_solve(Matrix<N> a, const Vector<N>& b, Vector<N>& y) noexcept {
  for (int j = 0; j < N; ++j) {
    double d = a[j][j];
    for (int k = 0; k < j; ++k) d -= a[j][k] * a[j][k];
    if (!(d > 0.0)) return false;
    d = cmath::sqrt(d);
    a[j][j] = d;
    for (int i = j + 1; i < N; ++i) {
      double s = a[i][j];
      for (int k = 0; k < j; ++k) s -= a[i][k] * a[j][k];
      a[i][j] = s / d;
    }
  }
  for (int i = 0; i < N; ++i) {  // L z = b
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= a[i][k] * y[k];
    y[i] = s / a[i][i];
  }
  for (int i = N - 1; i >= 0; --i) {  // L^T y = z
    double s = y[i];
    for (int k = i + 1; k < N; ++k) s -= a[k][i] * y[k];
    y[i] = s / a[i][i];
  }
  return true;
}

template <int N>
constexpr double norm(const Vector<N>& v) noexcept {
  double s = 0.0;
  for (double e : v) s += e * e;
  return cmath::sqrt(s);
}

/// The normal equations J^T J and J^T r, and the cost, accumulated over all rows at one point.
template <int N>
struct Linearization {
  Matrix<N> jtj{};
  Vector<N> jtr{};
  double cost = 0.0;
  bool finite = true;
};

template <LeastSquaresProblem P>
constexpr double cost_at(const P& problem, const Vector<P::num_parameters>& x) {
  const auto state = problem.prepare(x);
  const int m = problem.num_residuals();
  double sum = 0.0;
  for (int i = 0; i < m; ++i) {
    const double r = problem.residual(state, i);
    sum += r * r;
  }
  return 0.5 * sum;
}

template <LeastSquaresProblem P>
constexpr Linearization<P::num_parameters> linearize(const P& problem, const Vector<P::num_parameters>& x,
                                                      const Options& options) {
  constexpr int n = P::num_parameters;
  Linearization<n> lin;
  const int m = problem.num_residuals();
  const auto state = problem.prepare(x);
  Vector<n> row{};
  auto accumulate = [&lin](double r, const Vector<n>& gradient) {
    lin.cost += r * r;
    for (int a = 0; a < n; ++a) {
      lin.jtr[a] += gradient[a] * r;
      for (int b = 0; b <= a; ++b) lin.jtj[a][b] += gradient[a] * gradient[b];
    }
  };
  if constexpr (HasAnalyticJacobian<P>) {
    for (int i = 0; i < m; ++i) {
      const double r = problem.residual(state, i, row);
      accumulate(r, row);
    }
  } else {
    // Central differences: the 2N shifted points are prepared once, then each row is differenced.
    using State = decltype(problem.prepare(x));
    Vector<n> step{};
    for (int k = 0; k < n; ++k) step[k] = options.numeric_relative_step * cmath::max(cmath::abs(x[k]), 1.0);
    auto shifted = [&](int k, double sign) {
      Vector<n> y = x;
      y[k] += sign * step[k];
      return problem.prepare(y);
    };
    auto make_states = [&]<std::size_t... K>(std::index_sequence<K...>, double sign) {
      return std::array<State, sizeof...(K)>{shifted(static_cast<int>(K), sign)...};
    };
    const auto plus = make_states(std::make_index_sequence<static_cast<std::size_t>(n)>{}, +1.0);
    const auto minus = make_states(std::make_index_sequence<static_cast<std::size_t>(n)>{}, -1.0);
    for (int i = 0; i < m; ++i) {
      const double r = problem.residual(state, i);
      for (int k = 0; k < n; ++k)
        row[k] = (problem.residual(plus[k], i) - problem.residual(minus[k], i)) / (2.0 * step[k]);
      accumulate(r, row);
    }
  }
  lin.cost *= 0.5;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < a; ++b) lin.jtj[b][a] = lin.jtj[a][b];
    if (!cmath::isfinite(lin.jtr[a]) || !cmath::isfinite(lin.jtj[a][a])) lin.finite = false;
  }
  if (!cmath::isfinite(lin.cost)) lin.finite = false;
  return lin;
}

}  // namespace detail

/// Minimises 1/2 sum_i r_i(x)^2 from the starting point in `x`, which holds the result on return.
template <LeastSquaresProblem P>
constexpr Summary levenberg_marquardt(const P& problem, Vector<P::num_parameters>& x, const Options& options = {}) {
  constexpr int n = P::num_parameters;
  Summary summary;

  auto lin = detail::linearize(problem, x, options);
  ++summary.jacobian_evaluations;
  summary.initial_cost = lin.cost;
  summary.final_cost = lin.cost;
  if (!lin.finite) {
    summary.status = Status::non_finite_start;
    return summary;
  }

  // Jacobi column scaling D, fixed from the first Jacobian so that the problem seen by the solver does not move.
  Vector<n> scale{};
  for (int k = 0; k < n; ++k) scale[k] = 1.0 / (1.0 + cmath::sqrt(lin.jtj[k][k]));

  // The scaled system: A = D J^T J D, g = D J^T r.
  detail::Matrix<n> a{};
  Vector<n> g{};
  auto load_scaled = [&]() {
    double gmax = 0.0;
    for (int i = 0; i < n; ++i) {
      g[i] = scale[i] * lin.jtr[i];
      gmax = cmath::max(gmax, cmath::abs(g[i]));
      for (int j = 0; j < n; ++j) a[i][j] = scale[i] * lin.jtj[i][j] * scale[j];
    }
    summary.gradient_max_norm = gmax;
  };
  load_scaled();

  if (summary.gradient_max_norm <= options.gradient_tolerance) {
    summary.status = Status::gradient_too_small;
    return summary;
  }
  if (lin.cost <= options.cost_threshold) {
    summary.status = Status::cost_too_small;
    return summary;
  }

  double mu = 1.0 / options.initial_trust_region_radius;  // the damping parameter
  double nu = 2.0;                                         // its growth factor after a rejected step
  summary.status = Status::max_iterations_reached;
  while (summary.iterations < options.max_iterations) {
    ++summary.iterations;

    // (A + mu diag(A)) step = -g, with diag(A) clamped as in tiny_solver.
    detail::Matrix<n> regularized = a;
    for (int k = 0; k < n; ++k) regularized[k][k] += mu * cmath::min(cmath::max(a[k][k], 1e-6), 1e32);
    Vector<n> minus_g{};
    for (int k = 0; k < n; ++k) minus_g[k] = -g[k];
    Vector<n> step{};
    bool accepted = false;
    if (detail::cholesky_solve<n>(regularized, minus_g, step)) {
      Vector<n> dx{};
      for (int k = 0; k < n; ++k) dx[k] = scale[k] * step[k];
      if (detail::norm<n>(dx) <= options.parameter_tolerance * (detail::norm<n>(x) + options.parameter_tolerance)) {
        summary.status = Status::relative_step_too_small;
        break;
      }
      Vector<n> x_new = x;
      for (int k = 0; k < n; ++k) x_new[k] += dx[k];
      // With an analytic Jacobian the trial point is linearised at once: most steps are accepted, and then the
      // separate pass for its cost is saved. Central differences cost 2N passes more, so they check the cost first.
      detail::Linearization<n> trial;
      double cost_new = 0.0;
      if constexpr (HasAnalyticJacobian<P>) {
        trial = detail::linearize(problem, x_new, options);
        ++summary.jacobian_evaluations;
        cost_new = trial.finite ? trial.cost : std::numeric_limits<double>::infinity();
      } else {
        cost_new = detail::cost_at(problem, x_new);
        ++summary.residual_evaluations;
      }

      // Predicted reduction of the linear model: -g.step - 1/2 step.A.step.
      double predicted = 0.0;
      for (int i = 0; i < n; ++i) {
        double a_step = 0.0;
        for (int j = 0; j < n; ++j) a_step += a[i][j] * step[j];
        predicted -= step[i] * (g[i] + 0.5 * a_step);
      }
      const double actual = lin.cost - cost_new;
      const double rho = actual / predicted;
      if (cmath::isfinite(cost_new) && predicted > 0.0 && rho > 0.0) {
        accepted = true;
        ++summary.accepted_steps;
        const double cost_before = lin.cost;
        x = x_new;
        if constexpr (HasAnalyticJacobian<P>) {
          lin = trial;
        } else {
          lin = detail::linearize(problem, x, options);
          ++summary.jacobian_evaluations;
        }
        load_scaled();
        summary.final_cost = lin.cost;
        if (summary.gradient_max_norm <= options.gradient_tolerance) {
          summary.status = Status::gradient_too_small;
          break;
        }
        if (lin.cost <= options.cost_threshold) {
          summary.status = Status::cost_too_small;
          break;
        }
        if (actual <= options.function_tolerance * cost_before && predicted <= options.function_tolerance * cost_before) {
          summary.status = Status::cost_change_too_small;
          break;
        }
        const double t = 2.0 * rho - 1.0;
        mu *= cmath::max(1.0 / 3.0, 1.0 - t * t * t);  // Nielsen (1999)
        nu = 2.0;
      }
    }
    if (!accepted) {
      mu *= nu;
      nu *= 2.0;
      if (mu > 1e32) {
        summary.status = Status::damping_too_large;
        break;
      }
    }
  }
  summary.final_cost = lin.cost;
  return summary;
}

}  // namespace blockdem::solve
