#pragma once
// The contact pass of the rigid-rigid contacts (paper Sect. 3.1, DESIGN.md §4, step 1): one fused loop per joint law
// over the contacts of its group, four contacts at a time, one per vector lane. Per contact: the frame and the
// relative motion of the two blocks, reduced to the displacement increment at the origin and the relative rotation;
// per contact point: the increment by four multiply-adds -> law -> damping -> traction, summed into the contact's
// force and moments, which the block pass gathers. With a contact-field policy (damping::ContactFieldDamping) the
// branches act on the contact's resultant (integrate/maxwell_field.hpp).

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/lanes.hpp"
#include "blockdem/core/triple.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/integrate/maxwell_field.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// The fused contact loop of one law. Per contact: the frame and the relative motion of the two blocks, reduced
/// to the displacement increment at the origin and the relative rotation; per CP: the increment by four
/// multiply-adds -> law -> damping -> traction, summed into the contact's force and moments. AdvanceFields:
/// whether time passes for the Maxwell fields (contact_pass; no use without fields). inverse_omega_squared: 1 /
/// omega^2 (s^2) of the bound the timestep was set from, for the laws' closure impulse (contact/closure_impulse.hpp).
template <bool AdvanceFields, class Damping, class G>
void contact_pass_of(G& g, const model::RigidBodies& b, const Damping& damping, double increment_dt,
                     double inverse_omega_squared) {
  using L = typename G::LawType;
  // Raw pointers in locals: the compiler keeps the array addresses in registers instead of reloading them from the
  // vectors after every store. (GCC honours restrict only on parameters: the CP loop below gets its arrays as the
  // parameters of a lambda; here restrict documents the intent.)
  const Mat3* __restrict const rotation = b.rotation.data();
  const Vec3* __restrict const position = b.position.data();
  const Vec3* __restrict const velocity = b.velocity.data();
  const Vec3* __restrict const omega = b.angular_velocity.data();
  const std::uint32_t* __restrict const body_a = g.body_a.data();
  const std::uint32_t* __restrict const body_b = g.body_b.data();
  const std::uint16_t* __restrict const property = g.property.data();
  const Vec3* __restrict const origin_local = g.origin_a.data();
  const Vec3* __restrict const normal_local = g.normal_a.data();
  const Vec3* __restrict const tangent_local = g.tangent_a.data();
  const std::uint32_t* __restrict const first_point = g.first_point.data();
  Vec3* __restrict const contact_force = g.force.data();
  Vec3* __restrict const contact_moment = g.moment.data();
  const double* __restrict const plane_1 = g.s1.data();
  const double* __restrict const plane_2 = g.s2.data();
  const double* __restrict const area_of = g.area.data();
  const auto* __restrict const properties = g.properties.data();
  auto* __restrict const history = g.history.data();
  auto* __restrict const spring_state = g.spring_state.data();
  double* __restrict const slip_dissipation = g.slip_dissipation.data();
  double* __restrict const viscous_dissipation = g.viscous_dissipation.data();
  auto* __restrict const field = g.field.data();
  std::uint8_t* __restrict const field_form = g.field_form.data();
  const auto count = static_cast<std::ptrdiff_t>(g.contacts());
  const double h = 0.5 * increment_dt;
  const contact::Step step{increment_dt, inverse_omega_squared};
  // Whether the CP loop evaluates viscous stresses per CP (not for None, MassProportional, Local, nor for a
  // contact field, which acts on the contact's resultant).
  constexpr bool cp_viscous = !G::has_field && damping::PerSpringDamping<Damping>;
  // Four contacts at a time, one per lane: their kinematics (frame, increment at the origin, relative rotation)
  // and, after their CP loops, their forces and moments in lanes; the CP loops, the law and the damping one
  // contact after another. The last group of a pass repeats its last contact in the lanes it has no contact for
  // and keeps nothing of them. Which contacts share a group does not depend on the number of threads.
  static_assert(lane_count == 4);
  constexpr auto lanes = static_cast<std::ptrdiff_t>(lane_count);
  const std::ptrdiff_t groups_of_lanes = (count + lanes - 1) / lanes;
#pragma omp parallel for schedule(static) if (count > 256)
  for (std::ptrdiff_t lg = 0; lg < groups_of_lanes; ++lg) {
    const auto first = static_cast<std::size_t>(lg * lanes);
    const auto used = static_cast<std::size_t>(std::min(lanes, count - lg * lanes));  // lanes with a contact
    const auto contact_of = [&](std::size_t j) { return first + std::min(j, used - 1); };
    const std::size_t cs[4] = {contact_of(0), contact_of(1), contact_of(2), contact_of(3)};
    const std::uint32_t as[4] = {body_a[cs[0]], body_a[cs[1]], body_a[cs[2]], body_a[cs[3]]};
    const std::uint32_t bs[4] = {body_b[cs[0]], body_b[cs[1]], body_b[cs[2]], body_b[cs[3]]};
    // Lane j of v[index[j]], for the blocks (as, bs) or the contacts (cs) of the lanes.
    const auto gather = [](const Vec3* v, const auto& index) __attribute__((always_inline)) {
      return Triple{Lanes::of([&](int j) { return v[index[j]][0]; }), Lanes::of([&](int j) { return v[index[j]][1]; }),
                    Lanes::of([&](int j) { return v[index[j]][2]; })};
    };
    Lanes ra[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) ra[i][k] = Lanes::of([&](int j) { return rotation[as[j]](i, k); });
    const Triple n = turn(ra, gather(normal_local, cs));
    const Triple t1 = turn(ra, gather(tangent_local, cs));
    const Triple t2 = n.cross(t1);
    const Triple arm_a = turn(ra, gather(origin_local, cs));           // origin - x_A
    const Triple arm_b = gather(position, as) + arm_a - gather(position, bs);  // origin - x_B
    // The last move (velocities v(n-1/2)) is measured half a move back, at its middle, so that the same move
    // run backwards gives exactly the opposite increment (to third order): A turned back by h w_A (h = dt/2),
    // both centroids moved back by h v. The CP at origin + S, S = s1 t1 + s2 t2 fixed in A, then moves by
    // du = dt (u + W x S_mid), W = w_B - w_A, read in the mid-step frame (n, t1, t2)_mid = (I - h [w_A]x)(...).
    // In that frame W x S has the components (s2 W_1 - s1 W_2, -s2 W_n, s1 W_n): per CP the increment is
    // du0 plus four products.
    const Triple wa = gather(omega, as), wb = gather(omega, bs);
    const Triple dv = gather(velocity, bs) - gather(velocity, as);
    const Triple wa_arm_a = wa.cross(arm_a);
    const Triple u = increment_dt * (dv + wb.cross(arm_b + h * (dv - wa_arm_a)) - wa.cross(arm_a - h * wa_arm_a));
    const Triple w = increment_dt * (wb - wa);
    const Triple n_mid = n - h * wa.cross(n);
    const Triple t1_mid = t1 - h * wa.cross(t1);
    const Triple t2_mid = t2 - h * wa.cross(t2);
    // The increment at the origin and the relative rotation, in the contact frame, and the resultants that the
    // CP loops give back (force along n, t1, t2 and moment about the origin): one lane per contact.
    const Lanes motion[6] = {dot(u, n_mid), dot(u, t1_mid), dot(u, t2_mid), dot(w, n_mid), dot(w, t1_mid), dot(w, t2_mid)};
    // The resultants of the four contacts (force along n, t1, t2 and moment about the origin), one lane per contact:
    // each contact's CP loop sums from zero and writes its lane; a lane without a contact is set to zero here, so
    // that a full group writes the lanes only once. With Maxwell fields, the four contacts' fields are advanced
    // first, in lanes, and their force is added to the resultants after the CP loops, in vectors: when all four
    // are in the field form, as the fields keep it (the record, just written, is still in L1); else as the
    // masked advance gives it in `field_sum` (zero for the lanes whose CPs keep their own branch states). The
    // CP loops are then those of the policies without fields, and need no lane of the fields' force each. (The
    // simpler order, the advance after the CP loops adding its sums at once, made Maxwell<3> 4-5 % slower:
    // Elastic 415.0 instead of 401.6 instructions per contact.)
    Lanes resultant[6];
    [[maybe_unused]] Lanes field_sum[6];  // the fields' force where not all four lanes are in the field form
    [[maybe_unused]] unsigned released = 0;  // bit `lane`: a CP of the lane's contact failed or opened in this step
    [[maybe_unused]] std::uint32_t forms = 0;  // byte `lane`: the lane's field_form (0 past the last contact)
    constexpr std::uint32_t all_in_field_form = 0x01010101u;
    if constexpr (G::has_field) {
      std::memcpy(&forms, field_form + first, sizeof forms);
      const auto keep = [&] {
        return LaneMask::of(field_form[first], field_form[first + 1], field_form[first + 2], field_form[first + 3]);
      };
      if constexpr (AdvanceFields) {
        if (forms == all_in_field_form) [[likely]]
          damping.advance_field(field[lg], motion);
        else if (forms == 0)  // four contacts whose CPs keep their own branch states (or none)
          for (auto& f : field_sum) f = Lanes::zero();
        else
          damping.advance_field(field[lg], motion, keep(), field_sum);
      } else {
        Damping::field_force(field[lg], keep(), field_sum);
      }
    }
    if (used < lane_count)
      for (auto& r : resultant) r = Lanes::zero();
    for (std::size_t lane = 0; lane < used; ++lane) {
      const std::size_t c = first + lane;
      const double du0_n = motion[0][lane], du0_1 = motion[1][lane], du0_2 = motion[2][lane];
      const double w_n = motion[3][lane], w_1 = motion[4][lane], w_2 = motion[5][lane];
      const auto& p = properties[property[c]];
      const double kn = L::normal_stiffness(p);
      const double ks = L::shear_stiffness(p);
      // Resultants in the contact frame: force (normal, t1, t2) and moment about the origin.
      double fn = 0, f1 = 0, f2 = 0, mn = 0, m1 = 0, m2 = 0;
      const std::uint32_t begin = first_point[c], end = first_point[c + 1];
      // Maxwell branches in the contact-field form (damping::Maxwell::ContactField) are not evaluated per CP: the
      // field keeps each branch's generalised force on the contact, F_i = G h_i, advanced once per step under the
      // contact's generalised elongation increment q = (-du0, -w) through G q (G the contact's stiffness, diagonal
      // in the frame of the CPs' areas); the field's force on the contact is sum_i F_i, added to the resultants
      // after the CP loops, and its tractions at the CPs are evaluated only when asked for
      // (ContactGroup::traction_at). For such a contact the CP loop runs the law only and notes whether a CP
      // failed or opened. A contact whose CPs keep their own branch states (field_form 0, after a CP released its
      // branches) updates them in its CP loop, in the same pass over the CPs (a second pass after the CP loops
      // read every CP twice: on the damaged vault, where nearly every contact has a released CP, 20 % slower).
      [[maybe_unused]] bool inactive = false;
      // The CP loop through restrict parameters: GCC honours restrict on parameters, not on the local pointers above,
      // and without it guards the loop with a run-time check that the histories do not overlap the CPs' coordinates.
      // `own`: the contact's CPs keep their own branch states (a contact with a field after a CP released its
      // branches), updated in this loop; the contacts of a group are ordered by form (assign_contacts), so that the
      // choice per contact is predicted.
      const auto cp_loop = [&](auto own, const double* __restrict const point_1, const double* __restrict const point_2,
          const double* __restrict const point_area, typename G::History* __restrict const point_history,
          typename G::SpringState* __restrict const point_spring, double* __restrict const point_slip,
          double* __restrict const point_viscous) __attribute__((always_inline)) {
        constexpr bool own_branches = decltype(own)::value;
        constexpr bool viscous_here = cp_viscous || own_branches;
        for (std::uint32_t k = begin; k < end; ++k) {
          const double x1 = point_1[k], x2 = point_2[k];
          const double du_n = du0_n + x2 * w_1 - x1 * w_2;
          const contact::Shear du_s{du0_1 - x2 * w_n, du0_2 + x1 * w_n};
          const contact::Response r = L::update(p, point_history[k], du_n, du_s, step);
          const bool active = r.damping_active;  // L::damping_active(p, point_history[k]), from the step's registers
          const double area = point_area[k];
          double dissipated = 0.0;
          // Spring elongations in the sense of the stresses: closing the gap compresses, shear stress opposes du_s.
          [[maybe_unused]] const std::array<double, 3> e{-du_n, -du_s[0], -du_s[1]};
          std::array<double, 3> v{0.0, 0.0, 0.0};  // viscous stresses, Pa
          if constexpr (G::has_field) {  // own_branches only here: Clang checks the call for every policy otherwise
            if constexpr (own_branches)
              v = damping.spring_stresses(point_spring[k], kn, ks, e, increment_dt, active, dissipated);
            else
              inactive = inactive || !active;
          } else if constexpr (damping::SpringTripleDamping<Damping>) {
            v = damping.spring_stresses(point_spring[k], kn, ks, e, increment_dt, active, dissipated);
          } else {
            auto& spring = point_spring[k];
            v[0] = damping.spring_stress(spring[0], kn, e[0], increment_dt, active, dissipated);
            v[1] = damping.spring_stress(spring[1], ks, e[1], increment_dt, active, dissipated);
            v[2] = damping.spring_stress(spring[2], ks, e[2], increment_dt, active, dissipated);
          }
          // The traction is not stored: ContactGroup::traction_at() gets it back from the history and the state.
          // Policies without viscous stresses at the CP do not add v's zeros (x + 0.0 is not x for x = -0.0, so the
          // compiler keeps the additions).
          double sn = r.normal_stress, s1 = r.shear_stress[0], s2 = r.shear_stress[1];
          if constexpr (viscous_here) {
            sn += v[0];
            s1 += v[1];
            s2 += v[2];
          }
          add_cp_force(x1, x2, area * sn, area * s1, area * s2, fn, f1, f2, mn, m1, m2);
          // Only what can be non-zero is stored: a law or a policy that never dissipates costs no memory traffic here.
          if constexpr (L::dissipates) point_slip[k] += area * r.dissipated;
          if constexpr (viscous_here) point_viscous[k] += area * dissipated;
        }
      };
      if constexpr (G::has_field) {
        if (field_form[c]) [[likely]]
          cp_loop(std::false_type{}, plane_1, plane_2, area_of, history, spring_state, slip_dissipation, viscous_dissipation);
        else
          cp_loop(std::true_type{}, plane_1, plane_2, area_of, history, spring_state, slip_dissipation, viscous_dissipation);
      } else {
        cp_loop(std::false_type{}, plane_1, plane_2, area_of, history, spring_state, slip_dissipation, viscous_dissipation);
      }
      if constexpr (G::has_field) released |= static_cast<unsigned>(inactive) << lane;
      resultant[0].set(lane, fn);
      resultant[1].set(lane, f1);
      resultant[2].set(lane, f2);
      resultant[3].set(lane, mn);
      resultant[4].set(lane, m1);
      resultant[5].set(lane, m2);
    }
    // The fields' force; then contacts whose CPs keep their own branch states, and contacts in the field form
    // with a CP that released its branches in this step: both rare.
    if constexpr (G::has_field) {
      if (AdvanceFields && forms == all_in_field_form) [[likely]] {
        for (std::size_t j = 0; j < 6; ++j) resultant[j] += Damping::field_sum(field[lg], j);
      } else {
        for (std::size_t j = 0; j < 6; ++j) resultant[j] += field_sum[j];
      }
      if (forms != all_in_field_form || released != 0) [[unlikely]] {
        for (std::size_t lane = 0; lane < used; ++lane)
          if (field_form[first + lane] && (released >> lane & 1u))
            release_field<AdvanceFields>(damping, g, first + lane, motion, lane, resultant);
      }
    }
    const Triple f = combine(n, t1, t2, resultant[0], resultant[1], resultant[2]);
    const Triple m_origin = combine(n, t1, t2, resultant[3], resultant[4], resultant[5]);
    const Triple moment_a = -(arm_a.cross(f) + m_origin);
    const Triple moment_b = arm_b.cross(f) + m_origin;
    for (std::size_t lane = 0; lane < used; ++lane) {
      const std::size_t c = first + lane;
      contact_force[c] = f.vec(lane);
      contact_moment[2 * c] = moment_a.vec(lane);
      contact_moment[2 * c + 1] = moment_b.vec(lane);
    }
  }
}

/// The fused contact loop of one law (contact_pass_of). Groups with Maxwell fields get the loop compiled twice,
/// for steps in which time passes and for those in which none does (increment_dt 0: the forces of the present
/// state only), so that the loop has no branch on it per contact.
template <class Damping, class G>
void contact_pass(G& g, const model::RigidBodies& b, const Damping& damping, double increment_dt, double inverse_omega_squared) {
  if constexpr (G::has_field) {
    if (increment_dt > 0.0)
      contact_pass_of<true>(g, b, damping, increment_dt, inverse_omega_squared);
    else
      contact_pass_of<false>(g, b, damping, increment_dt, inverse_omega_squared);
  } else {
    contact_pass_of<true>(g, b, damping, increment_dt, inverse_omega_squared);
  }
}

}  // namespace blockdem
