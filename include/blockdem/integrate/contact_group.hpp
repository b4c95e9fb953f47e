#pragma once
// The contact points of one joint law, in struct-of-arrays storage: geometry fixed in the two blocks, the law's
// history, the damping policy's per-spring state, and the forces of the last step.

#include <array>
#include <cstdint>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"

namespace blockdem {

template <contact::ContactLaw Law, damping::DampingPolicy Damping>
struct ContactGroup {
  using Parameters = typename Law::Parameters;
  using History = typename Law::History;
  using SpringState = std::array<typename Damping::ContactState, 3>;  // normal, shear 1, shear 2

  std::vector<Parameters> properties;  // the parameter sets of this group; CPs refer to them by index

  // Per contact point.
  std::vector<std::uint32_t> body_a, body_b;
  std::vector<std::uint16_t> property;
  std::vector<Vec3> arm_a, arm_b;        // m, the CP in the body frames of A and B
  std::vector<Vec3> normal_a, tangent_a; // n and t1 in A's body frame (they turn with A)
  std::vector<double> area;              // m^2
  std::vector<History> history;
  std::vector<SpringState> spring_state;
  std::vector<Vec3> force;               // N, world frame, on B (A gets the opposite)
  std::vector<double> slip_dissipation;  // J, accumulated
  std::vector<double> viscous_dissipation;  // J, accumulated

  // Gather lists: for block i, entries first[i] .. first[i + 1] - 1 of `entry`, each 2 * cp + side (0: A, 1: B).
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> entry;

  std::size_t size() const { return body_a.size(); }

  void clear() {
    body_a.clear(); body_b.clear(); property.clear(); arm_a.clear(); arm_b.clear(); normal_a.clear();
    tangent_a.clear(); area.clear(); history.clear(); spring_state.clear(); force.clear();
    slip_dissipation.clear(); viscous_dissipation.clear();
  }

  /// Builds the gather lists for `blocks` blocks, in increasing CP order so that sums are reproducible.
  void build_gather_lists(std::size_t blocks) {
    first.assign(blocks + 1, 0);
    for (std::size_t k = 0; k < size(); ++k) {
      ++first[body_a[k] + 1];
      ++first[body_b[k] + 1];
    }
    for (std::size_t i = 0; i < blocks; ++i) first[i + 1] += first[i];
    entry.assign(first.back(), 0);
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::size_t k = 0; k < size(); ++k) {
      entry[next[body_a[k]]++] = static_cast<std::uint32_t>(2 * k);
      entry[next[body_b[k]]++] = static_cast<std::uint32_t>(2 * k + 1);
    }
  }
};

}  // namespace blockdem
