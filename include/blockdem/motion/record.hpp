#pragma once
// A ground-acceleration record: uniformly sampled acceleration in m/s^2 with its time step, as read from a file or
// generated; every function of blockdem::motion takes and returns these.

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/acceleration_unit.hpp"

namespace blockdem::motion {

struct Record {
  std::string name;                  // file name or a label
  std::string source;                // format read ("PEER NGA .AT2", ...) or "synthetic ..."
  double dt = 0.0;                   // s, time step
  double start_time = 0.0;           // s, time of the first sample
  std::vector<double> acceleration;  // m/s^2
  AccelerationUnit input_unit = AccelerationUnit::m_s2;  // the unit the samples were given in
  std::optional<double> header_pga;  // m/s^2, peak ground acceleration stated by the data provider, if any
  bool synthetic = false;            // generated in code, not a recording

  std::size_t size() const noexcept { return acceleration.size(); }
  /// Time of sample i in s.
  double time(std::size_t i) const noexcept { return start_time + dt * static_cast<double>(i); }
  /// Time from the first to the last sample in s.
  double duration() const noexcept { return acceleration.empty() ? 0.0 : dt * static_cast<double>(size() - 1); }
  double end_time() const noexcept { return start_time + duration(); }

  /// Throws InvalidArgument unless dt > 0, there are at least 2 samples and every sample is finite.
  void validate(const char* where = "record") const {
    if (!(dt > 0.0) || !std::isfinite(dt))
      throw InvalidArgument(std::string(where) + ": time step dt = " + std::to_string(dt) + " s must be > 0");
    if (size() < 2)
      throw InvalidArgument(std::string(where) + ": " + std::to_string(size()) +
                            " samples; a record needs at least 2");
    for (std::size_t i = 0; i < size(); ++i)
      if (!std::isfinite(acceleration[i]))
        throw InvalidArgument(std::string(where) + ": sample " + std::to_string(i) + " is not finite");
  }
};

}  // namespace blockdem::motion
