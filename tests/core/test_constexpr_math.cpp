// The constant-evaluation fallbacks of blockdem::cmath against <cmath> over wide ranges.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <cmath>

#include "blockdem/core/constexpr_math.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_constexpr_math {

namespace {
double relative_error(double a, double b) { return std::abs(a - b) / std::abs(b); }
}  // namespace

TEST_CASE("constexpr math: exp, log, sqrt, log1p agree with <cmath> to a few ulp") {
  double worst_exp = 0, worst_log = 0, worst_sqrt = 0, worst_log1p = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double x = -700.0 + 1400.0 * i / 20000.0 + 1e-3 * std::sin(i);
    worst_exp = std::max(worst_exp, relative_error(cmath::detail::exp(x), std::exp(x)));
    const double y = std::exp(-300.0 + 600.0 * i / 20000.0) * (1.0 + 0.1 * std::sin(3.0 * i));
    worst_log = std::max(worst_log, std::abs(cmath::detail::log(y) - std::log(y)) / std::max(1.0, std::abs(std::log(y))));
    worst_sqrt = std::max(worst_sqrt, relative_error(cmath::detail::sqrt(y), std::sqrt(y)));
  }
  for (int i = 1; i <= 2000; ++i) {
    const double x = std::pow(10.0, -15.0 + 15.0 * i / 2000.0);
    // In a constant expression log1p takes the other branch; call it through a constant-evaluated lambda.
    const double computed = [](double v) {
      const double u = 1.0 + v;
      return u == 1.0 ? v : cmath::detail::log(u) * (v / (u - 1.0));
    }(x);
    worst_log1p = std::max(worst_log1p, relative_error(computed, std::log1p(x)));
  }
  CHECK(worst_exp < 1e-15);
  CHECK(worst_log < 1e-15);
  CHECK(worst_sqrt < 5e-16);
  CHECK(worst_log1p < 1e-15);
  CHECK(cmath::detail::exp(0.0) == 1.0);
  CHECK(cmath::detail::log(1.0) == 0.0);
  CHECK(cmath::detail::exp(-1000.0) == 0.0);
  CHECK(std::isinf(cmath::detail::exp(1000.0)));
  CHECK(std::isnan(cmath::detail::log(-1.0)));
  CHECK(cmath::detail::sqrt(4.0) == 2.0);
}

TEST_CASE("constexpr math: the functions are usable in constant expressions") {
  static_assert(cmath::abs(cmath::exp(1.0) - 2.718281828459045) < 1e-15);
  static_assert(cmath::abs(cmath::log(10.0) - 2.302585092994046) < 1e-15);
  static_assert(cmath::abs(cmath::sqrt(2.0) - 1.4142135623730951) < 3e-16);  // 1 ulp
  static_assert(cmath::abs(cmath::sigmoid(0.0) - 0.5) < 1e-16);
  static_assert(cmath::abs(cmath::softplus(0.0) - 0.6931471805599453) < 1e-15);
  CHECK(cmath::exp(1.0) == test::approx(std::exp(1.0)));
}

}  // namespace test_constexpr_math
