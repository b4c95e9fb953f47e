// The Mavroeidis-Papageorgiou pulse (eq. 31): the closed-form acceleration against central differences of the
// velocity and the closed-form displacement against Simpson integration of the velocity, over many shapes.

#include <doctest/doctest.h>

#include <cmath>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/pulse.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_pulse {
using namespace blockdem::motion;

TEST_CASE("pulse: the velocity is eq. 31 and vanishes off its support") {
  const MavroeidisPapageorgiouPulse pulse{0.3, 2.5, 0.8, 4.0, 0.6};
  CHECK(pulse.start() == doctest::Approx(3.0));
  CHECK(pulse.end() == doctest::Approx(5.0));
  CHECK(pulse.velocity(4.0) == doctest::Approx(0.3 * std::cos(0.6)));  // envelope 1 at t0
  const double t = 4.37;
  const double expected = 0.15 * (1.0 + std::cos(two_pi * 0.37 / 2.0)) * std::cos(two_pi * 0.37 / 0.8 + 0.6);
  CHECK(pulse.velocity(t) == doctest::Approx(expected));
  for (double outside : {2.99, 5.01, -10.0, 100.0}) {
    CHECK(pulse.velocity(outside) == 0.0);
    CHECK(pulse.acceleration(outside) == 0.0);
  }
  CHECK(pulse.displacement(2.0) == 0.0);
  CHECK(pulse.displacement(100.0) == doctest::Approx(pulse.displacement(5.0)).epsilon(1e-14));  // residual after
}

TEST_CASE("pulse: acceleration and displacement agree with numerical differentiation and integration") {
  for (double gamma : {1.01, 1.5, 2.0, 3.7, 8.0})
    for (double phase : {0.0, 0.9, pi / 2.0, 2.5, 4.4}) {
      const MavroeidisPapageorgiouPulse pulse{0.25, gamma, 0.526, 3.0, phase};
      CAPTURE(gamma);
      CAPTURE(phase);
      // Fourth-order central differences, h = 1e-4 s, at interior points.
      const double h = 1e-4;
      double worst_a = 0.0, scale_a = 0.0;
      for (int k = 1; k < 200; ++k) {
        const double t = pulse.start() + (pulse.end() - pulse.start()) * k / 200.0;
        const double numeric = (-pulse.velocity(t + 2 * h) + 8 * pulse.velocity(t + h) - 8 * pulse.velocity(t - h) +
                                pulse.velocity(t - 2 * h)) / (12 * h);
        worst_a = std::max(worst_a, std::abs(pulse.acceleration(t) - numeric));
        scale_a = std::max(scale_a, std::abs(numeric));
      }
      CHECK(worst_a < 1e-9 * scale_a);
      // Composite Simpson integration of the velocity from the start of the support, 2000 intervals per segment.
      double worst_u = 0.0, scale_u = 0.0;
      double integral = 0.0;
      double from = pulse.start();
      for (int k = 1; k <= 40; ++k) {
        const double to = pulse.start() + (pulse.end() - pulse.start()) * k / 40.0 + (k == 40 ? 0.5 : 0.0);
        const int n = 2000;
        const double step = (to - from) / n;
        double s = pulse.velocity(from) + pulse.velocity(to);
        for (int j = 1; j < n; ++j) s += (j % 2 ? 4.0 : 2.0) * pulse.velocity(from + j * step);
        integral += s * step / 3.0;
        from = to;
        worst_u = std::max(worst_u, std::abs(pulse.displacement(to) - integral));
        scale_u = std::max(scale_u, std::abs(integral));
      }
      CHECK(worst_u < 1e-9 * scale_u + 1e-14);
    }
}

TEST_CASE("pulse: a sampled pulse integrates back to its closed-form velocity and displacement") {
  const MavroeidisPapageorgiouPulse pulse{0.26, 3.0, 0.526, 2.0, 1.2};
  const auto record = to_record(pulse, 0.001, 5001);
  CHECK(record.synthetic);
  const auto motion = integrate(record);
  for (std::size_t i = 0; i < record.size(); i += 250) {
    CHECK(motion.velocity[i] == doctest::Approx(pulse.velocity(record.time(i))).epsilon(1e-4).scale(0.26));
    CHECK(motion.displacement[i] == doctest::Approx(pulse.displacement(record.time(i))).epsilon(1e-5).scale(0.03));
  }
}

TEST_CASE("pulse: phase pi/2 leaves no residual displacement, gamma must exceed 1") {
  const MavroeidisPapageorgiouPulse odd{0.3, 4.0, 0.5, 1.0, pi / 2.0};
  CHECK(std::abs(odd.displacement(10.0)) < 1e-15);
  CHECK_THROWS_WITH_AS((MavroeidisPapageorgiouPulse{0.3, 1.0, 0.5, 1.0, 0.0}.validate()),
                       doctest::Contains("gamma = 1.000000 must be > 1"), InvalidArgument);
  CHECK_THROWS_AS((MavroeidisPapageorgiouPulse{0.3, 2.0, 0.0, 1.0, 0.0}.validate()), InvalidArgument);
}

}  // namespace test_pulse
