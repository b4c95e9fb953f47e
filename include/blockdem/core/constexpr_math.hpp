#pragma once
// exp, log, log1p, sqrt and friends that also work in constant expressions. At run time they call <cmath>; during
// constant evaluation (where std::exp and std::sqrt are not constexpr before C++26) they use the series below,
// accurate to a few ulp, so that a complete least-squares fit can run inside a static_assert.

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace blockdem::cmath {

namespace detail {

inline constexpr double ln2_hi = 6.93147180369123816490e-01;  // ln 2 split so that k * ln2_hi is exact
inline constexpr double ln2_lo = 1.90821492927058770002e-10;
inline constexpr double ln2 = 0.693147180559945309417232121458176568;
inline constexpr double sqrt2 = 1.41421356237309504880168872420969808;

/// 2^k for an integer k in the normal range [-1022, 1023].
constexpr double power_of_two(int k) noexcept {
  return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52);
}

constexpr double exp(double x) noexcept {
  if (x != x) return x;
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.1332191019412) return 0.0;
  // x = k ln2 + r with |r| <= ln2/2, exp(r) by its Taylor series (|r|^21/21! < 1e-26).
  const double kd = x / ln2 + (x < 0 ? -0.5 : 0.5);
  const int k = static_cast<int>(kd);
  const double r = (x - k * ln2_hi) - k * ln2_lo;
  double term = 1.0;
  double sum = 1.0;
  for (int n = 1; n <= 22; ++n) {
    term *= r / n;
    sum += term;
  }
  // Scale in two steps so that results in the subnormal range and 2^1024 overflow are handled.
  if (k > 1023) return sum * power_of_two(1023) * power_of_two(k - 1023);
  if (k < -1022) return sum * power_of_two(-1022) * power_of_two(k + 1022);
  return sum * power_of_two(k);
}

constexpr double log(double x) noexcept {
  if (x != x || x < 0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return -std::numeric_limits<double>::infinity();
  if (x == std::numeric_limits<double>::infinity()) return x;
  int e = 0;
  if (x < std::numeric_limits<double>::min()) {  // subnormal: scale into the normal range first
    x *= power_of_two(54);
    e -= 54;
  }
  const auto bits = std::bit_cast<std::uint64_t>(x);
  e += static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);  // in [1, 2)
  if (m > sqrt2) {
    m *= 0.5;
    ++e;
  }
  // log(m) = 2 atanh(s), s = (m - 1)/(m + 1), |s| <= 0.172: the odd series converges fast.
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double term = s;
  double sum = 0.0;
  for (int n = 1; n <= 41; n += 2) {
    sum += term / n;
    term *= s2;
  }
  return 2.0 * sum + e * ln2_lo + e * ln2_hi;
}

constexpr double sqrt(double x) noexcept {
  if (x != x || x < 0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0 || x == std::numeric_limits<double>::infinity()) return x;
  // Halve the exponent for a starting guess within a factor of 2, then Newton (quadratic convergence).
  double y = std::bit_cast<double>((std::bit_cast<std::uint64_t>(x) >> 1) + (std::uint64_t{1023} << 51));
  for (int i = 0; i < 8; ++i) y = 0.5 * (y + x / y);
  return y;
}

}  // namespace detail

constexpr double abs(double x) noexcept { return x < 0 ? -x : x; }
constexpr double max(double a, double b) noexcept { return a < b ? b : a; }
constexpr double min(double a, double b) noexcept { return b < a ? b : a; }

constexpr double exp(double x) noexcept {
  if (std::is_constant_evaluated()) return detail::exp(x);
  return std::exp(x);
}

constexpr double log(double x) noexcept {
  if (std::is_constant_evaluated()) return detail::log(x);
  return std::log(x);
}

constexpr double sqrt(double x) noexcept {
  if (std::is_constant_evaluated()) return detail::sqrt(x);
  return std::sqrt(x);
}

/// log(1 + x), accurate for small |x|.
constexpr double log1p(double x) noexcept {
  if (std::is_constant_evaluated()) {
    const double u = 1.0 + x;
    if (u == 1.0) return x;
    return detail::log(u) * (x / (u - 1.0));  // corrects the rounding of 1 + x
  }
  return std::log1p(x);
}

/// a^b for a > 0.
constexpr double pow(double a, double b) noexcept {
  if (std::is_constant_evaluated()) return detail::exp(b * detail::log(a));
  return std::pow(a, b);
}

constexpr bool isfinite(double x) noexcept {
  return x == x && x != std::numeric_limits<double>::infinity() && x != -std::numeric_limits<double>::infinity();
}

/// The logistic function 1 / (1 + e^-u), in (0, 1).
constexpr double sigmoid(double u) noexcept {
  if (u >= 0) return 1.0 / (1.0 + exp(-u));
  const double e = exp(u);
  return e / (1.0 + e);
}

/// log(1 + e^u) without overflow.
constexpr double softplus(double u) noexcept { return u > 0 ? u + log1p(exp(-u)) : log1p(exp(u)); }

}  // namespace blockdem::cmath
