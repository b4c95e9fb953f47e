#pragma once
// Four NIST StRD nonlinear regression problems with their certified values
// (NIST/ITL Statistical Reference Datasets, https://www.itl.nist.gov/div898/strd/nls/nls_main.shtml):
// Misra1a (lower difficulty), Roszman1 (average), MGH09 and Thurber (higher). Residual r_i = y_i - f(x_i; b).

#include <array>
#include <cmath>
#include <cstddef>

#include "blockdem/solve/levenberg_marquardt.hpp"

namespace blockdem::test {

template <int N, std::size_t M>
struct NistData {
  const char* name;
  std::array<double, M> y;
  std::array<double, M> x;
  std::array<double, N> start_1;
  std::array<double, N> start_2;
  std::array<double, N> certified;
  double certified_residual_sum_of_squares;
};

/// A NIST problem as a blockdem::solve problem: the model gives f(x; b) and, optionally, df/db.
template <int N, std::size_t M, class Model, bool Analytic = true>
struct NistProblem {
  static constexpr int num_parameters = N;
  const NistData<N, M>* data;
  Model model;

  constexpr int num_residuals() const { return static_cast<int>(M); }
  constexpr solve::Vector<N> prepare(const solve::Vector<N>& b) const { return b; }
  constexpr double residual(const solve::Vector<N>& b, int i) const {
    return data->y[static_cast<std::size_t>(i)] - model.value(b, data->x[static_cast<std::size_t>(i)]);
  }
  constexpr double residual(const solve::Vector<N>& b, int i, solve::Vector<N>& gradient) const
    requires Analytic
  {
    model.gradient(b, data->x[static_cast<std::size_t>(i)], gradient);
    for (auto& g : gradient) g = -g;
    return residual(b, i);
  }
};

// y = b1 (1 - exp(-b2 x))
struct Misra1aModel {
  double value(const solve::Vector<2>& b, double x) const { return b[0] * (1.0 - std::exp(-b[1] * x)); }
  void gradient(const solve::Vector<2>& b, double x, solve::Vector<2>& g) const {
    g[0] = 1.0 - std::exp(-b[1] * x);
    g[1] = b[0] * x * std::exp(-b[1] * x);
  }
};
inline constexpr NistData<2, 14> misra1a{
    "Misra1a",
    {10.07, 14.73, 17.94, 23.93, 29.61, 35.18, 40.02, 44.82, 50.76, 55.05, 61.01, 66.40, 75.47, 81.78},
    {77.6, 114.9, 141.1, 190.8, 239.9, 289.0, 332.8, 378.4, 434.8, 477.3, 536.8, 593.1, 689.1, 760.0},
    {500, 0.0001},
    {250, 0.0005},
    {2.3894212918E+02, 5.5015643181E-04},
    1.2455138894E-01};

// y = 1 + b1 - b2 x - arctan(b3 / (x - b4)) / pi
struct Roszman1Model {
  static constexpr double pi = 3.141592653589793238462643383279;
  double value(const solve::Vector<4>& b, double x) const {
    return b[0] - b[1] * x - std::atan(b[2] / (x - b[3])) / pi;
  }
  void gradient(const solve::Vector<4>& b, double x, solve::Vector<4>& g) const {
    const double d = x - b[3];
    const double u = b[2] / d;
    const double s = 1.0 / (pi * (1.0 + u * u));
    g[0] = 1.0;
    g[1] = -x;
    g[2] = -s / d;
    g[3] = -s * b[2] / (d * d);
  }
};
inline constexpr NistData<4, 25> roszman1{
    "Roszman1",
    {0.252429, 0.252141, 0.251809, 0.297989, 0.296257, 0.295319, 0.339603, 0.337731, 0.333820,
     0.389510, 0.386998, 0.438864, 0.434887, 0.427893, 0.471568, 0.461699, 0.461144, 0.513532,
     0.506641, 0.505062, 0.535648, 0.533726, 0.568064, 0.612886, 0.624169},
    {-4868.68, -4868.09, -4867.41, -3375.19, -3373.14, -3372.03, -2473.74, -2472.35, -2469.45,
     -1894.65, -1893.40, -1497.24, -1495.85, -1493.41, -1208.68, -1206.18, -1206.04, -997.92,
     -996.61,  -996.31,  -834.94,  -834.66,  -710.03,  -530.16,  -464.17},
    {0.1, -0.00001, 1000, -100},
    {0.2, -0.000005, 1200, -150},
    {2.0196866396E-01, -6.1953516256E-06, 1.2044556708E+03, -1.8134269537E+02},
    4.9484847331E-04};

// y = b1 (x^2 + x b2) / (x^2 + x b3 + b4)
struct Mgh09Model {
  double value(const solve::Vector<4>& b, double x) const {
    return b[0] * (x * x + x * b[1]) / (x * x + x * b[2] + b[3]);
  }
  void gradient(const solve::Vector<4>& b, double x, solve::Vector<4>& g) const {
    const double num = x * x + x * b[1];
    const double den = x * x + x * b[2] + b[3];
    g[0] = num / den;
    g[1] = b[0] * x / den;
    g[2] = -b[0] * num * x / (den * den);
    g[3] = -b[0] * num / (den * den);
  }
};
inline constexpr NistData<4, 11> mgh09{
    "MGH09",
    {1.957000E-01, 1.947000E-01, 1.735000E-01, 1.600000E-01, 8.440000E-02, 6.270000E-02, 4.560000E-02,
     3.420000E-02, 3.230000E-02, 2.350000E-02, 2.460000E-02},
    {4.000000E+00, 2.000000E+00, 1.000000E+00, 5.000000E-01, 2.500000E-01, 1.670000E-01, 1.250000E-01,
     1.000000E-01, 8.330000E-02, 7.140000E-02, 6.250000E-02},
    {25, 39, 41.5, 39},
    {0.25, 0.39, 0.415, 0.39},
    {1.9280693458E-01, 1.9128232873E-01, 1.2305650693E-01, 1.3606233068E-01},
    3.0750560385E-04};

// y = (b1 + b2 x + b3 x^2 + b4 x^3) / (1 + b5 x + b6 x^2 + b7 x^3)
struct ThurberModel {
  double value(const solve::Vector<7>& b, double x) const {
    return (b[0] + x * (b[1] + x * (b[2] + x * b[3]))) / (1.0 + x * (b[4] + x * (b[5] + x * b[6])));
  }
  void gradient(const solve::Vector<7>& b, double x, solve::Vector<7>& g) const {
    const double num = b[0] + x * (b[1] + x * (b[2] + x * b[3]));
    const double den = 1.0 + x * (b[4] + x * (b[5] + x * b[6]));
    double p = 1.0;
    for (int k = 0; k < 4; ++k, p *= x) g[k] = p / den;
    p = x;
    for (int k = 4; k < 7; ++k, p *= x) g[k] = -num * p / (den * den);
  }
};
inline constexpr NistData<7, 37> thurber{
    "Thurber",
    {80.574,   84.248,   87.264,   87.195,   89.076,   89.608,   89.868,   90.101,   92.405,   95.854,
     100.696,  101.060,  401.672,  390.724,  567.534,  635.316,  733.054,  759.087,  894.206,  990.785,
     1090.109, 1080.914, 1122.643, 1178.351, 1260.531, 1273.514, 1288.339, 1327.543, 1353.863, 1414.509,
     1425.208, 1421.384, 1442.962, 1464.350, 1468.705, 1447.894, 1457.628},
    {-3.067, -2.981, -2.921, -2.912, -2.840, -2.797, -2.702, -2.699, -2.633, -2.481, -2.363, -2.322, -1.501,
     -1.460, -1.274, -1.212, -1.100, -1.046, -0.915, -0.714, -0.566, -0.545, -0.400, -0.309, -0.109, -0.103,
     0.010,  0.119,  0.377,  0.790,  0.963,  1.006,  1.115,  1.572,  1.841,  2.047,  2.200},
    {1000, 1000, 400, 40, 0.7, 0.3, 0.03},
    {1300, 1500, 500, 75, 1, 0.4, 0.05},
    {1.2881396800E+03, 1.4910792535E+03, 5.8323836877E+02, 7.5416644291E+01, 9.6629502864E-01,
     3.9797285797E-01, 4.9727297349E-02},
    5.6427082397E+03};

}  // namespace blockdem::test
