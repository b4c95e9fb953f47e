#pragma once
// Inertial relaxation to static equilibrium: the fast inertial relaxation engine (FIRE; Bitzek, Koskinen, Gähler,
// Moseler and Gumbsch, Phys. Rev. Lett. 97, 170201, 2006) on the undamped central-difference step. While the model
// goes downhill (power F.v > 0) it keeps its inertia and its velocity is turned a little towards the force,
// v <- (1 - a) v + a |v| M^-1 F / |M^-1 F| (norms in the mass metric M); the moment it goes uphill (F.v <= 0) every
// velocity is set to zero and it starts again from rest. Only free degrees of freedom take part: the free nodes' translations and
// the free rigid blocks' translations and rotations (a fixed component is left as the step set it).
//
// Against local damping (damping::Local, 3DEC's way to settle): no force ever opposes the motion, so the model runs
// at its own pace down to each minimum of the potential energy, and without local damping's (1 + c) on the highest
// frequency (damping/local.hpp) static mass scaling gives every degree of freedom a mass 1 + c times smaller. On the
// deformable cross vault it reaches 1e-5 in half local damping's steps (docs/performance-history.md). The timestep
// does not grow here, unlike the original's: static mass scaling already puts every degree of freedom at its limit.
//
// The sums are taken over fixed chunks in a fixed order, so that the result does not depend on the threads.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <vector>

#include "blockdem/core/rotation.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

class InertialRelaxation {
 public:
  // FIRE's published parameters; on the deformable vault 0.05 and 0.25 for the first took as many steps or more.
  static constexpr double mixing_start = 0.1;   // a at each start (alpha_start)
  static constexpr double mixing_decay = 0.99;  // a *= this per downhill step once `delay` have passed (f_alpha)
  static constexpr int delay = 5;               // downhill steps before a decays (N_min)

  /// Stops counted since construction: the steps at which every velocity was set to zero.
  long long restarts() const { return restarts_; }

  /// After a step of `dt` (model forces F_n, velocities v_{n+1/2}, positions x_{n+1}): turns the velocities towards
  /// the forces or stops them, and moves the positions to x_n + dt v_{n+1/2} with the new velocities.
  void after_step(model::Model& m, double dt) {
    const Sums s = sums(m);
    if (s.power > 0) {
      const double scale = s.acceleration2 > 0 ? mixing_ * std::sqrt(s.velocity2 / s.acceleration2) : 0.0;
      mix(m, dt, 1 - mixing_, scale);
      if (++downhill_ > delay) mixing_ *= mixing_decay;
    } else {
      mix(m, dt, 0.0, 0.0);
      mixing_ = mixing_start;
      downhill_ = 0;
      ++restarts_;
    }
  }

 private:
  static constexpr std::size_t chunk = 2048;
  struct Sums {
    double power = 0, velocity2 = 0, acceleration2 = 0;  // F.v, v.M v, a.M a (a = M^-1 F)
  };

  // Free rigid block i (not a deformable block's body), and its world-frame inverse inertia applied to a moment.
  static bool free_rigid(const model::Model& m, std::size_t i) {
    return m.bodies.motion[i] == model::Motion::free && !m.deformable.is_deformable(i);
  }
  static Vec3 angular_acceleration(const model::RigidBodies& b, std::size_t i) {
    const Mat3& r = b.rotation[i];
    const Vec3 body = r.transpose() * b.moment[i];
    return r * body.cwiseQuotient(b.principal_inertia[i]);
  }
  static double mask(std::uint8_t fixity, int bit) { return (fixity >> bit) & 1u ? 0.0 : 1.0; }

  Sums sums(const model::Model& m) {
    const auto& nd = m.deformable.nodes;
    const auto& b = m.bodies;
    const std::size_t node_chunks = (nd.size() + chunk - 1) / chunk;
    partial_.assign(node_chunks, Sums{});
    const long long chunks = static_cast<long long>(node_chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
    for (long long c = 0; c < chunks; ++c) {
      Sums s;
      const std::size_t end = std::min(nd.size(), static_cast<std::size_t>(c + 1) * chunk);
      for (std::size_t i = static_cast<std::size_t>(c) * chunk; i < end; ++i) {
        const double mass = nd.mass[i];
        for (int k = 0; k < 3; ++k) {
          const double on = mask(nd.fixity[i], k), f = on * nd.force[i][k], v = on * nd.velocity[i][k];
          s.power += f * v;
          s.velocity2 += mass * v * v;
          s.acceleration2 += f * f / mass;
        }
      }
      partial_[static_cast<std::size_t>(c)] = s;
    }
    Sums total;
    for (const Sums& s : partial_) {
      total.power += s.power;
      total.velocity2 += s.velocity2;
      total.acceleration2 += s.acceleration2;
    }
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!free_rigid(m, i)) continue;
      const Vec3 alpha = angular_acceleration(b, i);
      const Vec3 w_body = b.rotation[i].transpose() * b.angular_velocity[i];
      const Vec3 alpha_body = b.rotation[i].transpose() * alpha;
      for (int k = 0; k < 3; ++k) {
        const double on = mask(b.fixity[i], k), f = on * b.force[i][k], v = on * b.velocity[i][k];
        total.power += f * v;
        total.velocity2 += b.mass[i] * v * v;
        total.acceleration2 += f * f / b.mass[i];
        const double turn = mask(b.fixity[i], 3 + k);
        total.power += turn * b.moment[i][k] * b.angular_velocity[i][k];
        total.velocity2 += b.principal_inertia[i][k] * w_body[k] * w_body[k];
        total.acceleration2 += b.principal_inertia[i][k] * alpha_body[k] * alpha_body[k];
      }
    }
    return total;
  }

  // v <- keep v + scale M^-1 F on every free component, and the step's move x_{n+1} - x_n = dt v taken again with
  // the new v (the contacts' increments come from the velocities: positions moved by the old v would leave their
  // springs out of step with the geometry).
  static void mix(model::Model& m, double dt, double keep, double scale) {
    auto& nd = m.deformable.nodes;
    const long long n = static_cast<long long>(nd.size());
#pragma omp parallel for schedule(static) if (n > 4096)
    for (long long j = 0; j < n; ++j) {
      const auto i = static_cast<std::size_t>(j);
      const double to_acceleration = scale / nd.mass[i];
      for (int k = 0; k < 3; ++k) {
        if ((nd.fixity[i] >> k) & 1u) continue;
        const double v = keep * nd.velocity[i][k] + to_acceleration * nd.force[i][k];
        nd.position[i][k] += dt * (v - nd.velocity[i][k]);
        nd.velocity[i][k] = v;
      }
    }
    auto& b = m.bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!free_rigid(m, i)) continue;
      const Vec3 alpha = angular_acceleration(b, i);
      Vec3 turn = Vec3::Zero();
      for (int k = 0; k < 3; ++k) {
        if (!((b.fixity[i] >> k) & 1u)) {
          const double v = keep * b.velocity[i][k] + scale / b.mass[i] * b.force[i][k];
          b.position[i][k] += dt * (v - b.velocity[i][k]);
          b.velocity[i][k] = v;
        }
        if (!((b.fixity[i] >> (3 + k)) & 1u)) {
          const double w = keep * b.angular_velocity[i][k] + scale * alpha[k];
          turn[k] = w - b.angular_velocity[i][k];
          b.angular_velocity[i][k] = w;
        }
      }
      b.orientation[i] = turned(b.orientation[i], turn, dt);
      b.rotation[i] = rotation_matrix(b.orientation[i]);
    }
  }

  double mixing_ = mixing_start;
  int downhill_ = 0;
  long long restarts_ = 0;
  std::vector<Sums> partial_;
};

}  // namespace blockdem
