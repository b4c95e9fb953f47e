// Truncation to a time window and to an Arias-intensity range, with the fraction of the Arias intensity kept
// checked against the closed form for a constant-amplitude record.

#include <doctest/doctest.h>

#include <cmath>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/truncation.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_truncation {
using namespace blockdem::motion;

namespace {
Record flat(double dt, double duration) {
  Record record;
  record.name = "flat";
  record.dt = dt;
  record.acceleration.assign(static_cast<std::size_t>(std::llround(duration / dt)) + 1, 1.5);
  return record;
}
}  // namespace

TEST_CASE("truncation: a time window keeps the samples that cover it and reports the Arias fraction") {
  // A constant-amplitude record's Arias intensity grows linearly: [3, 9] s of 20 s keeps 30 %.
  const auto record = flat(0.01, 20.0);
  const auto cut = truncate_window(record, 3.0, 9.0);
  CHECK(cut.start == doctest::Approx(3.0));
  CHECK(cut.end == doctest::Approx(9.0));
  CHECK(cut.record.size() == 601);
  CHECK(cut.record.start_time == doctest::Approx(3.0));
  CHECK(cut.arias_fraction == doctest::Approx(0.3).epsilon(1e-12));
  CHECK(cut.record.name == "flat [3-9 s]");

  const auto between = truncate_window(record, 3.004, 8.996);  // widened to the enclosing samples
  CHECK(between.start == doctest::Approx(3.0));
  CHECK(between.end == doctest::Approx(9.0));
  const auto clamped = truncate_window(record, -5.0, 100.0);
  CHECK(clamped.record.size() == record.size());
  CHECK(clamped.arias_fraction == doctest::Approx(1.0));
  CHECK_THROWS_WITH_AS(truncate_window(record, 30.0, 40.0), doctest::Contains("lies outside the record"), InvalidArgument);
  CHECK_THROWS_WITH_AS(truncate_window(record, 5.0, 5.0), doctest::Contains("must be before its end"), InvalidArgument);
}

TEST_CASE("truncation: an Arias range keeps at least that fraction") {
  const auto record = flat(0.01, 20.0);
  const auto cut = truncate_arias(record, 0.05, 0.95);
  CHECK(cut.start == doctest::Approx(1.0));
  CHECK(cut.end == doctest::Approx(19.0));
  CHECK(cut.arias_fraction == doctest::Approx(0.9).epsilon(1e-9));
  Record later = record;
  later.start_time = 100.0;  // times follow the record's clock
  const auto shifted = truncate_arias(later, 0.10, 0.90);
  CHECK(shifted.start == doctest::Approx(102.0));
  CHECK(shifted.end == doctest::Approx(118.0));
  CHECK(shifted.arias_fraction == doctest::Approx(0.8).epsilon(1e-9));
}

}  // namespace test_truncation
