#pragma once
// SplitMix64 (Steele, Lea and Flood 2014): a small, fixed, portable random stream, usable in constant expressions.
// The standard library's distributions are not portable across implementations; blockdem's results must be.

#include <cstdint>

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/units.hpp"

namespace blockdem {

class SplitMix64 {
 public:
  constexpr explicit SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  constexpr std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in (0, 1).
  constexpr double uniform() noexcept { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }
  /// Uniform in (-1, 1).
  constexpr double uniform_symmetric() noexcept { return 2.0 * uniform() - 1.0; }
  /// Standard normal (Box-Muller).
  double normal() {
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    return r * std::cos(two_pi * uniform());
  }

 private:
  std::uint64_t state_;
};

}  // namespace blockdem
