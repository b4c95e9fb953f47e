#pragma once
// One elasto-softening contact driven along a displacement path (direct tension, shear under a constant normal stress,
// compression, and cycles of tension or shear): the stress-displacement curve, peak, residual, dissipated energy.

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/contact/softening.hpp"
#include "blockdem/core/error.hpp"

namespace blockdem::analysis {

enum class JointPath { tension, shear, compression, cyclic_tension, cyclic_shear };

inline constexpr std::string_view to_string(JointPath p) noexcept {
  switch (p) {
    case JointPath::tension: return "tension";
    case JointPath::shear: return "shear";
    case JointPath::compression: return "compression";
    case JointPath::cyclic_tension: return "cyclic-tension";
    case JointPath::cyclic_shear: return "cyclic-shear";
  }
  return "?";
}

inline JointPath joint_path_from_string(std::string_view name) {
  for (auto p : {JointPath::tension, JointPath::shear, JointPath::compression, JointPath::cyclic_tension, JointPath::cyclic_shear})
    if (to_string(p) == name) return p;
  throw InvalidArgument("joint test: path '" + std::string(name) +
                        "' is not one of tension, shear, compression, cyclic-tension, cyclic-shear");
}

struct JointTestOptions {
  JointPath path = JointPath::tension;
  contact::ElastoSoftening::Parameters joint = contact::ElastoSoftening::Parameters::from_material();  // Table 1
  double area = 0.01;            // m^2 (0.1 x 0.1 m)
  double normal_stress = 0.5e6;  // Pa, compression positive, held during the shear paths
  /// m, the largest displacement of the driven component (opening, slip or closure); 0: where the strength above
  /// residual has fallen to 1e-6 of its peak.
  double amplitude = 0;
  int steps = 2000;  // of the driven part of the path (a pre-compression adds steps / 10)
  int cycles = 4;    // cyclic paths: amplitudes A/n, 2A/n, ..., A

  void validate() const {
    auto check = [](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument("joint test: " + what);
    };
    check(area > 0 && std::isfinite(area), "area must be > 0 m^2, got " + std::to_string(area));
    check(steps >= 10 && steps <= 10'000'000, "steps must be in 10..10000000, got " + std::to_string(steps));
    check(cycles >= 1 && cycles <= 1000, "cycles must be in 1..1000, got " + std::to_string(cycles));
    check(amplitude >= 0 && amplitude <= 1 && std::isfinite(amplitude),
          "amplitude must be in [0, 1] m (0: to the residual), got " + std::to_string(amplitude));
    check(normal_stress > -joint.tensile_strength && normal_stress < joint.compressive_strength,
          "normal stress must be in (-f_t, f_c) = (" + std::to_string(-joint.tensile_strength) + ", " +
              std::to_string(joint.compressive_strength) + ") Pa, got " + std::to_string(normal_stress));
  }
};

/// One step of the path. Stresses as the joint resists: normal compression positive, shear along +slip positive.
struct JointTestSample {
  double opening = 0;        // m, the gap (positive open)
  double slip = 0;           // m, B relative to A along t1
  double normal_stress = 0;  // Pa, compression positive
  double shear_stress = 0;   // Pa, resisting the slip (positive for positive slip)
  double damage = 0;         // combined damage d
  double dissipated = 0;     // J/m^2, cumulative
  double stored = 0;         // J/m^2
};

struct JointTestResult {
  std::vector<JointTestSample> samples;
  double amplitude = 0;        // m, as used
  double peak_stress = 0;      // Pa, of the driven component (tension positive in the tension paths)
  double expected_peak = 0;    // Pa, f_t, c + sigma tan(phi) or f_c
  double residual_stress = 0;  // Pa, the driven component at the largest displacement (end of the last loading)
  double dissipated = 0;       // J/m^2
  double work = 0;             // J/m^2 done on the joint (trapezoid rule)
  double stored = 0;           // J/m^2 at the end
  double energy_balance_error = 0;  // |work - stored - dissipated| / max(work, dissipated)
  double final_damage = 0;
  bool failed = false;
};

/// Closure (m) at which the joint carries the compressive stress sigma (Pa) on its first loading; a negative sigma
/// gives the (negative) opening of an elastic tension.
inline double closure_for_stress(const contact::ElastoSoftening::Parameters& p, double sigma) {
  const double fc = p.compressive_strength;
  if (sigma <= fc / 3) return sigma / p.normal_stiffness;
  // The hardening parabola sigma = f_c - (2 f_c / 3) ((s_p - s) / (s_p - s_i))^2, solved for s.
  return p.peak_closure - p.hardening_span * std::sqrt((fc - sigma) / (2.0 * fc / 3.0));
}

/// The displacement of the driven component at which its strength above residual is 1e-6 of the peak.
inline double residual_amplitude(const contact::ElastoSoftening::Parameters& p, JointPath path, double normal_stress) {
  const double decades = std::log(1e6);
  switch (path) {
    case JointPath::tension:
    case JointPath::cyclic_tension: return p.tensile_strength / p.normal_stiffness + decades / p.tension_softening_rate;
    case JointPath::compression: return p.peak_closure + decades / p.compression_softening_rate;
    default: {
      const double peak = contact::ElastoSoftening::shear_strength(p, {}, normal_stress);
      return peak / p.shear_stiffness + decades / p.shear_softening_rate;
    }
  }
}

inline JointTestResult run_joint_test(const JointTestOptions& o) {
  o.validate();
  using Law = contact::ElastoSoftening;
  const Law::Parameters& p = o.joint;
  JointTestResult r;
  r.amplitude = o.amplitude > 0 ? o.amplitude : residual_amplitude(p, o.path, o.normal_stress);
  const bool shear_path = o.path == JointPath::shear || o.path == JointPath::cyclic_shear;
  const bool tension_path = o.path == JointPath::tension || o.path == JointPath::cyclic_tension;

  Law::History h{};
  double sigma = 0, tau = 0, slip = 0;
  // The driven component of a sample: tension, compression or shear, as positive numbers for the peak.
  auto driven = [&](const JointTestSample& s) {
    if (shear_path) return s.shear_stress;
    return tension_path ? -s.normal_stress : s.normal_stress;
  };
  auto step = [&](double du_normal, double du_slip) {
    const contact::Response response = Law::update(p, h, du_normal, {du_slip, 0.0});
    // The joint resists closing with sigma and slip with -tau_1.
    r.work += -0.5 * (sigma + response.normal_stress) * du_normal - 0.5 * (tau + response.shear_stress[0]) * du_slip;
    sigma = response.normal_stress;
    tau = response.shear_stress[0];
    slip += du_slip;
    r.dissipated += response.dissipated;
    JointTestSample s{h.gap, slip, sigma, -tau, h.damage, r.dissipated, Law::stored_energy(p, h)};
    r.samples.push_back(s);
    return s;
  };
  /// A straight leg from the current state to (opening, slip) in n steps.
  auto leg = [&](double opening, double to_slip, int n) {
    const double dn = (opening - h.gap) / n, ds = (to_slip - slip) / n;
    JointTestSample last{};
    for (int i = 0; i < n; ++i) {
      last = step(dn, ds);
      r.peak_stress = std::max(r.peak_stress, driven(last));
    }
    return last;
  };
  /// A monotonic leg of `n` steps along the normal (sign -1: closing) or the slip, with a step boundary at the peak
  /// displacement so that the curve passes through the peak itself.
  auto monotonic = [&](double to, double at_peak, bool normal, int n) {
    const int before = std::clamp(static_cast<int>(std::lround(n * at_peak / std::abs(to))), 1, n - 1);
    if (std::abs(to) <= at_peak) return normal ? leg(to, 0, n) : leg(h.gap, to, n);
    const double peak_point = std::copysign(at_peak, to);
    if (normal) {
      leg(peak_point, 0, before);
      return leg(to, 0, n - before);
    }
    leg(h.gap, peak_point, before);
    return leg(h.gap, to, n - before);
  };

  r.samples.reserve(static_cast<std::size_t>(o.steps + o.steps / 10 + 2));
  r.samples.push_back({});
  const double a = r.amplitude;
  const int n_cycle_leg = std::max(2, o.steps / (2 * o.cycles));
  switch (o.path) {
    case JointPath::tension:
      r.expected_peak = p.tensile_strength;
      r.residual_stress = driven(monotonic(a, p.tensile_strength / p.normal_stiffness, true, o.steps));
      break;
    case JointPath::compression:
      r.expected_peak = p.compressive_strength;
      r.residual_stress = driven(monotonic(-a, p.peak_closure, true, o.steps));
      break;
    case JointPath::cyclic_tension: {
      r.expected_peak = p.tensile_strength;
      const double reclose = -p.tensile_strength / p.normal_stiffness;  // closed again to a compression of f_t
      for (int k = 1; k <= o.cycles; ++k) {
        r.residual_stress = driven(leg(a * k / o.cycles, 0, n_cycle_leg));
        leg(reclose, 0, n_cycle_leg);
      }
      leg(0, 0, std::max(1, n_cycle_leg / 4));
      break;
    }
    case JointPath::shear:
    case JointPath::cyclic_shear: {
      const double gap = -closure_for_stress(p, o.normal_stress);
      leg(gap, 0, std::max(1, o.steps / 10));
      r.peak_stress = 0;  // the shear peak only
      r.expected_peak = Law::shear_strength(p, h, sigma);
      if (o.path == JointPath::shear) {
        r.residual_stress = driven(monotonic(a, r.expected_peak / p.shear_stiffness, false, o.steps));
      } else {
        for (int k = 1; k <= o.cycles; ++k) {
          leg(gap, a * k / o.cycles, n_cycle_leg / 2);
          leg(gap, -a * k / o.cycles, n_cycle_leg);
          r.residual_stress = std::abs(r.samples.back().shear_stress);
          leg(gap, 0, n_cycle_leg / 2);
        }
      }
      break;
    }
  }
  r.stored = Law::stored_energy(p, h);
  const double scale = std::max({std::abs(r.work), r.dissipated, 1e-300});
  r.energy_balance_error = std::abs(r.work - r.stored - r.dissipated) / scale;
  r.final_damage = h.damage;
  r.failed = h.failed != 0;
  return r;
}

}  // namespace blockdem::analysis
