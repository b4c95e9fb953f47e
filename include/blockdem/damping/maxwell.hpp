#pragma once
// Maxwell damping (paper Sect. 4.2): N spring-dashpot branches in parallel with each joint spring (and each
// tetrahedron). Branch i adds a spring alpha_i k in series with a dashpot of relaxation time tau_i.

#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/lanes.hpp"
#include "blockdem/damping/concepts.hpp"

namespace blockdem::damping {

/// The normalised complex modulus M_T = Re + i Im of a spring with Maxwell branches (eq. 15, 19).
struct ComplexModulus {
  double real = 1.0;
  double imag = 0.0;

  /// |M_T| (eq. 18).
  constexpr double magnitude() const noexcept { return cmath::sqrt(real * real + imag * imag); }
  /// zeta = Im(M_T) / (2 Re(M_T)) (eq. 16, 19).
  constexpr double damping_ratio() const noexcept { return imag / (2.0 * real); }
};

/// One Maxwell branch: stiffness fraction alpha (dimensionless, > 0) and relaxation time tau = eta / (alpha k) (s).
struct MaxwellBranch {
  double alpha = 0.0;
  double tau = 0.0;  // s

  /// The branch's own contribution to the complex modulus at omega (rad/s), eq. 14.
  constexpr ComplexModulus modulus_term(double omega) const noexcept {
    const double x = tau * omega;
    const double d = 1.0 + x * x;
    return {alpha * x * x / d, alpha * x / d};
  }

  /// Damping ratio of the standard linear solid made of this branch alone (eq. 16).
  constexpr double damping_ratio(double omega) const noexcept {
    const double x = tau * omega;
    return alpha * x / (2.0 * (1.0 + x * x * (1.0 + alpha)));
  }

  /// |M_T| of this branch alone (eq. 18).
  constexpr double modulus(double omega) const noexcept {
    const double x2 = tau * tau * omega * omega;
    return cmath::sqrt(1.0 + alpha * (2.0 + alpha) * x2 / (1.0 + x2));
  }

  /// Peak of eq. 16: alpha / (4 sqrt(1 + alpha)) (eq. 17).
  constexpr double peak_damping_ratio() const noexcept { return alpha / (4.0 * cmath::sqrt(1.0 + alpha)); }

  /// Angular frequency of the peak: 1 / (tau sqrt(1 + alpha)) (eq. 17), rad/s.
  constexpr double peak_angular_frequency() const noexcept { return 1.0 / (tau * cmath::sqrt(1.0 + alpha)); }

  /// The branch whose peak is `peak_damping_ratio` at `peak_omega` (rad/s): eq. 17 inverted. With s = sqrt(1 + alpha),
  /// zeta = (s^2 - 1) / (4 s) gives s = 2 zeta + sqrt(4 zeta^2 + 1). This is how 3DEC's `maxwell z f` pairs are read.
  static constexpr MaxwellBranch from_peak(double peak_damping_ratio, double peak_omega) {
    if (!(peak_damping_ratio > 0.0) || !(peak_omega > 0.0))
      throw InvalidArgument("maxwell branch: the peak damping ratio and the peak frequency must be > 0");
    const double root = cmath::sqrt(4.0 * peak_damping_ratio * peak_damping_ratio + 1.0);
    const double s = 2.0 * peak_damping_ratio + root;
    // alpha = s^2 - 1 = (s - 1)(s + 1), with s - 1 written without cancellation for small ratios.
    const double s_minus_1 = 2.0 * peak_damping_ratio + 4.0 * peak_damping_ratio * peak_damping_ratio / (root + 1.0);
    return {s_minus_1 * (s + 1.0), 1.0 / (peak_omega * s)};
  }
};

/// M_T = 1 + sum_i alpha_i (tau_i^2 w^2 + i tau_i w) / (1 + tau_i^2 w^2) (eq. 19).
constexpr ComplexModulus complex_modulus(std::span<const MaxwellBranch> branches, double omega) noexcept {
  ComplexModulus m;
  for (const auto& b : branches) {
    const auto t = b.modulus_term(omega);
    m.real += t.real;
    m.imag += t.imag;
  }
  return m;
}

/// Damping ratio of a spring with these branches at omega (rad/s), eq. 19.
constexpr double damping_ratio(std::span<const MaxwellBranch> branches, double omega) noexcept {
  return complex_modulus(branches, omega).damping_ratio();
}

/// 1 + sum alpha_i: the high-frequency limit of |M_T|, the stiffness increase the branches impose.
constexpr double stiffness_factor(std::span<const MaxwellBranch> branches) noexcept {
  double s = 1.0;
  for (const auto& b : branches) s += b.alpha;
  return s;
}

/// Reduction of the critical timestep, 1 / sqrt(1 + sum alpha_i) (eq. 20).
constexpr double timestep_factor(std::span<const MaxwellBranch> branches) noexcept {
  return 1.0 / cmath::sqrt(stiffness_factor(branches));
}

/// Maxwell damping with N branches on every spring, the compile-time policy of the integrator.
template <int N>
struct Maxwell {
  static_assert(N >= 1 && N <= 8, "Maxwell<N>: 1 to 8 branches");
  static constexpr int num_branches = N;
  std::array<MaxwellBranch, static_cast<std::size_t>(N)> branches{};

  constexpr Maxwell() = default;
  constexpr explicit Maxwell(const std::array<MaxwellBranch, static_cast<std::size_t>(N)>& b) : branches(b) {}

  constexpr ComplexModulus complex_modulus(double omega) const noexcept {
    return damping::complex_modulus(branches, omega);
  }
  constexpr double damping_ratio(double omega) const noexcept { return damping::damping_ratio(branches, omega); }
  constexpr double timestep_factor() const noexcept { return damping::timestep_factor(branches); }

  // DampingPolicy: N branches in parallel with every spring. Branch i under a rate du/dt constant over the step
  // follows s_i' = alpha_i k du/dt - s_i / tau_i exactly: s_i <- s_i e^(-dt/tau_i) + alpha_i k tau_i (1 - e^(-dt/tau_i)) du/dt.
  using ContactState = std::array<double, static_cast<std::size_t>(N)>;  // branch stresses, Pa

  /// Precomputes e^(-dt/tau_i) and alpha_i tau_i (1 - e^(-dt/tau_i)) / dt for the timestep dt (s).
  void prepare(double dt) noexcept {
    for (int i = 0; i < N; ++i) {
      const auto& b = branches[static_cast<std::size_t>(i)];
      decay_[static_cast<std::size_t>(i)] = std::exp(-dt / b.tau);
      gain_[static_cast<std::size_t>(i)] = b.alpha * b.tau * (1.0 - decay_[static_cast<std::size_t>(i)]) / dt;
      inverse_alpha_[static_cast<std::size_t>(i)] = 1.0 / b.alpha;
    }
    // The contact field's last slot (sum_i F_i): its own decay, the others' excess over it (from expm1, without
    // cancellation), and the summed gain.
    const auto last = static_cast<std::size_t>(N - 1);
    gain_sum_ = 0.0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
      gain_sum_ += gain_[i];
      decay_excess_[i] = i < last ? std::expm1(-dt / branches[i].tau) - std::expm1(-dt / branches[last].tau) : 0.0;
    }
  }

  double spring_stress(ContactState& s, double stiffness, double du, double dt, bool active,
                       double& dissipated) const noexcept {
    // `dissipated` receives the work done on the branches; what they store (stored_energy) is subtracted when the
    // energy is reported, so that the loop needs no division.
    double total = 0.0;
    if (dt <= 0.0) {  // no time passes (first step, forces recomputed after a detection): no relaxation
      for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) total += active ? s[i] : 0.0;
      return total;
    }
    // The work on the branches, sum_i (old_i + updated_i) du / 2, from the two sums.
    const double kdu = stiffness * du;
    double old_total = 0.0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
      const double old = s[i];
      const double updated = active ? old * decay_[i] + gain_[i] * kdu : 0.0;
      s[i] = updated;
      old_total += old;
      total += updated;
    }
    dissipated += 0.5 * (old_total + total) * du;
    return total;
  }
  /// The sum of the branch stresses, Pa.
  static constexpr double held_stress(const ContactState& s) noexcept {
    double total = 0.0;
    for (const double branch : s) total += branch;
    return total;
  }
  // Branches in parallel with the elastic stiffness D of a whole constant-strain tetrahedron (the paper attaches
  // them to the internal elements as well as the joints): branch i carries a stress tensor S_i with
  // S_i <- S_i e^(-dt/tau_i) + alpha_i tau_i (1 - e^(-dt/tau_i)) D de / dt, the same update as on a spring, applied to
  // the elastic stress increment D de of the step. Branch-major storage: the six components of one branch are
  // contiguous, so that the update vectorises.
  using ElementState = std::array<std::array<double, 6>, static_cast<std::size_t>(N)>;  // Pa, xx yy zz xy yz zx

  /// Adds the branch stresses to `stress` (Pa), given the elastic stress increment `elastic_increment` (Pa) and the
  /// strain increment `strain_increment` (engineering shear strains) of the step dt (s); adds their work (J/m^3) to
  /// `dissipated` (what they still store is subtracted when the energy is reported: element_stored_energy).
  void element_stress(ElementState& s, const std::array<double, 6>& elastic_increment, const std::array<double, 6>& strain_increment,
                      double dt, std::array<double, 6>& stress, double& dissipated) const noexcept {
    if (dt <= 0.0) {  // no time passes: the branches summed first, as element_stress_tile does
      for (std::size_t c = 0; c < 6; ++c) {
        double sum = 0.0;
        for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) sum += s[i][c];
        stress[c] += sum;
      }
      return;
    }
    // One component at a time, over the branches: few values live at once, so that nothing is spilled to the stack.
    double work = 0.0;
    for (std::size_t c = 0; c < 6; ++c) {
      const double increment = elastic_increment[c];
      double old_sum = 0.0, new_sum = 0.0;
      for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
        const double old = s[i][c];
        const double updated = old * decay_[i] + gain_[i] * increment;
        s[i][c] = updated;
        old_sum += old;
        new_sum += updated;
      }
      stress[c] += new_sum;
      work += 0.5 * (old_sum + new_sum) * strain_increment[c];
    }
    dissipated += work;
  }

  // The same update for Width consecutive tetrahedra at once, one per SIMD lane. One tetrahedron's 6 N branch
  // stresses are few and each update is a short dependent chain, so that per element the update stays scalar;
  // across elements every operation is the same, and with the state stored [component][branch][lane] each one is a
  // contiguous vector over the tile. Per lane the operations and their order are those of element_stress.
  template <std::size_t Width>
  using ElementLanes = std::array<std::array<double, Width>, 6>;  // one value per component (xx yy zz xy yz zx) and lane
  template <std::size_t Width>
  struct alignas(64) ElementTile {
    std::array<std::array<std::array<double, Width>, static_cast<std::size_t>(N)>, 6> stress{};  // Pa, [component][branch][lane]
  };

  /// element_stress for the tile's elements: `branch_stress` receives the sum of the branch stresses (Pa), `work` the
  /// work on the branches (J/m^3; 0 when dt <= 0), per lane. Lanes past the last element hold zero increments (their
  /// branch stresses then stay zero).
  template <std::size_t Width>
  void element_stress_tile(ElementTile<Width>& tile, const ElementLanes<Width>& elastic_increment,
                           const ElementLanes<Width>& strain_increment, double dt, ElementLanes<Width>& branch_stress,
                           std::array<double, Width>& work) const noexcept {
    constexpr std::size_t n = static_cast<std::size_t>(N);
    if (dt <= 0.0) {  // no time passes (see element_stress)
      for (std::size_t c = 0; c < 6; ++c)
        for (std::size_t l = 0; l < Width; ++l) {
          double sum = 0.0;
          for (std::size_t i = 0; i < n; ++i) sum += tile.stress[c][i][l];
          branch_stress[c][l] = sum;
        }
      work.fill(0.0);
      return;
    }
    update_tile<Width>(tile.stress[0][0].data(), elastic_increment[0].data(), strain_increment[0].data(), decay_.data(),
                       gain_.data(), branch_stress[0].data(), work.data());
  }
  /// Energy in the element branches, sum_i (p_i^2 / (2K) + s_i : s_i / (4G)) / alpha_i, J/m^3 (bulk K, shear G in Pa).
  double element_stored_energy(const ElementState& s, double bulk, double shear) const noexcept {
    double e = 0.0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
      const auto& b = s[i];
      const double p = (b[0] + b[1] + b[2]) / 3.0;
      const double dev = (b[0] - p) * (b[0] - p) + (b[1] - p) * (b[1] - p) + (b[2] - p) * (b[2] - p) +
                         2.0 * (b[3] * b[3] + b[4] * b[4] + b[5] * b[5]);
      e += (0.5 * p * p / bulk + 0.25 * dev / shear) * inverse_alpha_[i];
    }
    return e;
  }

  constexpr double velocity_update(double v, double force, Inertia mass, double dt, double&) const noexcept {
    return undamped_velocity_update(v, force, mass, dt);
  }
  constexpr double timestep_factor(double) const noexcept { return timestep_factor(); }
  /// The three springs of a CP (normal, shear 1, shear 2; stiffnesses k_n, k_s, k_s) at once, equal to three
  /// spring_stress calls: one loop over the 3N branch stresses, which the compiler vectorises (a CP's branches are
  /// contiguous). The fused loop uses it when a policy provides it.
  std::array<double, 3> spring_stresses(std::array<ContactState, 3>& s, double kn, double ks, const std::array<double, 3>& du,
                                        double dt, bool active, double& dissipated) const noexcept {
    constexpr std::size_t n = static_cast<std::size_t>(N);
    std::array<double, 3> total{0.0, 0.0, 0.0};
    if (dt <= 0.0) {  // no time passes (see spring_stress)
      for (std::size_t j = 0; j < 3; ++j)
        for (std::size_t i = 0; i < n; ++i) total[j] += active ? s[j][i] : 0.0;
      return total;
    }
    const double on = active ? 1.0 : 0.0;  // a failed or open joint releases the branches
    const std::array<double, 3> kdu{kn * du[0], ks * du[1], ks * du[2]};
    std::array<double, 3> old_total{0.0, 0.0, 0.0};
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const double old = s[j][i];
        const double updated = on * (old * decay_[i] + gain_[i] * kdu[j]);
        s[j][i] = updated;
        old_total[j] += old;
        total[j] += updated;
      }
    dissipated += 0.5 * ((old_total[0] + total[0]) * du[0] + (old_total[1] + total[1]) * du[1] +
                         (old_total[2] + total[2]) * du[2]);
    return total;
  }

  // The branches of a whole contact between two rigid blocks, in one state per contact instead of one per CP.
  // A CP at plane coordinates (x1, x2) of a rigid contact has the elongation e = B(x1, x2) q, q the contact's
  // generalised elongation (e0_n, e0_1, e0_2 at the origin; relative rotation r_n, r_1, r_2, in the contact frame):
  //   e_n = e0_n + x2 r_1 - x1 r_2,   e_1 = e0_1 - x2 r_n,   e_2 = e0_2 + x1 r_n.
  // The branch update is linear, so while every CP of the contact is active its branch stresses are exactly
  // s_i = K B h_i (K = diag(k_n, k_s, k_s)) with one filtered elongation per branch, h_i <- h_i e^(-dt/tau_i) +
  // alpha_i tau_i (1 - e^(-dt/tau_i)) q / dt. Summed over the CPs (area a) they act on the contact with the
  // generalised force F_i = G h_i, G = sum a B^T K B (contact_stiffness), which follows the same update with G q
  // in place of q. The field keeps the F_i: six numbers per branch and contact instead of three per branch and CP,
  // per step one product G q, and the contact's force is R = sum_i F_i. Its last slot holds R itself instead of F_N
  // (branch_forces gives F_N = R - sum_(i<N) F_i), updated as R' = e^(-dt/tau_N) R + sum_(i<N) (e^(-dt/tau_i) -
  // e^(-dt/tau_N)) F_i + sum_i alpha_i tau_i (1 - e^(-dt/tau_i)) G q / dt: the force needs no sum over the
  // branches, nor the work one over their old values (Maxwell<3> 2-5 % faster). With the origin at the area
  // centroid of the CPs and t1 along a principal axis of their areas (sum a x1 = sum a x2 = sum a x1 x2 = 0), as
  // ContactGroup keeps every contact, G is diagonal and G q six products. The per-CP stresses K B h_i follow from
  // h_i = G^+ F_i (ContactGroup::field_elongations), exact at the CPs also where G is singular. When a CP releases
  // its branches (it fails or opens), the contact goes over to the per-CP state (spring_stresses), from the
  // field's values at its CPs.
  using Generalised = std::array<double, 6>;  // e0_n, e0_1, e0_2 (m); r_n, r_1, r_2 (rad); or the forces (N, N m)
  // F_1 .. F_(N-1), then sum_i F_i (N, N m; force along n, t1, t2, then moment about the origin along n, t1, t2).
  using ContactField = std::array<Generalised, static_cast<std::size_t>(N)>;
  /// The diagonal of a contact's stiffness G on its generalised elongation (contact_stiffness): N/m for the three
  /// elongations, N m for the three rotations.
  using FieldStiffness = Generalised;
  /// Contacts between rigid blocks start in the field form; false keeps every CP's own branch state from the start
  /// (the reference the field form is tested against).
  bool contact_field = true;
  /// Its bool members, which a checkpoint reader checks (io/checkpoint.hpp).
  static constexpr std::array<bool Maxwell::*, 1> checkpoint_flags() { return {&Maxwell::contact_field}; }

  /// The fields of four contacts, one per lane, as the contact pass advances them (ContactGroup keeps them so):
  /// forces[i][j] holds component j of F_i (the last slot their sum, as in ContactField), stiffness[stiffness_slot(j)]
  /// component j of diag G, work twice the branches' viscous work. diag G has five distinct components (its two
  /// shear ones are both k_s A, contact_stiffness), so that a record is (6 N + 6) vectors of four, whole cache lines:
  /// the contact pass streams the records, and fewer bytes per contact make the Maxwell steps less sensitive to
  /// what else uses the memory.
  struct alignas(64) FieldLanes {
    Lanes forces[static_cast<std::size_t>(N)][6];
    Lanes stiffness[5];
    Lanes work;
  };
  static_assert(sizeof(FieldLanes) == (6 * N + 6) * sizeof(Lanes), "a field record is whole cache lines, unpadded");
  /// The slot of FieldLanes::stiffness that holds component j of diag G: G_11 and G_22 share slot 1.
  static constexpr std::size_t stiffness_slot(std::size_t j) noexcept { return j < 2 ? j : j - 1; }
  /// Component j of the generalised force sum_i F_i of four fields, one per lane (N, N m; the last slot, as in
  /// ContactField).
  [[gnu::always_inline]] static Lanes field_sum(const FieldLanes& f, std::size_t j) noexcept {
    return f.forces[static_cast<std::size_t>(N - 1)][j];
  }
  /// Advances the fields of four contacts, one per lane, by one step of the timestep prepared for (prepare; only
  /// when time passes: with none, the fields are unchanged and field_force gives their force) under each
  /// contact's generalised displacement increment du = -q (du0 at the origin, relative rotation w; the contact
  /// pass's increments as they are, closing and sliding positive; du[j]: the lanes of component j). Adds each
  /// field's work over the step, sum over CPs of a (old + new) / 2 . B q = q . sum_i (F_i before + F_i after) / 2,
  /// twice, to f.work; field_sum then gives the generalised force at the end of the step, sum_i F_i (N, N m).
  /// Taking du instead of q saves negating six numbers per step: G q = -G du, and q . R = -du . R. Every lane is
  /// advanced (the overload with a mask advances only some).
  [[gnu::always_inline]] void advance_field(FieldLanes& f, const Lanes (&du)[6]) const noexcept {
    constexpr std::size_t last = static_cast<std::size_t>(N - 1);
    // The factors in locals: the stores to the field could otherwise change them (both are doubles), and the
    // compiler would load them again for every component.
    const auto decay = decay_, gain = gain_, decay_excess = decay_excess_;
    const double gain_sum = gain_sum_;
    Lanes w = f.work;
    for (std::size_t j = 0; j < 6; ++j) {
      const Lanes g = f.stiffness[stiffness_slot(j)] * du[j];  // G du = -G q
      const Lanes r = f.forces[last][j];       // sum_i F_i before the step
      Lanes n = r * decay[last] - gain_sum * g;
      for (std::size_t i = 0; i < last; ++i) {
        const Lanes fi = f.forces[i][j];
        n += decay_excess[i] * fi;
        f.forces[i][j] = fi * decay[i] - gain[i] * g;
      }
      w -= (r + n) * du[j];
      f.forces[last][j] = n;
    }
    f.work = w;
  }
  /// advance_field for the lanes where `keep` is set, giving in `sum` their generalised force at the end of the step;
  /// the others keep their values and give a zero force in `sum` (contacts whose CPs hold their own branch states,
  /// and the lanes without a contact at the end of a group).
  /// Every lane is advanced and the others put back from a copy, so that the advance has no selection. Rare, and
  /// not inlined: inlined beside advance_field, the compiler would load the copy's values with the advance's and
  /// keep them for this path, on the stack, in every group.
  [[gnu::noinline, gnu::cold]] void advance_field(FieldLanes& f, const Lanes (&du)[6], const LaneMask& keep,
                                                  Lanes (&sum)[6]) const noexcept {
    const FieldLanes before = f;
    advance_field(f, du);
    for (std::size_t j = 0; j < 6; ++j) sum[j] = select(keep, field_sum(f, j), Lanes::zero());
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i)
      for (std::size_t j = 0; j < 6; ++j) f.forces[i][j] = select(keep, f.forces[i][j], before.forces[i][j]);
    f.work = select(keep, f.work, before.work);
  }
  /// field_force for four contacts, one per lane (zero where `keep` is not set).
  static void field_force(const FieldLanes& f, const LaneMask& keep, Lanes (&sum)[6]) noexcept {
    for (std::size_t j = 0; j < 6; ++j) sum[j] = select(keep, f.forces[static_cast<std::size_t>(N - 1)][j], Lanes::zero());
  }
  /// The branches' forces F_i of a field (N, N m): the last one from the sum the field keeps.
  static std::array<Generalised, static_cast<std::size_t>(N)> branch_forces(const ContactField& f) noexcept {
    std::array<Generalised, static_cast<std::size_t>(N)> forces{};
    constexpr std::size_t last = static_cast<std::size_t>(N - 1);
    for (std::size_t j = 0; j < 6; ++j) {
      double rest = f[last][j];
      for (std::size_t i = 0; i < last; ++i) {
        forces[i][j] = f[i][j];
        rest -= f[i][j];
      }
      forces[last][j] = rest;
    }
    return forces;
  }
  /// The field of the branch forces F_i (N, N m): branch_forces inverted.
  static ContactField field_of(const std::array<Generalised, static_cast<std::size_t>(N)>& forces) noexcept {
    ContactField f{};
    constexpr std::size_t last = static_cast<std::size_t>(N - 1);
    for (std::size_t j = 0; j < 6; ++j) {
      double sum = 0.0;
      for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) sum += forces[i][j];
      for (std::size_t i = 0; i < last; ++i) f[i][j] = forces[i][j];
      f[last][j] = sum;
    }
    return f;
  }
  /// K B(x1, x2) h: the stresses (Pa; normal, shear 1, shear 2) of a field value h at a CP.
  static constexpr std::array<double, 3> field_stress(const Generalised& h, double kn, double ks, double x1, double x2) noexcept {
    return {kn * (h[0] + x2 * h[4] - x1 * h[5]), ks * (h[1] - x2 * h[3]), ks * (h[2] + x1 * h[3])};
  }
  /// G = sum_CPs a B^T K B, the stiffness of a contact on its generalised elongation (N/m, N m), of which only the
  /// diagonal is not zero when the origin is the area centroid of the CPs and t1 a principal axis of their areas:
  /// diag(k_n A, k_s A, k_s A, k_s (I_1 + I_2), k_n I_2, k_n I_1), A = sum a, I_1 = sum a x1^2, I_2 = sum a x2^2.
  static constexpr FieldStiffness contact_stiffness(double area, double i1, double i2, double kn, double ks) noexcept {
    return {kn * area, ks * area, ks * area, ks * (i1 + i2), kn * i2, kn * i1};
  }
  /// The per-CP branch stresses K B(x1, x2) h_i at (x1, x2) of a field in elongation form (h_i, one per branch):
  /// s[direction][branch].
  static std::array<ContactState, 3> field_branch_stresses(const std::array<Generalised, static_cast<std::size_t>(N)>& f,
                                                           double kn, double ks, double x1, double x2) noexcept {
    std::array<ContactState, 3> s{};
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
      const auto branch = field_stress(f[i], kn, ks, x1, x2);
      for (std::size_t j = 0; j < 3; ++j) s[j][i] = branch[j];
    }
    return s;
  }

  /// Energy in the branch springs, sum s_i^2 / (2 alpha_i k), J/m^2.
  double stored_energy(const ContactState& s, double stiffness) const noexcept {
    double e = 0.0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) e += 0.5 * s[i] * s[i] * inverse_alpha_[i] / stiffness;
    return e;
  }

 private:
  // The kernel of element_stress_tile, on restrict parameters: GCC honours restrict on parameters, and without it
  // the alias checks between the tile and the increments exceed its limit and the loop stays scalar. Components
  // outermost and lanes innermost, with the branches unrolled inside: the tile is then read and written in address
  // order (a stream the hardware prefetches; lanes innermost over all 6 N rows at once touched 72 cache lines
  // alternately and cost more than the vectors saved), and every access is a full vector.
  template <std::size_t Width>
  static void update_tile(double* __restrict state, const double* __restrict elastic, const double* __restrict strain,
                          const double* __restrict decay, const double* __restrict gain, double* __restrict branch,
                          double* __restrict work) noexcept {
    constexpr std::size_t n = static_cast<std::size_t>(N);
    for (std::size_t l = 0; l < Width; ++l) work[l] = 0.0;
    for (std::size_t c = 0; c < 6; ++c) {
      double* __restrict const row = state + c * n * Width;
      for (std::size_t l = 0; l < Width; ++l) {
        const double increment = elastic[c * Width + l];
        double old_sum = 0.0, new_sum = 0.0;
#pragma GCC unroll 8
        for (std::size_t i = 0; i < n; ++i) {
          const double old = row[i * Width + l];
          const double updated = old * decay[i] + gain[i] * increment;
          row[i * Width + l] = updated;
          old_sum += old;
          new_sum += updated;
        }
        branch[c * Width + l] = new_sum;
        work[l] += 0.5 * (old_sum + new_sum) * strain[c * Width + l];
      }
    }
  }

  std::array<double, static_cast<std::size_t>(N)> decay_{};
  std::array<double, static_cast<std::size_t>(N)> gain_{};
  std::array<double, static_cast<std::size_t>(N)> inverse_alpha_{};
  std::array<double, static_cast<std::size_t>(N)> decay_excess_{};  // e^(-dt/tau_i) - e^(-dt/tau_N), 0 for i = N
  double gain_sum_ = 0.0;
};

}  // namespace blockdem::damping
