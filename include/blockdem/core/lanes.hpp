#pragma once
// Four doubles in one vector register, for the fused contact loop, which runs the kinematics of four contacts at a
// time (contact_pass_of, integrate/contact_pass.hpp), and for the Maxwell fields of four contacts
// (damping::Maxwell::FieldLanes).
// A GCC/Clang vector extension: one AVX register with -mavx (-march=native), two SSE2 halves otherwise.
//
// The vector is wrapped in a struct: without AVX, GCC and Clang warn that a function taking or returning a bare
// 32-byte vector by value has another ABI than with AVX (-Wpsabi), although every one here is inlined; a struct
// holding it is passed in memory either way.

#include <cstddef>

namespace blockdem {

inline constexpr std::size_t lane_count = 4;

/// One flag per lane, as a mask of all bits set or none (a struct for the reason Lanes is).
struct LaneMask {
  using Vector = long long __attribute__((vector_size(32)));
  Vector v;

  /// Lane j set where flag j is true.
  [[gnu::always_inline]] static LaneMask of(bool a, bool b, bool c, bool d) {
    return {Vector{a ? -1LL : 0LL, b ? -1LL : 0LL, c ? -1LL : 0LL, d ? -1LL : 0LL}};
  }
};

struct Lanes {
  using Vector = double __attribute__((vector_size(32)));
  Vector v;

  /// {a, b, c, d}, one value per lane.
  [[gnu::always_inline]] static Lanes of(double a, double b, double c, double d) { return {Vector{a, b, c, d}}; }
  /// {get(0), get(1), get(2), get(3)}.
  template <class Get>
  [[gnu::always_inline]] static Lanes of(Get&& get) {
    return {Vector{get(0), get(1), get(2), get(3)}};
  }
  [[gnu::always_inline]] static Lanes zero() { return {Vector{0.0, 0.0, 0.0, 0.0}}; }

  [[gnu::always_inline]] double operator[](std::size_t j) const { return v[j]; }
  [[gnu::always_inline]] void set(std::size_t j, double x) { v[j] = x; }
  [[gnu::always_inline]] Lanes& operator+=(const Lanes& o) {
    v += o.v;
    return *this;
  }
  [[gnu::always_inline]] Lanes& operator-=(const Lanes& o) {
    v -= o.v;
    return *this;
  }
};

[[gnu::always_inline]] inline Lanes operator+(const Lanes& a, const Lanes& b) { return {a.v + b.v}; }
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a, const Lanes& b) { return {a.v - b.v}; }
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a) { return {-a.v}; }
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, const Lanes& b) { return {a.v * b.v}; }
[[gnu::always_inline]] inline Lanes operator*(double s, const Lanes& a) { return {s * a.v}; }
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, double s) { return {a.v * s}; }

/// Lane by lane: a where `mask` is set, else b. On the bits (and, and-not, or), the same values as the vector
/// conditional `mask ? a : b`, which GCC compiles without AVX to a branch per lane, writing the lanes one at a time to
/// the stack and reading them back in pairs (a store-forwarding stall per pair).
[[gnu::always_inline]] inline Lanes select(const LaneMask& mask, const Lanes& a, const Lanes& b) {
  using Bits = LaneMask::Vector;
  const Bits bits = (__builtin_bit_cast(Bits, a.v) & mask.v) | (__builtin_bit_cast(Bits, b.v) & ~mask.v);
  return {__builtin_bit_cast(Lanes::Vector, bits)};
}

}  // namespace blockdem
