#pragma once
// Four doubles at once, for the fused contact loop, which runs the kinematics of four contacts at a time
// (contact_pass_of, integrate/contact_pass.hpp), and for the Maxwell fields of four contacts
// (damping::Maxwell::FieldLanes).
// GCC/Clang vector extensions: one 32-byte vector with AVX (-march=native), two 16-byte SSE2 halves otherwise. A
// 32-byte vector without AVX is split by the compiler, which built some of them through the stack (a broadcast
// stored lane by lane and read back in pairs: a store-forwarding stall each time); the halves are the SSE2
// registers themselves. Every operation is lane by lane, so both forms give the same bits.
//
// The vector is wrapped in a struct: without AVX, GCC and Clang warn that a function taking or returning a bare
// 32-byte vector by value has another ABI than with AVX (-Wpsabi), although every one here is inlined; a struct
// holding it is passed in memory either way. Aligned to 32 bytes in both forms, so that records of lanes
// (damping::Maxwell::FieldLanes) have one layout.

#include <cstddef>

#if defined(__AVX__)
#define BLOCKDEM_LANES_AVX 1
#else
#define BLOCKDEM_LANES_AVX 0
#endif

namespace blockdem {

inline constexpr std::size_t lane_count = 4;

/// One flag per lane, as a mask of all bits set or none (a struct for the reason Lanes is).
struct alignas(32) LaneMask {
#if BLOCKDEM_LANES_AVX
  using Vector = long long __attribute__((vector_size(32)));
  Vector v;
#else
  using Half = long long __attribute__((vector_size(16)));
  Half lo, hi;
#endif

  /// Lane j set where flag j is true.
  [[gnu::always_inline]] static LaneMask of(bool a, bool b, bool c, bool d) {
    const long long x = a ? -1LL : 0LL, y = b ? -1LL : 0LL, z = c ? -1LL : 0LL, w = d ? -1LL : 0LL;
#if BLOCKDEM_LANES_AVX
    return {Vector{x, y, z, w}};
#else
    return {Half{x, y}, Half{z, w}};
#endif
  }
};

struct alignas(32) Lanes {
#if BLOCKDEM_LANES_AVX
  using Vector = double __attribute__((vector_size(32)));
  Vector v;
#else
  using Half = double __attribute__((vector_size(16)));
  Half lo, hi;  // lanes 0 and 1, lanes 2 and 3
#endif

  /// {a, b, c, d}, one value per lane.
  [[gnu::always_inline]] static Lanes of(double a, double b, double c, double d) {
#if BLOCKDEM_LANES_AVX
    return {Vector{a, b, c, d}};
#else
    return {Half{a, b}, Half{c, d}};
#endif
  }
  /// {get(0), get(1), get(2), get(3)}.
  template <class Get>
  [[gnu::always_inline]] static Lanes of(Get&& get) {
    const double a = get(0), b = get(1), c = get(2), d = get(3);
    return of(a, b, c, d);
  }
  [[gnu::always_inline]] static Lanes zero() { return of(0.0, 0.0, 0.0, 0.0); }

  [[gnu::always_inline]] double operator[](std::size_t j) const {
#if BLOCKDEM_LANES_AVX
    return v[j];
#else
    return j < 2 ? lo[j] : hi[j - 2];
#endif
  }
  [[gnu::always_inline]] void set(std::size_t j, double x) {
#if BLOCKDEM_LANES_AVX
    v[j] = x;
#else
    if (j < 2) lo[j] = x;
    else hi[j - 2] = x;
#endif
  }
  [[gnu::always_inline]] Lanes& operator+=(const Lanes& o);
  [[gnu::always_inline]] Lanes& operator-=(const Lanes& o);
};

#if BLOCKDEM_LANES_AVX
[[gnu::always_inline]] inline Lanes operator+(const Lanes& a, const Lanes& b) { return {a.v + b.v}; }
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a, const Lanes& b) { return {a.v - b.v}; }
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a) { return {-a.v}; }
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, const Lanes& b) { return {a.v * b.v}; }
[[gnu::always_inline]] inline Lanes operator*(double s, const Lanes& a) { return {s * a.v}; }
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, double s) { return {a.v * s}; }
#else
[[gnu::always_inline]] inline Lanes operator+(const Lanes& a, const Lanes& b) { return {a.lo + b.lo, a.hi + b.hi}; }
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a, const Lanes& b) { return {a.lo - b.lo, a.hi - b.hi}; }
[[gnu::always_inline]] inline Lanes operator-(const Lanes& a) { return {-a.lo, -a.hi}; }
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, const Lanes& b) { return {a.lo * b.lo, a.hi * b.hi}; }
[[gnu::always_inline]] inline Lanes operator*(double s, const Lanes& a) {
  const Lanes::Half b{s, s};
  return {b * a.lo, b * a.hi};
}
[[gnu::always_inline]] inline Lanes operator*(const Lanes& a, double s) {
  const Lanes::Half b{s, s};
  return {a.lo * b, a.hi * b};
}
#endif

[[gnu::always_inline]] inline Lanes& Lanes::operator+=(const Lanes& o) { return *this = *this + o; }
[[gnu::always_inline]] inline Lanes& Lanes::operator-=(const Lanes& o) { return *this = *this - o; }

/// Lane by lane: a where `mask` is set, else b. On the bits (and, and-not, or), the same values as the vector
/// conditional `mask ? a : b`, which GCC compiles without AVX to a branch per lane, writing the lanes one at a time to
/// the stack and reading them back in pairs (a store-forwarding stall per pair).
[[gnu::always_inline]] inline Lanes select(const LaneMask& mask, const Lanes& a, const Lanes& b) {
#if BLOCKDEM_LANES_AVX
  using Bits = LaneMask::Vector;
  const Bits bits = (__builtin_bit_cast(Bits, a.v) & mask.v) | (__builtin_bit_cast(Bits, b.v) & ~mask.v);
  return {__builtin_bit_cast(Lanes::Vector, bits)};
#else
  using Bits = LaneMask::Half;
  const Bits lo = (__builtin_bit_cast(Bits, a.lo) & mask.lo) | (__builtin_bit_cast(Bits, b.lo) & ~mask.lo);
  const Bits hi = (__builtin_bit_cast(Bits, a.hi) & mask.hi) | (__builtin_bit_cast(Bits, b.hi) & ~mask.hi);
  return {__builtin_bit_cast(Lanes::Half, lo), __builtin_bit_cast(Lanes::Half, hi)};
#endif
}

}  // namespace blockdem
