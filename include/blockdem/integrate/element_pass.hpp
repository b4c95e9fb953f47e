#pragma once
// The element pass (DESIGN.md §4, step 2): constant-strain tetrahedra, strain increment from the nodal velocities
// v(n-1/2) over the last move -> Hooke -> damping -> nodal forces stored per element, gathered by the node pass.
//
// Damping inside a tetrahedron: the policy's `spring_stress` is applied to seven independent strain components in
// parallel with the element's elastic stiffness: the volumetric strain with the bulk modulus K, the three deviatoric
// normal strains with 2G and the three engineering shear strains with G. Hooke's law is exactly K tr(e) I + 2G dev(e),
// so a Maxwell branch of fraction alpha (or a dashpot beta k) on each component is a branch alpha D (or beta D) on the
// whole element, and the branch energies s^2 / (2 alpha k) add up to the element's. A policy with a tensor form
// (damping::ElementTileDamping, Maxwell<N>: one branch stress tensor updated with the elastic stress increment) does
// the same, equivalent and cheaper (6 components instead of 7), across a tile of elements at once, one per SIMD lane.

#include <algorithm>
#include <array>
#include <cstddef>

#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/geometry/tetrahedral_mesh.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/parallel/thread_ranges.hpp"

namespace blockdem {

namespace detail {

/// dt times the symmetric part of grad v = sum_i v_i (x) grad N_i: xx yy zz and the engineering shear strains
/// xy yz zx. Summed component by component: through a 3 x 3 temporary, GCC packed pairs through the stack, a
/// store-forwarding stall per node.
inline std::array<double, 6> strain_increment(const Vec3* __restrict velocity, const geometry::Tetrahedron& nodes,
                                              const std::array<Vec3, 4>& g, double dt) {
  double exx = 0.0, eyy = 0.0, ezz = 0.0, gxy = 0.0, gyz = 0.0, gzx = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec3& u = velocity[nodes[k]];
    const Vec3& b = g[k];
    exx += u[0] * b[0];
    eyy += u[1] * b[1];
    ezz += u[2] * b[2];
    gxy += u[0] * b[1] + u[1] * b[0];
    gyz += u[1] * b[2] + u[2] * b[1];
    gzx += u[2] * b[0] + u[0] * b[2];
  }
  return {exx * dt, eyy * dt, ezz * dt, gxy * dt, gyz * dt, gzx * dt};
}

/// f_i = -V sigma grad N_i (N), with -V sigma formed first: each force component is then a plain sum. Scaling the
/// vector sigma grad N_i instead made GCC pack components in pairs, through the stack when registers ran out.
inline void element_forces(double v, const std::array<double, 6>& total, const std::array<Vec3, 4>& g,
                           std::array<Vec3, 4>& f) {
  const double sxx = -v * total[0], syy = -v * total[1], szz = -v * total[2], sxy = -v * total[3],
               syz = -v * total[4], szx = -v * total[5];
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec3& b = g[k];
    f[k] = Vec3(sxx * b[0] + sxy * b[1] + szx * b[2], sxy * b[0] + syy * b[1] + syz * b[2], szx * b[0] + syz * b[1] + szz * b[2]);
  }
}

/// K and G (Pa) of every material, from E and nu once per pass: per element they cost two divisions.
template <class State>
const std::array<double, 2>* material_moduli_of(State& state, const model::Model& m) {
  const auto& materials = m.deformable.materials;
  state.material_moduli.resize(materials.size());  // sized in setup: allocates only if materials were added since
  for (std::size_t i = 0; i < materials.size(); ++i) state.material_moduli[i] = {materials[i].bulk(), materials[i].shear()};
  return state.material_moduli.data();
}

/// The element pass of the other policies over the tiles [first_tile, end_tile), on the calling thread: the seven
/// strain components' springs per element (spring_stress). moduli: material_moduli_of.
template <class State, class Damping>
void element_springs_range(State& state, model::Model& m, const Damping& damping, double increment_dt,
                           const std::array<double, 2>* __restrict moduli, std::size_t first_tile, std::size_t end_tile) {
  auto& te = m.deformable.tetrahedra;
  const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
  const auto count = te.size();
  for (std::size_t tile = first_tile; tile < end_tile; ++tile) {
    const std::size_t first = tile * State::element_tile;
    const std::size_t last = std::min(first + State::element_tile, count);
    double viscous = 0.0;  // J, on this tile's dashpots
    for (std::size_t t = first; t < last; ++t) {
      const auto& g = te.gradient[t];
      const auto [exx, eyy, ezz, gxy, gyz, gzx] = strain_increment(velocity, te.node[t], g, increment_dt);
      const double ev = exx + eyy + ezz;
      const auto [bulk, shear] = moduli[te.material[t]];
      auto& s = te.stress[t];
      const double dp = bulk * ev;
      const double dxx = exx - ev / 3.0, dyy = eyy - ev / 3.0, dzz = ezz - ev / 3.0;
      s[0] += dp + 2.0 * shear * dxx;
      s[1] += dp + 2.0 * shear * dyy;
      s[2] += dp + 2.0 * shear * dzz;
      s[3] += shear * gxy;
      s[4] += shear * gyz;
      s[5] += shear * gzx;
      std::array<double, 6> total = s;
      double dissipated = 0.0;
      if constexpr (damping::PerSpringDamping<Damping>) {
        auto& st = state.element_state[t];
        const double p = damping.spring_stress(st[0], bulk, ev, increment_dt, true, dissipated);
        total[0] += p + damping.spring_stress(st[1], 2.0 * shear, dxx, increment_dt, true, dissipated);
        total[1] += p + damping.spring_stress(st[2], 2.0 * shear, dyy, increment_dt, true, dissipated);
        total[2] += p + damping.spring_stress(st[3], 2.0 * shear, dzz, increment_dt, true, dissipated);
        total[3] += damping.spring_stress(st[4], shear, gxy, increment_dt, true, dissipated);
        total[4] += damping.spring_stress(st[5], shear, gyz, increment_dt, true, dissipated);
        total[5] += damping.spring_stress(st[6], shear, gzx, increment_dt, true, dissipated);
      }
      const double v = te.volume[t];
      element_forces(v, total, g, state.element_force[t]);
      viscous += v * dissipated;
    }
    state.element_viscous[tile] += viscous;
  }
}

/// The element pass of the tensor form over the tiles [first_tile, end_tile), on the calling thread, one tile of
/// element_tile elements at a time: the increments of the tile's
/// elements (per element), the branch update (across the tile's elements, damping.element_stress_tile), then the
/// forces (per element). Per element the same operations in the same order as element_stress.
template <class State, class Damping>
void element_tiles_range(State& state, model::Model& m, const Damping& damping, double increment_dt,
                         const std::array<double, 2>* __restrict moduli, std::size_t first_tile, std::size_t end_tile) {
  constexpr std::size_t lanes = State::element_tile;
  using TileLanes = typename Damping::template ElementLanes<lanes>;
  auto& te = m.deformable.tetrahedra;
  const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
  const auto count = te.size();
  alignas(64) TileLanes elastic, strain, branch;  // Pa, -, Pa: per component and element of the tile
  alignas(64) std::array<double, lanes> work;  // J/m^3
  for (std::size_t tile = first_tile; tile < end_tile; ++tile) {
    const std::size_t begin = tile * lanes;
    const std::size_t n = std::min(lanes, count - begin);
    double viscous = 0.0;  // J, on this tile's branches
    // The next tile's branch stresses are fetched while this tile's increments are computed: the branch update
    // reads and writes a whole tile in a burst (4.6 kB for Maxwell<3>), faster than the hardware prefetcher
    // brings it in, and stalled on its loads.
    const std::size_t next = tile + 1;
    const char* const ahead = next < end_tile ? reinterpret_cast<const char*>(&state.element_state[next]) : nullptr;
    constexpr std::size_t ahead_step = (sizeof(typename State::ElementState) + lanes - 1) / lanes;  // bytes per element, <= 3 lines
    static_assert(ahead_step <= 192, "three cache lines per element");
    for (std::size_t l = 0; l < n; ++l) {
      const std::size_t t = begin + l;
      if (ahead != nullptr)
        for (std::size_t b = 0; b < ahead_step; b += 64) __builtin_prefetch(ahead + l * ahead_step + b, 1);
      const auto [exx, eyy, ezz, gxy, gyz, gzx] = strain_increment(velocity, te.node[t], te.gradient[t], increment_dt);
      const double ev = exx + eyy + ezz;
      const auto [bulk, shear] = moduli[te.material[t]];
      const double dp = bulk * ev;
      const double dxx = exx - ev / 3.0, dyy = eyy - ev / 3.0, dzz = ezz - ev / 3.0;
      const double d[6] = {dp + 2.0 * shear * dxx, dp + 2.0 * shear * dyy, dp + 2.0 * shear * dzz,
                           shear * gxy, shear * gyz, shear * gzx};
      const double e[6] = {exx, eyy, ezz, gxy, gyz, gzx};
      auto& s = te.stress[t];
      for (std::size_t k = 0; k < 6; ++k) {
        s[k] += d[k];
        elastic[k][l] = d[k];
        strain[k][l] = e[k];
      }
    }
    for (std::size_t k = 0; k < 6; ++k)  // a last, partial tile: no increment on the lanes past the last element
      for (std::size_t l = n; l < lanes; ++l) elastic[k][l] = strain[k][l] = 0.0;
    damping.element_stress_tile(state.element_state[tile], elastic, strain, increment_dt, branch, work);
    for (std::size_t l = 0; l < n; ++l) {
      const std::size_t t = begin + l;
      const auto& s = te.stress[t];
      const std::array<double, 6> total{s[0] + branch[0][l], s[1] + branch[1][l], s[2] + branch[2][l],
                                        s[3] + branch[3][l], s[4] + branch[4][l], s[5] + branch[5][l]};
      const double v = te.volume[t];
      element_forces(v, total, te.gradient[t], state.element_force[t]);
      viscous += v * work[l];
    }
    state.element_viscous[tile] += viscous;
  }
}

}  // namespace detail

/// The element tiles [first_tile, end_tile) on the calling thread (element_pass). moduli: material_moduli_of, taken
/// outside the parallel region (it may allocate).
template <class State, class Damping>
void element_range(State& state, model::Model& m, const Damping& damping, double increment_dt,
                   const std::array<double, 2>* moduli, std::size_t first_tile, std::size_t end_tile) {
  if constexpr (State::tensor_form) detail::element_tiles_range(state, m, damping, increment_dt, moduli, first_tile, end_tile);
  else detail::element_springs_range(state, m, damping, increment_dt, moduli, first_tile, end_tile);
}

/// Constant-strain tetrahedra of the deformable state: strain increment from v(n-1/2) over the last move,
/// stress, damping, nodal forces (state.element_force) and the damping work (state.element_viscous), over the threads
/// by state.tile_bounds (parallel/thread_ranges.hpp).
template <class State, class Damping>
void element_pass(State& state, model::Model& m, const Damping& damping, double increment_dt) {
  const auto* moduli = detail::material_moduli_of(state, m);
  const std::size_t count = m.deformable.tetrahedra.size();
#pragma omp parallel if (count > 1024)
  {
    const auto [first_tile, end_tile] = parallel::my_range(state.tile_bounds, State::element_tiles(count));
    element_range(state, m, damping, increment_dt, moduli, first_tile, end_tile);
  }
}

}  // namespace blockdem
