#pragma once
// Physical constants and unit conversions. blockdem is SI throughout: m, kg, s, N, Pa; joint stiffness in Pa/m;
// frequencies in Hz at user interfaces and in rad/s inside the library.

namespace blockdem {

inline constexpr double pi = 3.141592653589793238462643383279502884;
inline constexpr double two_pi = 2.0 * pi;
inline constexpr double standard_gravity = 9.80665;  // m/s^2

/// Frequency in Hz to angular frequency in rad/s.
constexpr double angular_frequency(double frequency_hz) noexcept { return two_pi * frequency_hz; }
/// Angular frequency in rad/s to frequency in Hz.
constexpr double frequency_hz(double angular_frequency) noexcept { return angular_frequency / two_pi; }

}  // namespace blockdem
