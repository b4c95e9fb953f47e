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
  AreaMoments moments;
  for (const auto& [x1, x2, a] : points) moments.add(x1, x2, a);
  const double c1 = moments.centroid_1(), c2 = moments.centroid_2(), turn = moments.principal_turn();
  for (auto& [x1, x2, a] : points) {
    const double u = x1 - c1, v = x2 - c2;
    x1 = std::cos(turn) * u + std::sin(turn) * v;
    x2 = -std::sin(turn) * u + std::cos(turn) * v;
  }
}

}  // namespace blockdem::test
