#pragma once
// The frame of a contact between rigid blocks (origin, n from A to B, t1, t2; fixed in block A), and the turn of
// shear components from an old frame to a new one when a contact is detected again (contact::ShearTurn).

#include <cstddef>
#include <type_traits>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// The world frame of a contact: origin, n (from A to B), t1, t2, all turning with block A.
struct ContactFrame {
  Vec3 origin, n, t1, t2;
  Vec3 point(double u, double v) const { return origin + u * t1 + v * t2; }
};

/// The world frame of contact c of a rigid contact group.
template <class G>
ContactFrame contact_frame(const model::RigidBodies& b, const G& g, std::size_t c) {
  const Mat3& ra = b.rotation[g.body_a[c]];
  ContactFrame fr;
  fr.origin = b.position[g.body_a[c]] + rotate(ra, g.origin_a[c]);
  fr.n = rotate(ra, g.normal_a[c]);
  fr.t1 = rotate(ra, g.tangent_a[c]);
  fr.t2 = fr.n.cross(fr.t1);
  return fr;
}

/// The turn from the tangents (old_t1, old_t2) to (t1, t2) of the same plane.
inline contact::ShearTurn shear_turn(const Vec3& old_t1, const Vec3& old_t2, const Vec3& t1, const Vec3& t2) {
  return {old_t1, old_t2, t1, t2};
}

/// A shear pair (s1, s2) of a damping state re-expressed along the new tangents: component by component for a
/// state that holds one value per Maxwell branch; nothing for a policy without spring state.
template <class S>
void turn_shear_pair(S& s1, S& s2, const contact::ShearTurn& turn) {
  if constexpr (std::is_arithmetic_v<S>) {
    turn.apply(s1, s2);
  } else if constexpr (requires { s1.size(); }) {
    for (std::size_t i = 0; i < s1.size(); ++i) turn_shear_pair(s1[i], s2[i], turn);
  }
}

}  // namespace blockdem
