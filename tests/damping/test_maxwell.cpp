// Maxwell branches: the closed forms of a single branch (eq. 16-18) against the general evaluator (eq. 19), and the
// evaluator against an independent std::complex computation of springs in series with dashpots.

#include <doctest/doctest.h>

#include "../approx.hpp"
#include "../area_frame.hpp"

#include <array>
#include <cmath>
#include <complex>

#include "blockdem/core/lanes.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_maxwell {
using damping::MaxwellBranch;

TEST_CASE("maxwell: single-branch closed forms (eq. 16-18) agree with the general evaluator (eq. 19)") {
  for (const MaxwellBranch b : {MaxwellBranch{0.1, 0.01}, MaxwellBranch{0.5, 0.3}, MaxwellBranch{2.0, 1e-4}}) {
    const std::array<MaxwellBranch, 1> one{b};
    for (int j = 0; j <= 200; ++j) {
      const double omega = std::pow(10.0, -2.0 + 8.0 * j / 200.0);
      CHECK(damping::damping_ratio(one, omega) == test::approx(b.damping_ratio(omega)).epsilon(1e-13));
      CHECK(damping::complex_modulus(one, omega).magnitude() == test::approx(b.modulus(omega)).epsilon(1e-13));
    }
    // eq. 17: the peak of eq. 16 and where it lies.
    const double w_peak = b.peak_angular_frequency();
    CHECK(b.damping_ratio(w_peak) == test::approx(b.peak_damping_ratio()).epsilon(1e-14));
    CHECK(b.damping_ratio(w_peak * 1.01) < b.peak_damping_ratio());
    CHECK(b.damping_ratio(w_peak / 1.01) < b.peak_damping_ratio());
    // eq. 18: |M_T| rises monotonically to 1 + alpha.
    CHECK(b.modulus(1e12 / b.tau) == test::approx(1.0 + b.alpha).epsilon(1e-12));
    CHECK(b.modulus(1e-12 / b.tau) == test::approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("maxwell: the evaluator agrees with std::complex springs-and-dashpots") {
  // A spring alpha k in series with a dashpot alpha k tau has complex stiffness alpha k (i w tau) / (1 + i w tau).
  const std::array<MaxwellBranch, 3> branches{{{0.129, 0.1507}, {0.1006, 0.0241}, {0.1652, 0.00371}}};
  for (int j = 0; j <= 300; ++j) {
    const double omega = std::pow(10.0, -1.0 + 5.0 * j / 300.0);
    std::complex<double> m{1.0, 0.0};
    for (const auto& b : branches) {
      const std::complex<double> iwt{0.0, omega * b.tau};
      m += b.alpha * iwt / (1.0 + iwt);
    }
    const auto ours = damping::complex_modulus(branches, omega);
    CHECK(ours.real == test::approx(m.real()).epsilon(1e-14));
    CHECK(ours.imag == test::approx(m.imag()).epsilon(1e-14));
    CHECK(ours.damping_ratio() == test::approx(m.imag() / (2.0 * m.real())).epsilon(1e-14));
    CHECK(ours.magnitude() == test::approx(std::abs(m)).epsilon(1e-14));
  }
}

TEST_CASE("maxwell: from_peak inverts eq. 17, the form 3DEC takes branches in") {
  for (double zeta : {0.005, 0.03, 0.2}) {
    for (double f : {0.5, 7.5, 40.0}) {
      const auto b = MaxwellBranch::from_peak(zeta, angular_frequency(f));
      CHECK(b.peak_damping_ratio() == test::approx(zeta).epsilon(1e-14));
      CHECK(frequency_hz(b.peak_angular_frequency()) == test::approx(f).epsilon(1e-14));
    }
  }
  CHECK_THROWS_AS(MaxwellBranch::from_peak(0.0, 1.0), InvalidArgument);
  CHECK_THROWS_AS(MaxwellBranch::from_peak(0.05, -1.0), InvalidArgument);
}

TEST_CASE("maxwell: Maxwell<N> policy and the eq. 20 timestep factor") {
  damping::Maxwell<3> policy{{{{0.1, 0.1}, {0.2, 0.01}, {0.09, 0.001}}}};
  static_assert(damping::Maxwell<3>::num_branches == 3);
  CHECK(policy.timestep_factor() == test::approx(1.0 / std::sqrt(1.39)).epsilon(1e-15));
  CHECK(damping::stiffness_factor(policy.branches) == test::approx(1.39));
  CHECK(policy.damping_ratio(10.0) == test::approx(policy.complex_modulus(10.0).damping_ratio()));
}

TEST_CASE("maxwell: spring_stresses (three springs at once) equals three spring_stress calls") {
  // Reference: the per-spring update, which the damping-ratio tests validate against eq. 19.
  damping::Maxwell<3> m({MaxwellBranch::from_peak(0.02, 2 * pi * 1.0), MaxwellBranch::from_peak(0.02, 2 * pi * 6.0),
                         MaxwellBranch::from_peak(0.02, 2 * pi * 40.0)});
  const double dt = 1e-4;
  m.prepare(dt);
  std::array<damping::Maxwell<3>::ContactState, 3> batch{}, single{};
  double batch_work = 0, single_work = 0;
  for (int step = 0; step < 200; ++step) {
    const std::array<double, 3> du{1e-7 * std::sin(0.1 * step), -2e-7 * std::cos(0.07 * step), 3e-8 * std::sin(0.3 * step)};
    const bool active = step < 150 || step > 160;  // released while "open", then active again
    const double kn = 1e10, ks = 4e9;
    const auto got = m.spring_stresses(batch, kn, ks, du, step == 0 ? 0.0 : dt, active, batch_work);
    const std::array<double, 3> want{m.spring_stress(single[0], kn, du[0], step == 0 ? 0.0 : dt, active, single_work),
                                     m.spring_stress(single[1], ks, du[1], step == 0 ? 0.0 : dt, active, single_work),
                                     m.spring_stress(single[2], ks, du[2], step == 0 ? 0.0 : dt, active, single_work)};
    for (std::size_t j = 0; j < 3; ++j) CHECK(got[j] == test::approx(want[j]).epsilon(1e-13).scale(1.0));
  }
  CHECK(batch_work == test::approx(single_work).epsilon(1e-12));
  CHECK(single_work > 0);
}

TEST_CASE("maxwell: the contact fields of four contacts (FieldLanes) give the resultant and the work of every CP's own branch states (spring_stresses)") {
  // Reference: spring_stresses at the four CPs of each contact, each driven by the elongation B(x1, x2) q of its
  // contact's generalised increment q (the rigid relative motion), summed over the CPs with their areas, against
  // the four contacts' fields in lanes, advanced by their q. The contacts differ in size and motion. Lane 3 is not
  // kept in some steps (a contact whose CPs hold their own branch states): it must keep its values and give no
  // force, and its CPs do not move in those steps.
  using M = damping::Maxwell<3>;
  M m({MaxwellBranch::from_peak(0.02, 2 * pi * 1.0), MaxwellBranch::from_peak(0.02, 2 * pi * 6.0),
       MaxwellBranch::from_peak(0.02, 2 * pi * 40.0)});
  const double dt = 1e-4, kn = 1e10, ks = 4e9;
  m.prepare(dt);
  // Four CPs of unequal areas, in the frame of their areas (origin at the centroid, t1 along a principal axis),
  // where G is diagonal: turned and shifted there from an arbitrary placement. Contact c is the same layout
  // scaled by 1 + 0.3 c (still in the frame of its areas).
  std::array<std::array<double, 3>, 4> points{{{0.12, 0.05, 0.01}, {-0.12, 0.05, 0.02}, {-0.12, -0.05, 0.015}, {0.3, -0.2, 0.005}}};
  test::to_area_frame(points);
  std::array<std::array<std::array<double, 3>, 4>, 4> contact_points{};
  M::FieldLanes lanes{};
  for (std::size_t c = 0; c < 4; ++c) {
    const double scale = 1.0 + 0.3 * static_cast<double>(c);
    double area = 0, i1 = 0, i2 = 0, product = 0;
    for (std::size_t p = 0; p < 4; ++p) {
      const auto [x1, x2, a] = points[p];
      contact_points[c][p] = {scale * x1, scale * x2, scale * scale * a};
      const auto [y1, y2, b] = contact_points[c][p];
      area += b;
      i1 += b * y1 * y1;
      i2 += b * y2 * y2;
      product += b * y1 * y2;
    }
    REQUIRE(std::abs(product) < 1e-15 * (i1 + i2));
    REQUIRE(std::abs(i1 - i2) > 0.1 * (i1 + i2));  // not a symmetric layout
    const auto g = M::contact_stiffness(area, i1, i2, kn, ks);
    for (std::size_t j = 0; j < 6; ++j) lanes.stiffness[M::stiffness_slot(j)].set(c, g[j]);
  }
  // Adds a B^T s, the generalised force of stresses s (normal, shear 1, shear 2) on area a at (x1, x2), to r.
  const auto add_generalised = [](M::Generalised& r, double x1, double x2, double a, const std::array<double, 3>& s) {
    r = {r[0] + a * s[0], r[1] + a * s[1], r[2] + a * s[2], r[3] + a * (x1 * s[2] - x2 * s[1]), r[4] + a * x2 * s[0],
         r[5] - a * x1 * s[0]};
  };
  std::array<std::array<std::array<M::ContactState, 3>, 4>, 4> own{};  // [contact][CP][direction]
  std::array<double, 4> own_work{};
  // The two differ by rounding only: relative to the largest force and moment.
  double largest = 0, deviation = 0, branch_deviation = 0, round_trip = 0, unchanged = 0, force_of_unkept = 0;
  int unkept_steps = 0;
  for (int step = 0; step < 300; ++step) {
    const double t = step;
    const double h = step == 0 ? 0.0 : dt;  // no time passes at first: the fields only give their force
    const bool lane_3_kept = step % 7 != 3;
    unkept_steps += lane_3_kept ? 0 : 1;
    const auto keep = LaneMask::of(true, true, true, lane_3_kept);
    std::array<M::Generalised, 4> q{};
    Lanes du[6];
    for (std::size_t c = 0; c < 4; ++c) {
      const double phase = 0.7 * static_cast<double>(c);
      q[c] = {1e-7 * std::sin(0.1 * t + phase), -2e-7 * std::cos(0.07 * t + phase), 3e-8 * std::sin(0.3 * t + phase),
              4e-7 * std::cos(0.05 * t + phase), -1e-6 * std::sin(0.02 * t + phase), 5e-7 * std::sin(0.11 * t + phase)};
      for (std::size_t j = 0; j < 6; ++j) du[j].set(c, -q[c][j]);
    }
    const M::FieldLanes before = lanes;
    Lanes sum[6];
    if (h > 0.0 && lane_3_kept) {
      m.advance_field(lanes, du);
      for (std::size_t j = 0; j < 6; ++j) sum[j] = M::field_sum(lanes, j);
    } else if (h > 0.0)
      m.advance_field(lanes, du, keep, sum);
    else
      M::field_force(lanes, keep, sum);
    for (std::size_t c = 0; c < 4; ++c) {
      if (c == 3 && !lane_3_kept) {
        for (std::size_t j = 0; j < 6; ++j) {
          force_of_unkept = std::max(force_of_unkept, std::abs(sum[j][c]));
          for (std::size_t i = 0; i < 3; ++i) unchanged = std::max(unchanged, std::abs(lanes.forces[i][j][c] - before.forces[i][j][c]));
        }
        unchanged = std::max(unchanged, std::abs(lanes.work[c] - before.work[c]));
        continue;
      }
      M::Generalised want{};  // sum a B^T s over the CPs
      for (std::size_t p = 0; p < 4; ++p) {
        const auto [x1, x2, a] = contact_points[c][p];
        const auto& qc = q[c];
        const std::array<double, 3> e{qc[0] + x2 * qc[4] - x1 * qc[5], qc[1] - x2 * qc[3], qc[2] + x1 * qc[3]};
        double work = 0;
        const auto s = m.spring_stresses(own[c][p], kn, ks, e, h, true, work);
        own_work[c] += a * work;
        add_generalised(want, x1, x2, a, s);
      }
      for (std::size_t j = 0; j < 6; ++j) {
        largest = std::max(largest, std::abs(want[j]));
        deviation = std::max(deviation, std::abs(sum[j][c] - want[j]));
      }
      // Branch by branch (the field keeps the sum in place of the last branch): sum a B^T s_i.
      M::ContactField field{};
      for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 6; ++j) field[i][j] = lanes.forces[i][j][c];
      const auto forces = M::branch_forces(field);
      for (std::size_t i = 0; i < 3; ++i) {
        M::Generalised branch{};
        for (std::size_t p = 0; p < 4; ++p) {
          const auto [x1, x2, a] = contact_points[c][p];
          const std::array<double, 3> s{own[c][p][0][i], own[c][p][1][i], own[c][p][2][i]};
          add_generalised(branch, x1, x2, a, s);
        }
        for (std::size_t j = 0; j < 6; ++j) branch_deviation = std::max(branch_deviation, std::abs(forces[i][j] - branch[j]));
      }
      const auto back = M::branch_forces(M::field_of(forces));
      for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 6; ++j) round_trip = std::max(round_trip, std::abs(back[i][j] - forces[i][j]));
    }
  }
  CHECK(unkept_steps > 10);
  CHECK(largest > 1.0);
  CHECK(deviation < 1e-12 * largest);
  CHECK(branch_deviation < 1e-12 * largest);
  CHECK(round_trip < 1e-14 * largest);
  CHECK(unchanged == 0.0);
  CHECK(force_of_unkept == 0.0);
  for (std::size_t c = 0; c < 4; ++c) {
    CHECK(own_work[c] > 0);
    CHECK(0.5 * lanes.work[c] == test::approx(own_work[c]).epsilon(1e-12));
  }
  // All four lanes kept: the advance with a mask gives the numbers of the one without.
  M::FieldLanes a = lanes, b = lanes;
  Lanes du[6], sum_a[6], sum_b[6];
  for (std::size_t j = 0; j < 6; ++j) du[j] = Lanes::of(1e-7, -2e-7, 3e-7, 4e-8) * (1.0 + static_cast<double>(j));
  const auto all = LaneMask::of(true, true, true, true);
  m.advance_field(a, du);
  for (std::size_t j = 0; j < 6; ++j) sum_a[j] = M::field_sum(a, j);
  m.advance_field(b, du, all, sum_b);
  for (std::size_t c = 0; c < 4; ++c) {
    CHECK(a.work[c] == b.work[c]);
    for (std::size_t j = 0; j < 6; ++j) {
      CHECK(sum_a[j][c] == sum_b[j][c]);
      for (std::size_t i = 0; i < 3; ++i) CHECK(a.forces[i][j][c] == b.forces[i][j][c]);
    }
  }
}

TEST_CASE("maxwell: element_stress_tile (elements across lanes) equals element_stress per element") {
  // Reference: the per-element update, which the deformable damping-ratio test validates against eq. 19.
  using M = damping::Maxwell<3>;
  constexpr std::size_t lanes = 8, used = 5;  // lanes past `used` stand for the end of a last, partial tile
  M m({MaxwellBranch::from_peak(0.02, 2 * pi * 1.0), MaxwellBranch::from_peak(0.02, 2 * pi * 6.0),
       MaxwellBranch::from_peak(0.02, 2 * pi * 40.0)});
  const double dt = 1e-4;
  m.prepare(dt);
  M::ElementTile<lanes> tile{};
  std::array<M::ElementState, used> single{};
  for (int step = 0; step < 200; ++step) {
    const double h = (step == 0 || step == 100) ? 0.0 : dt;  // no time passes: the first step, and after a detection
    M::ElementLanes<lanes> elastic{}, strain{}, branch{};
    std::array<double, lanes> work{};
    for (std::size_t l = 0; l < used; ++l)
      for (std::size_t c = 0; c < 6; ++c) {
        strain[c][l] = 1e-6 * std::sin(0.1 * step + 0.7 * static_cast<double>(l) + 1.3 * static_cast<double>(c));
        elastic[c][l] = 5e9 * (1.0 + 0.1 * static_cast<double>(c)) * strain[c][l];
      }
    m.element_stress_tile(tile, elastic, strain, h, branch, work);
    for (std::size_t l = 0; l < used; ++l) {
      std::array<double, 6> want{}, e{}, s{};
      for (std::size_t c = 0; c < 6; ++c) {
        e[c] = elastic[c][l];
        s[c] = strain[c][l];
      }
      double want_work = 0.0;
      m.element_stress(single[l], e, s, h, want, want_work);
      for (std::size_t c = 0; c < 6; ++c) CHECK(branch[c][l] == test::approx(want[c]).epsilon(1e-13).scale(1.0));
      CHECK(work[l] == test::approx(want_work).epsilon(1e-13).scale(1e-30));
    }
    for (std::size_t l = used; l < lanes; ++l) {
      CHECK(work[l] == 0.0);
      for (std::size_t c = 0; c < 6; ++c) CHECK(branch[c][l] == 0.0);
    }
  }
  for (std::size_t l = 0; l < used; ++l)
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t c = 0; c < 6; ++c) CHECK(tile.stress[c][i][l] == test::approx(single[l][i][c]).epsilon(1e-13).scale(1.0));
  CHECK(m.element_stored_energy(single[0], 5e9 / 2.4, 5e9 / 2.4) > 0);
}

}  // namespace test_maxwell
