#pragma once
// Baseline correction of an acceleration record: mean removal, least-squares polynomial detrend and zero-phase
// Butterworth high-pass filtering, alone or chained ("mean,highpass:0.1").

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/butterworth.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

/// Subtracts the least-squares polynomial of the given order (0..10) in time from the acceleration; order 0 removes
/// the mean. The fit uses Legendre polynomials of the time scaled to [-1, 1], which keeps it well conditioned.
inline Record detrend_polynomial(Record record, int order) {
  if (order < 0 || order > 10)
    throw InvalidArgument("baseline: polynomial order " + std::to_string(order) + " is outside 0..10");
  record.validate("baseline");
  const auto n = static_cast<Eigen::Index>(record.size());
  Eigen::MatrixXd basis(n, order + 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = n > 1 ? 2.0 * static_cast<double>(i) / static_cast<double>(n - 1) - 1.0 : 0.0;
    basis(i, 0) = 1.0;
    if (order >= 1) basis(i, 1) = x;
    for (int k = 2; k <= order; ++k)  // (k) P_k = (2k - 1) x P_{k-1} - (k - 1) P_{k-2}
      basis(i, k) = ((2.0 * k - 1.0) * x * basis(i, k - 1) - (k - 1.0) * basis(i, k - 2)) / k;
  }
  const Eigen::Map<const Eigen::VectorXd> a(record.acceleration.data(), n);
  const Eigen::VectorXd coefficients = basis.colPivHouseholderQr().solve(a);
  const Eigen::VectorXd trend = basis * coefficients;
  for (Eigen::Index i = 0; i < n; ++i) record.acceleration[static_cast<std::size_t>(i)] -= trend(i);
  return record;
}

inline Record remove_mean(Record record) { return detrend_polynomial(std::move(record), 0); }

/// Zero-phase Butterworth high-pass of the acceleration (corner in Hz, order 1..8). The record is padded with its
/// odd reflection over 1.5 N / (2 f_c) seconds at each end (at most its own length), so the filter's start-up
/// transient stays in the padding (Boore and Bommer 2005).
inline Record highpass(Record record, double corner_hz, int order = 4) {
  record.validate("baseline");
  const ButterworthFilter filter(FilterType::highpass, order, corner_hz, record.dt);
  record.acceleration = filter.filtfilt_record(record.acceleration);
  return record;
}

struct BaselineStep {
  enum class Kind { mean, polynomial, highpass } kind = Kind::mean;
  int order = 0;           // polynomial order, or filter order for highpass
  double corner_hz = 0.0;  // Hz, highpass only
};

inline constexpr const char* baseline_grammar =
    "none, mean, poly:N (N in 0..10), highpass:FC[:ORDER] (FC in Hz, ORDER in 1..8, default 4), "
    "joined by commas, e.g. mean,highpass:0.1";

/// Parses a baseline specification such as "mean", "poly:2", "highpass:0.1:4", "mean,highpass:0.05" or "none".
inline std::vector<BaselineStep> parse_baseline(std::string_view spec) {
  std::vector<BaselineStep> steps;
  const auto fail = [&](std::string_view part, const std::string& why) {
    throw InvalidArgument("baseline: '" + std::string(part) + "' " + why + " (allowed: " + baseline_grammar + ")");
  };
  const auto number = [&](std::string_view part, std::string_view text) {
    std::string s(text);
    char* end = nullptr;
    const double value = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(value)) fail(part, "has a bad number");
    return value;
  };
  // Every comma joins two steps: "mean," or "mean,,highpass:0.1" name an empty one.
  if (!spec.empty() && spec.back() == ',') fail(spec, "ends with a comma, an empty step");
  while (!spec.empty()) {
    const auto comma = spec.find(',');
    const std::string_view part = spec.substr(0, comma);
    spec = comma == std::string_view::npos ? std::string_view{} : spec.substr(comma + 1);
    std::vector<std::string_view> fields;
    for (std::string_view rest = part;;) {
      const auto colon = rest.find(':');
      fields.push_back(rest.substr(0, colon));
      if (colon == std::string_view::npos) break;
      rest = rest.substr(colon + 1);
    }
    const std::string_view kind = fields[0];
    if (kind == "none" && fields.size() == 1) continue;
    if (kind == "mean" && fields.size() == 1) {
      steps.push_back({BaselineStep::Kind::mean, 0, 0.0});
    } else if (kind == "poly" && fields.size() == 2) {
      const double order = number(part, fields[1]);
      if (order != std::floor(order) || order < 0 || order > 10) fail(part, "needs an order in 0..10");
      steps.push_back({BaselineStep::Kind::polynomial, static_cast<int>(order), 0.0});
    } else if (kind == "highpass" && (fields.size() == 2 || fields.size() == 3)) {
      const double corner = number(part, fields[1]);
      if (!(corner > 0.0)) fail(part, "needs a corner frequency > 0 Hz");
      double order = 4;
      if (fields.size() == 3) order = number(part, fields[2]);
      if (order != std::floor(order) || order < 1 || order > 8) fail(part, "needs a filter order in 1..8");
      steps.push_back({BaselineStep::Kind::highpass, static_cast<int>(order), corner});
    } else {
      fail(part, "is not a baseline step");
    }
  }
  return steps;
}

inline std::string to_string(const BaselineStep& step) {
  switch (step.kind) {
    case BaselineStep::Kind::mean: return "mean";
    case BaselineStep::Kind::polynomial: return "poly:" + std::to_string(step.order);
    case BaselineStep::Kind::highpass: {
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "highpass:%g:%d", step.corner_hz, step.order);
      return buffer;
    }
  }
  return "?";
}

inline std::string to_string(const std::vector<BaselineStep>& steps) {
  std::string text;
  for (const auto& step : steps) {
    if (!text.empty()) text += ',';
    text += to_string(step);
  }
  return text.empty() ? "none" : text;
}

/// Applies the steps in order.
inline Record correct_baseline(Record record, const std::vector<BaselineStep>& steps) {
  for (const auto& step : steps) {
    switch (step.kind) {
      case BaselineStep::Kind::mean: record = remove_mean(std::move(record)); break;
      case BaselineStep::Kind::polynomial: record = detrend_polynomial(std::move(record), step.order); break;
      case BaselineStep::Kind::highpass: record = highpass(std::move(record), step.corner_hz, step.order); break;
    }
  }
  return record;
}

}  // namespace blockdem::motion
