#pragma once
// doctest::Approx is relative only above 1 (tolerance epsilon * (1 + |value|)); blockdem's tests compare small
// physical quantities (damping ratios of 0.001, displacements of 1e-5 m), so they use a purely relative one.

#include <doctest/doctest.h>

namespace blockdem::test {

/// |a - value| < epsilon * max(|a|, |value|), epsilon 1e-10 unless set with .epsilon().
inline doctest::Approx approx(double value) { return doctest::Approx(value).scale(0.0).epsilon(1e-10); }

}  // namespace blockdem::test
