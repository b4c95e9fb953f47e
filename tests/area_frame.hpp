#pragma once
// CPs placed as the simulation places them on a contact plane: the origin at the area centroid, t1 along a
// principal axis of the areas (where a Maxwell contact field's stiffness is diagonal).

#include <array>
#include <cmath>

#include "blockdem/integrate/contact_group.hpp"

namespace blockdem::test {

/// Shifts and turns CPs (x1, x2, area) into the frame of their areas.
template <class Points>
void to_area_frame(Points& points) {
  double a0 = 0, c1 = 0, c2 = 0;
  for (const auto& [x1, x2, a] : points) {
    a0 += a;
    c1 += a * x1;
    c2 += a * x2;
  }
  c1 /= a0;
  c2 /= a0;
  double i11 = 0, i22 = 0, i12 = 0;
  for (const auto& [x1, x2, a] : points) {
    i11 += a * (x1 - c1) * (x1 - c1);
    i22 += a * (x2 - c2) * (x2 - c2);
    i12 += a * (x1 - c1) * (x2 - c2);
  }
  const double turn = principal_turn(i11, i22, i12);
  for (auto& [x1, x2, a] : points) {
    const double u = x1 - c1, v = x2 - c2;
    x1 = std::cos(turn) * u + std::sin(turn) * v;
    x2 = -std::sin(turn) * u + std::cos(turn) * v;
  }
}

}  // namespace blockdem::test
