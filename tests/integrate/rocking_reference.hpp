#pragma once
// An independent reference for the rocking block of analysis/rocking.hpp: the same rigid block on the same springs,
// written here as a planar ODE (x, z, theta of the block in the base's frame, the base's acceleration as a body
// force) and integrated by Boost.Odeint's classical Runge-Kutta at a step a thousand times finer than the contact's
// period. No line of the DEM is used: no contact detection, no central differences, no joint law.
//
// The block (width w along x, height h, depth d, mass m, I = m (w^2 + h^2) / 12 about its centroid) stands on two
// corner springs, the bottom edges at x = -w/2 and +w/2 (each the two contact points of that edge, area w d / 2):
// a normal spring k_n A on the overlap below the base's top (z = 0) and a shear spring k_s A on the displacement
// since the corner touched, capped by Coulomb friction (|shear| <= tan(phi) normal: the spring's anchor slides, the
// return mapping done after each step), both zero while the corner is off the base.

#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace blockdem::test {

struct RockingReference {
  double width = 1, height = 1, depth = 0.5, density = 2000;  // m, kg/m^3
  double stiffness = 1e9;                                     // Pa/m, normal and shear
  double friction = 5.67128181961771;                         // tan(phi), 80 degrees
  double gravity = 9.81;                                      // m/s^2
  std::vector<double> base_acceleration;                      // m/s^2 along x, samples every base_dt from t = 0
  double base_dt = 1e-3;                                      // s
  double duration = 2.0;                                      // s
  double dt = 1e-6;                                           // s, the Runge-Kutta step
  double restitution_rotation = 0.01;                         // rad, as RockingOptions

  struct Result {
    double max_rotation = 0;            // rad
    std::vector<double> restitution;    // per impact, angular velocities after / before, as analyse_rocking
    double slip = 0;                    // m, the corners' slip on the base, summed over the run
  };

  // state: x, z, theta, vx, vz, omega (theta about y, positive turning +z towards +x)
  using State = std::array<double, 6>;

  double base_at(double t) const {
    const double s = t / base_dt;
    const auto i = static_cast<std::size_t>(std::floor(s));
    if (i + 1 >= base_acceleration.size()) return 0.0;
    return base_acceleration[i] + (s - static_cast<double>(i)) * (base_acceleration[i + 1] - base_acceleration[i]);
  }

  Result run() const {
    namespace odeint = boost::numeric::odeint;
    const double m = density * width * height * depth;
    const double inertia = m * (width * width + height * height) / 12;
    const double k = stiffness * width * depth / 2;  // N/m, per bottom edge
    const std::array<double, 2> corner_x{-width / 2, width / 2};
    std::array<double, 2> anchor = corner_x;  // x of each corner where it touched (the shear spring's zero)
    std::array<bool, 2> touching{true, true};
    double slip = 0;

    // Corner position and velocity for the state.
    const auto corner = [&](const State& s, int i, double& cx, double& cz, double& vx, double& vz) {
      const double c = std::cos(s[2]), sn = std::sin(s[2]);
      const double rx = corner_x[static_cast<std::size_t>(i)] * c + (-height / 2) * sn;
      const double rz = -corner_x[static_cast<std::size_t>(i)] * sn + (-height / 2) * c;
      cx = s[0] + rx;
      cz = s[1] + rz;
      vx = s[3] + s[5] * rz;  // omega about y: v = omega x r, (omega_y r_z, -, -omega_y r_x)
      vz = s[4] - s[5] * rx;
    };
    double time = 0;
    const auto rhs = [&](const State& s, State& ds, double t) {
      double fx = -m * base_at(t), fz = -m * gravity, moment = 0;
      for (int i = 0; i < 2; ++i) {
        double cx, cz, vx, vz;
        corner(s, i, cx, cz, vx, vz);
        if (cz >= 0 || !touching[static_cast<std::size_t>(i)]) continue;
        const double normal = -k * cz;
        const double trial = -k * (cx - anchor[static_cast<std::size_t>(i)]);
        const double shear = std::clamp(trial, -friction * normal, friction * normal);
        const double rx = cx - s[0], rz = cz - s[1];
        fx += shear;
        fz += normal;
        moment += rz * shear - rx * normal;  // (r x F)_y = r_z F_x - r_x F_z
      }
      ds = {s[3], s[4], s[5], fx / m, fz / m, moment / inertia};
    };
    // At rest on its springs: each edge carries half the weight.
    State s{0, height / 2 - m * gravity / (2 * k), 0, 0, 0, 0};
    odeint::runge_kutta4<State> stepper;
    Result r;
    const double overturn = std::atan(width / height);
    const double p2 = 3 * gravity / (4 * 0.5 * std::hypot(width, height));
    const auto at_impact = [&](double omega, double theta) {
      return std::sqrt(omega * omega + 2 * p2 * (std::cos(overturn - std::abs(theta)) - std::cos(overturn)));
    };
    double approach = 0, departure_sign = 0;
    const auto steps = static_cast<long long>(std::llround(duration / dt));
    for (long long n = 0; n < steps; ++n) {
      stepper.do_step(rhs, s, time, dt);
      time += dt;
      for (int i = 0; i < 2; ++i) {  // a corner that leaves the base loses its shear spring; one that lands gets one
        double cx, cz, vx, vz;
        corner(s, i, cx, cz, vx, vz);
        const auto j = static_cast<std::size_t>(i);
        if (cz >= 0) touching[j] = false;
        else if (!touching[j]) {
          touching[j] = true;
          anchor[j] = cx;
        }
        const double limit = friction * (-cz);  // the largest |cx - anchor| friction allows (k cancels)
        if (touching[j] && std::abs(cx - anchor[j]) > limit) {  // sliding: the anchor follows at the limit
          const double moved = cx - (cx > anchor[j] ? limit : -limit);
          slip += std::abs(moved - anchor[j]);
          anchor[j] = moved;
        }
      }
      const double theta = s[2];
      r.max_rotation = std::max(r.max_rotation, std::abs(theta));
      if (std::abs(theta) >= restitution_rotation) {
        const double omega = s[5], sign = theta > 0 ? 1.0 : -1.0;
        if (departure_sign != 0 && sign != departure_sign && approach > 0 && omega * sign > 0)
          r.restitution.push_back(at_impact(omega, theta) / approach);
        approach = omega * sign < 0 ? at_impact(omega, theta) : 0.0;
        departure_sign = sign;
      }
    }
    r.slip = slip;
    return r;
  }
};

}  // namespace blockdem::test
