#pragma once
// The kinematics axis: the two kinds of block side a contact point can have. Rigid: 6 degrees of freedom per block
// (centroid, orientation, principal inertia); Deformable: 3 degrees of freedom per node, lumped mass, constant-strain
// tetrahedra. Contact points are grouped by (law, kinematics of the side that owns the face): rigid-rigid groups
// (integrate/contact_group.hpp), and node groups whose node side is deformable and whose face side is either
// (kinematics/node_contact_group.hpp), each with its own specialised loop.

#include <concepts>

namespace blockdem::kinematics {

struct Rigid {
  static constexpr bool deformable = false;
};
struct Deformable {
  static constexpr bool deformable = true;
};

template <class K>
concept Kinematics = std::same_as<K, Rigid> || std::same_as<K, Deformable>;

}  // namespace blockdem::kinematics
