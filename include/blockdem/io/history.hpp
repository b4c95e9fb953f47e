#pragma once
// Histories of named points attached to blocks: displacement relative to the base, velocity, and acceleration from
// centred differences of the velocity (as the paper does for its accelerometers, Sect. 5.3), written as CSV.

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::io {

struct MonitorPoint {
  std::string name;
  std::size_t block = 0;
  Vec3 body_point = Vec3::Zero();  // in the block's body frame
};

class HistoryRecorder {
 public:
  /// Records every `interval` calls of record().
  explicit HistoryRecorder(int interval = 1) : interval_(interval) {
    if (interval < 1) throw InvalidArgument("history: the recording interval must be >= 1 step");
  }

  /// A point given in world coordinates now, attached to `block` from here on.
  void add_point(const model::Model& model, std::string name, std::size_t block, const Vec3& world_point) {
    const auto& b = model.bodies;
    if (block >= b.size()) throw InvalidArgument("history: point '" + name + "' refers to block " + std::to_string(block) + ", outside 0.." + std::to_string(b.size() - 1));
    points_.push_back({std::move(name), block, b.rotation[block].transpose() * (world_point - b.position[block])});
    origin_.push_back(world_point);
  }

  /// `base_displacement`: the displacement of the base since the start, subtracted from the displacements.
  void record(const model::Model& model, double time, const Vec3& base_displacement = Vec3::Zero()) {
    if (calls_++ % interval_ != 0) return;
    const auto& b = model.bodies;
    time_.push_back(time);
    for (std::size_t p = 0; p < points_.size(); ++p) {
      const auto& m = points_[p];
      const Vec3 arm = b.rotation[m.block] * m.body_point;
      displacement_.push_back(b.position[m.block] + arm - origin_[p] - base_displacement);
      velocity_.push_back(b.velocity[m.block] + b.angular_velocity[m.block].cross(arm));
    }
  }

  const std::vector<MonitorPoint>& points() const { return points_; }
  std::size_t samples() const { return time_.size(); }
  double time(std::size_t k) const { return time_[k]; }
  const Vec3& displacement(std::size_t k, std::size_t point) const { return displacement_[k * points_.size() + point]; }
  const Vec3& velocity(std::size_t k, std::size_t point) const { return velocity_[k * points_.size() + point]; }
  /// Centred difference of the velocity (one-sided at the ends), m/s^2.
  Vec3 acceleration(std::size_t k, std::size_t point) const {
    if (samples() < 2) return Vec3::Zero();
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = k + 1 < samples() ? k + 1 : k;
    return (velocity(hi, point) - velocity(lo, point)) / (time_[hi] - time_[lo]);
  }

  /// Columns: time_s, then for each point <name>_ux,_uy,_uz (m), _vx,_vy,_vz (m/s), _ax,_ay,_az (m/s^2).
  /// Written atomically (io/atomic_file.hpp).
  void write_csv(const std::string& path) const {
    write_atomically(path, [&](std::ostream& out) { write_rows(out); });
  }

 private:
  void write_rows(std::ostream& out) const {
    out << "time_s";
    for (const auto& p : points_)
      for (const char* q : {"ux", "uy", "uz", "vx", "vy", "vz", "ax", "ay", "az"}) out << ',' << p.name << '_' << q;
    out << '\n';
    char buffer[64];
    for (std::size_t k = 0; k < samples(); ++k) {
      std::snprintf(buffer, sizeof buffer, "%.9g", time_[k]);
      out << buffer;
      for (std::size_t p = 0; p < points_.size(); ++p) {
        const Vec3 a = acceleration(k, p);
        for (const Vec3* v : {&displacement(k, p), &velocity(k, p), &a})
          for (int c = 0; c < 3; ++c) {
            std::snprintf(buffer, sizeof buffer, ",%.9g", (*v)[c]);
            out << buffer;
          }
      }
      out << '\n';
    }
  }

  int interval_;
  long long calls_ = 0;
  std::vector<MonitorPoint> points_;
  std::vector<Vec3> origin_;
  std::vector<double> time_;
  std::vector<Vec3> displacement_, velocity_;
};

}  // namespace blockdem::io
