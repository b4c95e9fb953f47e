// Velocity, displacement and peaks: exact for piecewise-linear acceleration (checked against closed-form integrals of
// polynomials and a sine), and the real PEER records against the PGV and PGD of their headers.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include "blockdem/core/units.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/readers.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_integration {
using namespace blockdem::motion;

TEST_CASE("integration: linear acceleration integrates exactly to the quadratic velocity and cubic displacement") {
  Record record;
  record.dt = 0.01;
  for (int i = 0; i <= 500; ++i) record.acceleration.push_back(2.0 - 3.0 * record.time(static_cast<std::size_t>(i)));
  const auto motion = integrate(record);
  for (std::size_t i = 0; i < record.size(); i += 50) {
    const double t = record.time(i);
    CHECK(motion.velocity[i] == doctest::Approx(2.0 * t - 1.5 * t * t).epsilon(1e-12));
    CHECK(motion.displacement[i] == doctest::Approx(t * t - 0.5 * t * t * t).epsilon(1e-12));
  }
}

TEST_CASE("integration: a sampled sine converges to its closed-form velocity and displacement at second order") {
  // a = sin(w t), v = (1 - cos(w t)) / w, u = t / w - sin(w t) / w^2.
  const double w = 2.0 * pi;
  double previous_error = 0.0;
  for (double dt : {0.02, 0.01}) {
    Record record;
    record.dt = dt;
    const auto n = static_cast<std::size_t>(std::llround(3.0 / dt)) + 1;
    for (std::size_t i = 0; i < n; ++i) record.acceleration.push_back(std::sin(w * record.time(i)));
    const auto motion = integrate(record);
    double error = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = record.time(i);
      error = std::max(error, std::abs(motion.displacement[i] - (t / w - std::sin(w * t) / (w * w))));
      CHECK(motion.velocity[i] == doctest::Approx((1.0 - std::cos(w * t)) / w).epsilon(2e-3));
    }
    if (previous_error > 0.0) CHECK(previous_error / error == doctest::Approx(4.0).epsilon(0.05));
    previous_error = error;
    const auto peaks = peak_values(record);
    // The sampled peak of a sine lies within 1 - cos(w dt / 2) of 1; the trapezoid rule's velocity at the half period
    // is dt cot(w dt / 2), where the continuous one is 2 / w.
    CHECK(peaks.pga <= 1.0);
    CHECK(peaks.pga >= std::cos(w * dt / 2) * (1 - 1e-12));
    CHECK(peaks.pgv == test::approx(dt / std::tan(w * dt / 2)).epsilon(1e-9));
  }
}

TEST_CASE("integration: the real PEER records reproduce the PGV and PGD of their headers") {
  // Reference: PGV= and PGD= in each header (the provider's processed record; trapezoid integration from rest).
  const auto data = std::filesystem::path(BLOCKDEM_SHARED_DIR) / "data";
  if (!std::filesystem::exists(data / "ImperialValley1979_ElCentroArray4_140.AT2")) {
    MESSAGE("skipped: " << data.string() << " is absent");
    return;
  }
  struct Case {
    std::string file;
    double pgv_cm_s;
    double pgd_cm;
  };
  for (const Case& c : {Case{"ImperialValley1979_ElCentroArray4_140.AT2", 39.6246, 25.1238},
                       Case{"ImperialValley1979_ElCentroArray4_230.AT2", 80.3737, 74.2297}}) {
    CAPTURE(c.file);
    const auto peaks = peak_values(read_record(data / c.file));
    CHECK(100.0 * peaks.pgv == doctest::Approx(c.pgv_cm_s).epsilon(1e-3));
    CHECK(100.0 * peaks.pgd == doctest::Approx(c.pgd_cm).epsilon(1e-3));
  }
}

}  // namespace test_integration
