#pragma once
// The motion of a shake table (or a rigid foundation) along one axis, from a ground-acceleration record: baseline
// corrected, integrated to velocity and displacement by the toolkit (motion/integration.hpp), sampled at any time.
// What the engine takes as the base velocity of a model (model::Model::base_velocity).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/motion/baseline.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

class BaseMotion {
 public:
  BaseMotion() = default;

  /// The table follows `record` (already windowed and scaled) along the unit `direction`, from time `start` (s, on
  /// the simulation's clock) on, starting at `initial_velocity` (m/s: where an earlier motion left the table). It
  /// keeps that velocity before the start; after the record ends it keeps its last velocity (final_velocity())
  /// without acceleration, so that a record cut while the table moves loads the model with no impulse (stopping the
  /// table there would be one).
  BaseMotion(const Record& record, const std::vector<BaselineStep>& baseline, Vec3 direction, double start = 0.0,
             double initial_velocity = 0.0)
      : record_(correct_baseline(record, baseline)), direction_(direction.normalized()), start_(start), v0_(initial_velocity) {
    record_.validate("base motion");
    if (!std::isfinite(start)) throw InvalidArgument("base motion: the start time must be finite");
    motion_ = integrate(record_);
  }

  const Record& record() const { return record_; }
  double start() const { return start_; }
  double duration() const { return record_.duration(); }
  double end() const { return start_ + duration(); }
  const Vec3& direction() const { return direction_; }
  /// Table velocity at the end of the record, m/s (what the baseline correction or the cut left; kept after it).
  double final_velocity() const { return v0_ + (motion_.velocity.empty() ? 0.0 : motion_.velocity.back()); }

  /// Acceleration, velocity and displacement along the axis at simulation time t (s): m/s^2, m/s, m. Velocity and
  /// displacement are interpolated linearly between the samples of the exact integrals of the piecewise-linear
  /// acceleration.
  double acceleration(double t) const { return sample(record_.acceleration, t); }
  double velocity(double t) const { return t >= end() ? final_velocity() : v0_ + sample(motion_.velocity, t); }
  /// Displacement since the start (before it: 0 at the start, moving at the initial velocity).
  double displacement(double t) const {
    if (motion_.displacement.empty() || t <= start_) return v0_ * (t - start_);
    if (t >= end()) return motion_.displacement.back() + v0_ * duration() + final_velocity() * (t - end());
    return v0_ * (t - start_) + sample(motion_.displacement, t);
  }
  Vec3 velocity_vector(double t) const { return velocity(t) * direction_; }

 private:
  double sample(const std::vector<double>& values, double t) const {
    if (values.empty()) return 0.0;
    const double u = (t - start_) / record_.dt;
    if (!(u >= 0.0) || u > static_cast<double>(values.size() - 1)) return 0.0;
    const auto i = std::min(static_cast<std::size_t>(u), values.size() - 2);
    const double f = u - static_cast<double>(i);
    return (1.0 - f) * values[i] + f * values[i + 1];
  }

  Record record_;
  GroundMotion motion_;
  Vec3 direction_ = Vec3::UnitY();
  double start_ = 0.0;
  double v0_ = 0.0;  // m/s
};

}  // namespace blockdem::motion
