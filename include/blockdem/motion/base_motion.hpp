#pragma once
// The motion of a shake table (or a rigid foundation): a sum of ground-acceleration records along directions
// (baseline corrected, integrated by the toolkit, motion/integration.hpp), whole cycles of sine velocity and a
// constant velocity, sampled at any time. A value: what a model holds as its base motion (model::Model::base_motion).

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/baseline.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

namespace detail {
inline Vec3 unit_direction(const Vec3& direction, const char* where) {
  const double norm = direction.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw InvalidArgument(std::string(where) + ": the direction must be a non-zero finite vector");
  return direction / norm;
}
}  // namespace detail

/// The table following one acceleration record along a unit direction. Sample i of the record (already windowed and
/// scaled; its own start_time is not used) acts at time start + i dt on the simulation's clock.
class RecordMotion {
 public:
  /// From time `start` (s) on, starting at `initial_velocity` (m/s: where an earlier motion left the table). The
  /// table keeps that velocity before the start; after the record ends it keeps its last velocity (final_velocity())
  /// without acceleration, so that a record cut while the table moves loads the model with no impulse (stopping the
  /// table there would be one).
  RecordMotion(const Record& record, const std::vector<BaselineStep>& baseline, const Vec3& direction,
               double start = 0.0, double initial_velocity = 0.0)
      : record_(correct_baseline(record, baseline)),
        direction_(detail::unit_direction(direction, "base motion")),
        start_(start),
        v0_(initial_velocity) {
    record_.validate("base motion");
    if (!std::isfinite(start)) throw InvalidArgument("base motion: the start time must be finite");
    if (!std::isfinite(initial_velocity)) throw InvalidArgument("base motion: the initial velocity must be finite");
    motion_ = integrate(record_);
  }

  const Record& record() const { return record_; }
  double start() const { return start_; }
  double duration() const { return record_.duration(); }
  double end() const { return start_ + duration(); }
  const Vec3& direction() const { return direction_; }
  double initial_velocity() const { return v0_; }
  /// Table velocity at the end of the record, m/s (what the baseline correction or the cut left; kept after it).
  double final_velocity() const { return v0_ + motion_.velocity.back(); }

  /// Acceleration, velocity and displacement along the direction at simulation time t (s): m/s^2, m/s, m. Velocity
  /// and displacement are interpolated linearly between the samples of the exact integrals of the piecewise-linear
  /// acceleration (so the velocity's slope is the mean acceleration over each step of the record: a record coarse
  /// against the model's periods must be resampled first, motion::resample).
  double acceleration(double t) const { return sample(record_.acceleration, t); }
  double velocity(double t) const { return t >= end() ? final_velocity() : v0_ + sample(motion_.velocity, t); }
  /// Displacement since the start (before it: 0 at the start, moving at the initial velocity).
  double displacement(double t) const {
    if (t <= start_) return v0_ * (t - start_);
    if (t >= end()) return motion_.displacement.back() + v0_ * duration() + final_velocity() * (t - end());
    return v0_ * (t - start_) + sample(motion_.displacement, t);
  }

 private:
  double sample(const std::vector<double>& values, double t) const {
    const double u = (t - start_) / record_.dt;
    if (!(u >= 0.0) || u > static_cast<double>(values.size() - 1)) return 0.0;
    const auto i = std::min(static_cast<std::size_t>(u), values.size() - 2);
    const double f = u - static_cast<double>(i);
    return (1.0 - f) * values[i] + f * values[i + 1];
  }

  Record record_;
  GroundMotion motion_;
  Vec3 direction_;
  double start_;
  double v0_;  // m/s
};

/// Whole cycles of a sine velocity along a unit direction, in closed form: v(t) = A sin(2 pi u), u = (t - start) / T,
/// for 0 < u < n, zero outside. The table starts and ends at rest where it started: one cycle is the pulse of a
/// free-vibration test, many a harmonic input.
struct SineVelocity {
  double amplitude = 0.0;          // m/s, A
  double period = 1.0;             // s, T
  int cycles = 1;                  // n
  Vec3 direction = Vec3::UnitX();  // any non-zero vector: made a unit vector when a BaseMotion takes it
  double start = 0.0;              // s, on the simulation's clock

  /// Throws InvalidArgument unless A and start are finite, T > 0, n >= 1 and the direction is non-zero.
  void validate() const {
    if (!std::isfinite(amplitude) || !std::isfinite(start))
      throw InvalidArgument("sine velocity: the amplitude and the start time must be finite");
    if (!(period > 0.0) || !std::isfinite(period))
      throw InvalidArgument("sine velocity: the period " + std::to_string(period) + " s must be > 0");
    if (cycles < 1) throw InvalidArgument("sine velocity: " + std::to_string(cycles) + " cycles; at least 1");
    (void)detail::unit_direction(direction, "sine velocity");
  }

  double end() const { return start + cycles * period; }
  double velocity(double t) const {  // m/s
    const double u = (t - start) / period;
    return u > 0 && u < cycles ? amplitude * std::sin(2 * pi * u) : 0.0;
  }
  double acceleration(double t) const {  // m/s^2
    const double u = (t - start) / period;
    return u > 0 && u < cycles ? amplitude * (2 * pi / period) * std::cos(2 * pi * u) : 0.0;
  }
  /// Displacement since the start, m: A T / (2 pi) (1 - cos 2 pi u), back to zero after the last cycle.
  double displacement(double t) const {
    const double u = (t - start) / period;
    return u > 0 && u < cycles ? amplitude * period / (2 * pi) * (1.0 - std::cos(2 * pi * u)) : 0.0;
  }
};

/// The table's motion: a constant velocity plus any number of records (RecordMotion) and sine velocities
/// (SineVelocity), each along its own direction. A value: copied with the records it holds, no reference to the
/// caller's data. Built at rest (the default), constant, from one record or one sine, and summed with +.
class BaseMotion {
 public:
  /// At rest.
  BaseMotion() = default;
  static BaseMotion at_rest() { return {}; }
  /// A constant velocity (m/s) at all times: where an earlier motion left the table.
  static BaseMotion constant(const Vec3& velocity) {
    if (!velocity.allFinite()) throw InvalidArgument("base motion: the constant velocity must be finite");
    BaseMotion m;
    m.constant_ = velocity;
    return m;
  }
  /// One record along `direction` from `start`, starting at `initial_velocity` (RecordMotion).
  BaseMotion(const Record& record, const std::vector<BaselineStep>& baseline, const Vec3& direction,
             double start = 0.0, double initial_velocity = 0.0)
      : BaseMotion(RecordMotion(record, baseline, direction, start, initial_velocity)) {}
  explicit BaseMotion(RecordMotion record) { records_.push_back(std::move(record)); }
  explicit BaseMotion(SineVelocity sine) {
    sine.validate();
    sine.direction = detail::unit_direction(sine.direction, "sine velocity");
    sines_.push_back(sine);
  }

  /// The sum: the table moves by both (along several directions, or by several inputs along one).
  BaseMotion& operator+=(const BaseMotion& other) {
    constant_ += other.constant_;
    records_.insert(records_.end(), other.records_.begin(), other.records_.end());
    sines_.insert(sines_.end(), other.sines_.begin(), other.sines_.end());
    return *this;
  }
  friend BaseMotion operator+(BaseMotion a, const BaseMotion& b) { return a += b; }

  /// Acceleration (m/s^2) and velocity (m/s) at simulation time t (s).
  Vec3 acceleration(double t) const {
    return sum(Vec3::Zero(), [t](const auto& c) { return c.acceleration(t); });
  }
  Vec3 velocity(double t) const {
    return sum(constant_, [t](const auto& c) { return c.velocity(t); });
  }
  /// Displacement from time `since` to time t (s), m.
  Vec3 displacement(double t, double since = 0.0) const {
    return sum(constant_ * (t - since),
               [t, since](const auto& c) { return c.displacement(t) - c.displacement(since); });
  }
  /// Velocity after end(), m/s: the constant plus what each record left (a sine ends at rest).
  Vec3 final_velocity() const {
    return sum(constant_, [](const auto& c) {
      if constexpr (requires { c.final_velocity(); }) return c.final_velocity();
      else return 0.0;
    });
  }
  /// When the last record or sine ends, s; -infinity for a constant motion.
  double end() const {
    double last = -std::numeric_limits<double>::infinity();
    for (const auto& r : records_) last = std::max(last, r.end());
    for (const auto& s : sines_) last = std::max(last, s.end());
    return last;
  }

  const Vec3& constant_velocity() const { return constant_; }
  const std::vector<RecordMotion>& records() const { return records_; }
  const std::vector<SineVelocity>& sines() const { return sines_; }

 private:
  /// `constant` plus of(c) along c's direction for every component. A zero constant is replaced, not added to, so
  /// that a motion of one component is sampled bit for bit as that component alone (0 + (-0) would be +0).
  template <class Of>
  Vec3 sum(const Vec3& constant, Of of) const {
    Vec3 total = constant;
    bool zero = constant == Vec3::Zero();
    auto add = [&](const Vec3& term) {
      if (zero) total = term;
      else total += term;
      zero = false;
    };
    for (const auto& r : records_) add(of(r) * r.direction());
    for (const auto& s : sines_) add(of(s) * s.direction);
    return total;
  }

  Vec3 constant_ = Vec3::Zero();  // m/s
  std::vector<RecordMotion> records_;
  std::vector<SineVelocity> sines_;
};

}  // namespace blockdem::motion
