#pragma once
// Four doubles in one vector register, for the fused contact loop, which runs the kinematics of four contacts at a
// time (Simulation::contact_pass_of), and for the Maxwell fields of four contacts (damping::Maxwell::FieldLanes).
// A GCC/Clang vector extension: one AVX register with -mavx (-march=native), two SSE2 halves otherwise.
//
// The vector is wrapped in a struct: without AVX, GCC and Clang warn that a function taking or returning a bare
// 32-byte vector by value has another ABI than with AVX (-Wpsabi), although every one here is inlined; a struct
// holding it is passed in memory either way.

#include <cstddef>

namespace blockdem {

inline constexpr std::size_t lane_count = 4;

/// One mask per lane (all bits set or none).
using LaneMask = long long __attribute__((vector_size(32)));

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

/// Lane by lane: a where `mask` is set, else b.
[[gnu::always_inline]] inline Lanes select(const LaneMask& mask, const Lanes& a, const Lanes& b) { return {mask ? a.v : b.v}; }

/// The 4 x 4 transpose of the rows r0..r3: afterwards r_i holds lane i of the old rows (lane j from r_j).
[[gnu::always_inline]] inline void transpose(Lanes& r0, Lanes& r1, Lanes& r2, Lanes& r3) {
  const Lanes::Vector t0 = __builtin_shufflevector(r0.v, r1.v, 0, 4, 2, 6), t1 = __builtin_shufflevector(r0.v, r1.v, 1, 5, 3, 7);
  const Lanes::Vector t2 = __builtin_shufflevector(r2.v, r3.v, 0, 4, 2, 6), t3 = __builtin_shufflevector(r2.v, r3.v, 1, 5, 3, 7);
  r0.v = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  r1.v = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  r2.v = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  r3.v = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

}  // namespace blockdem
