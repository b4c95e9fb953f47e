#pragma once
// What a contact point found at a re-detection inherits from the contacts before it: one rule for the contacts
// between rigid blocks (integrate/contact_assignment.hpp) and the node contacts of deformable blocks
// (integrate/node_contact_assignment.hpp). The law says how its state does so (contact::ContactLaw: turn_shear,
// start_unbonded); of a history's members the engine sets the gap only, and reads an old one's to bound it.

#include <algorithm>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/integrate/contact_frame.hpp"

namespace blockdem {

/// Where a contact point's state comes from.
enum class Inheritance {
  first_detection,  // the contacts of the model as built: bonded joints, from the law's initial state
  same_point,       // an old contact point at the same place of the same block pair: its whole state
  same_joint,       // a point that the joint's re-drawn contact adds (a corner that appeared as the faces turned, a
                    // CP split off): the state of the joint where it is, that of the old contact's closest point,
                    // with its own gap but closed no farther than that point, and no damping state
  new_contact,      // where the pair had no contact (an impact after separation, a new pair after sliding): never
                    // part of a bonded joint, it starts unbonded (contact::ContactLaw::start_unbonded), closed no
                    // farther than touching
};

// A point that a re-detection finds already closed (an overlap) is loaded only as far as a contact point that stood
// there all along would be: a new contact from touching (gap 0), a point of a re-drawn joint from the closure of
// the joint's point it inherits. The laws are incremental (as in 3DEC), so the overlap beyond stays unloaded and
// the stress grows from there with the gap's increments. The overlap is the faces' motion between two detections,
// when no spring stood there: loading it at once would store 1/2 k_n d^2 that no force put in, and give it back
// as motion when the joint opens (docs/energy.md, what re-detection does to the balance).

/// The law's history of a contact point found with gap `gap` (m) whose state comes from `old` (same_point and
/// same_joint; null otherwise), its shear turned to the new contact frame by `turn`.
template <contact::ContactLaw L>
typename L::History inherited_history(Inheritance from, const typename L::History* old, double gap,
                                      const contact::ShearTurn& turn) noexcept {
  typename L::History h{};
  h.gap = gap;
  switch (from) {
    case Inheritance::first_detection:
      break;
    case Inheritance::same_point:
      h = *old;
      L::turn_shear(h, turn);
      break;
    case Inheritance::same_joint:
      h = *old;
      h.gap = std::max(gap, std::min(old->gap, 0.0));
      L::turn_shear(h, turn);
      break;
    case Inheritance::new_contact:
      L::start_unbonded(h);
      h.gap = std::max(gap, 0.0);
      break;
  }
  return h;
}

/// The damping state of the three springs of a contact point that inherits `old`'s (same_point), its shear springs
/// turned to the new frame like the law's shear stresses.
template <class SpringState>
SpringState inherited_spring_state(const SpringState& old, const contact::ShearTurn& turn) {
  SpringState s = old;
  turn_shear_pair(s[1], s[2], turn);
  return s;
}

}  // namespace blockdem
