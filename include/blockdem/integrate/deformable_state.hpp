#pragma once
// The integrator's state of the deformable blocks, the trusses and the node contacts (DESIGN.md §4, paper Sect.
// 3.1-3.2): node contact groups (rigid face side and deformable face side, one per law and kind), element damping
// states and forces, truss forces, node energies and inverse masses, the real masses of density-scaled rigid blocks,
// and the gather lists through which every node and block sums its own contributions in a fixed order (no atomics:
// results do not depend on the number of threads). The passes over it are in integrate/element_pass.hpp and
// integrate/node_pass.hpp, its contact assignment in integrate/node_contact_assignment.hpp.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/integrate/frequency_bound.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/kinematics/concepts.hpp"
#include "blockdem/kinematics/node_contact_group.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/parallel/thread_ranges.hpp"

namespace blockdem {

/// Energy terms of the deformable part (J), added to the simulation's report.
struct DeformableEnergy {
  double kinetic = 0, elastic = 0, gravity_work = 0, viscous = 0, slip = 0;
  double base_work = 0;  // done by dashpots anchored to the table (damping/frame.hpp)
};

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
class DeformableState {
 public:
  template <contact::ContactLaw L>
  using RigidFaceGroup = kinematics::NodeContactGroup<L, Damping, kinematics::Rigid>;
  template <contact::ContactLaw L>
  using DeformableFaceGroup = kinematics::NodeContactGroup<L, Damping, kinematics::Deformable>;
  using Groups = std::tuple<RigidFaceGroup<Laws>..., DeformableFaceGroup<Laws>...>;
  /// Elements per tile of the tensor form: fixed, so that which elements share a vector does not depend on the
  /// number of threads. With 32, a tile's branch stresses (4.6 kB for Maxwell<3>), its increment buffers and the
  /// gradients it reads twice fit the L1 cache together. 64 was slower (22.7 against 19.9 ms per step on the
  /// benchmark wall with Maxwell<3>); 16 was not distinguishable from 32.
  static constexpr std::size_t element_tile = 32;
  /// Policies with a tensor form for whole elements (Maxwell<N>: element_stress_tile) keep their own element state,
  /// per tile of element_tile elements; the others act on the seven strain components (volumetric, 3 deviatoric
  /// normal, 3 shear), per element.
  static constexpr bool tensor_form = damping::ElementTileDamping<Damping, element_tile>;
  using ElementState = typename decltype([] {
    if constexpr (tensor_form) return std::type_identity<typename Damping::template ElementTile<element_tile>>{};
    else return std::type_identity<std::array<typename Damping::ContactState, 7>>{};
  }())::type;

  Groups groups;
  std::vector<ElementState> element_state;  // per tile (tensor form) or per element
  std::vector<std::array<Vec3, 4>> element_force;  // N, on the element's nodes
  /// The work on the element dashpots or branches is summed per tile of element_tile elements: a fixed grouping, so
  /// that the sums (and the energy report) depend neither on the number of threads nor on their ranges. A
  /// per-element array cost 16 bytes read and written per element-step; per tile it is half a byte.
  std::vector<double> element_viscous;              // J, work on the element dashpots / branches, per tile
  std::vector<Vec3> truss_force;                    // N, on end 0 (end 1 gets the opposite)
  std::vector<double> node_inverse_mass;            // 1/kg
  std::vector<double> node_kinetic, node_gravity_work, node_viscous;
  std::vector<double> node_frame_work;  // J: done by dashpots anchored to the table (damping/frame.hpp)
  std::vector<Vec3> extra_force, extra_moment;      // N, N m, on rigid blocks: node contacts, trusses, weight correction
  std::vector<double> rigid_real_mass;              // kg, before density scaling
  std::vector<Vec3> rigid_real_inertia;             // kg m^2, idem
  double extra_work = 0;                            // J, work of the weight correction of scaled rigid blocks
  double retired_slip = 0, retired_viscous = 0;
  std::vector<Vec3> detected_node_position;
  std::vector<std::array<double, 6>> element_pair_norm;  // N/m, ||K_ij||_2 of each element's node pairs (FrequencyBound)
  /// The threads' ranges over the nodes, the element tiles and each group's contact points (parallel/thread_ranges.hpp),
  /// for a team of parallel::available_threads(): runs of whole blocks. Made with the contact lists; not saved.
  parallel::Bounds node_bounds, tile_bounds;
  std::array<parallel::Bounds, 2 * sizeof...(Laws)> contact_bounds;

  static constexpr std::size_t element_tiles(std::size_t elements) { return (elements + element_tile - 1) / element_tile; }

  template <class F>
  void for_each_group(F&& f) {
    std::apply([&](auto&... g) { (f(g), ...); }, groups);
  }
  template <class F>
  void for_each_group(F&& f) const {
    std::apply([&](const auto&... g) { (f(g), ...); }, groups);
  }

  /// Sizes the arrays and builds the gather lists: the static ones (elements and trusses to nodes) and those of the
  /// node contacts and rigid truss ends (for the groups as they are: empty before the first assign()), so that the
  /// state can step right after setup, also when no assign() follows (a rigid-only model switched to the mixed step
  /// by density scaling).
  void setup(const model::Model& m) {
    const auto& nd = m.deformable.nodes;
    const auto& te = m.deformable.tetrahedra;
    element_state.assign(tensor_form ? (te.size() + element_tile - 1) / element_tile : te.size(), ElementState{});
    element_force.assign(te.size(), {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
    element_viscous.assign(element_tiles(te.size()), 0.0);
    material_moduli.assign(m.deformable.materials.size(), {0.0, 0.0});
    element_pair_norm.resize(te.size());
    for (std::size_t t = 0; t < te.size(); ++t) {
      const auto& mat = m.deformable.materials[te.material[t]];
      element_pair_norm[t] = FrequencyBound::tetrahedron_pair_norms(te.gradient[t], te.volume[t], mat.bulk(), mat.shear());
    }
    truss_force.assign(m.deformable.trusses.size(), Vec3::Zero());
    node_inverse_mass.resize(nd.size());
    for (std::size_t i = 0; i < nd.size(); ++i) node_inverse_mass[i] = 1.0 / nd.mass[i];
    node_kinetic.assign(nd.size(), 0.0);
    for (std::size_t i = 0; i < nd.size(); ++i) node_kinetic[i] = 0.5 * nd.mass[i] * nd.velocity[i].squaredNorm();
    node_gravity_work.assign(nd.size(), 0.0);
    node_viscous.assign(nd.size(), 0.0);
    node_frame_work.assign(nd.size(), 0.0);
    extra_force.assign(m.bodies.size(), Vec3::Zero());
    extra_moment.assign(m.bodies.size(), Vec3::Zero());
    if (rigid_real_mass.size() != m.bodies.size()) {  // kept over a second setup: the blocks may be scaled by then
      rigid_real_mass = m.bodies.mass;
      rigid_real_inertia = m.bodies.principal_inertia;
    }
    // Element entries of each node: 4 t + k, in increasing order.
    element_first.assign(nd.size() + 1, 0);
    for (const auto& e : te.node)
      for (auto n : e) ++element_first[n + 1];
    for (std::size_t i = 0; i < nd.size(); ++i) element_first[i + 1] += element_first[i];
    element_entry.assign(element_first.back(), 0);
    std::vector<std::uint32_t> next(element_first.begin(), element_first.end() - 1);
    for (std::size_t t = 0; t < te.size(); ++t)
      for (std::uint32_t k = 0; k < 4; ++k) element_entry[next[te.node[t][k]]++] = static_cast<std::uint32_t>(4 * t + k);
    truss_first.assign(nd.size() + 1, 0);
    const auto& trusses = m.deformable.trusses;
    for (const auto& t : trusses)
      for (const auto& e : t.end)
        if (e.node >= 0) ++truss_first[static_cast<std::size_t>(e.node) + 1];
    for (std::size_t i = 0; i < nd.size(); ++i) truss_first[i + 1] += truss_first[i];
    truss_entry.assign(truss_first.back(), 0);
    next.assign(truss_first.begin(), truss_first.end() - 1);
    for (std::size_t t = 0; t < trusses.size(); ++t)
      for (std::uint32_t s = 0; s < 2; ++s)
        if (trusses[t].end[s].node >= 0) truss_entry[next[static_cast<std::size_t>(trusses[t].end[s].node)]++] = static_cast<std::uint32_t>(2 * t + s);
    detected_node_position = nd.position;
    build_contact_lists(m);
  }

  /// The branch stresses of element t (tensor form), gathered from its tile: Damping::ElementState, Pa.
  auto element_branch_stress(std::size_t t) const requires tensor_form {
    typename Damping::ElementState s{};
    const auto& tile = element_state[t / element_tile];
    for (std::size_t i = 0; i < s.size(); ++i)
      for (std::size_t c = 0; c < 6; ++c) s[i][c] = tile.stress[c][i][t % element_tile];
    return s;
  }

  /// Copies the contact histories (not the damping state) and the real rigid masses from the state of another
  /// damping policy. The inverse node masses come from the model's present masses (setup), not from `other`.
  template <class Other>
  void take_over(const Other& other, const model::Model& m) {
    rigid_real_mass = other.rigid_real_mass;
    rigid_real_inertia = other.rigid_real_inertia;
    setup(m);
    copy_groups(other.groups, std::make_index_sequence<2 * sizeof...(Laws)>{});
    node_kinetic = other.node_kinetic;
    build_contact_lists(m);
  }

  // ---- timestep and energy ----

  /// Adds the stiffness (N/m) of the node contacts, elements and trusses: to each node (k_node), and to the rigid
  /// blocks (translation, and rotation k r^2).
  void add_stiffness(const model::Model& m, std::vector<double>& k_node, std::vector<double>& k_translation,
                     std::vector<double>& k_rotation) const {
    const auto& te = m.deformable.tetrahedra;
    k_node.assign(m.deformable.nodes.size(), 0.0);
    for (std::size_t t = 0; t < te.size(); ++t)
      for (auto n : te.node[t]) k_node[n] += te.stiffness[t];  // eq. 2
    for_each_group([&](const auto& g) {
      using G = std::remove_cvref_t<decltype(g)>;
      using L = typename G::LawType;
      for (std::size_t k = 0; k < g.size(); ++k) {
        const auto& p = g.properties[g.property[k]];
        const double s = std::max(L::normal_stiffness(p), L::shear_stiffness(p)) * g.area[k];
        k_node[g.node[k]] += s;
        if constexpr (G::FaceKinematics::deformable) {
          for (auto n : g.triangle[k]) k_node[n] += s;
        } else {
          const std::size_t b = g.face_block[k];
          k_translation[b] += s;
          k_rotation[b] += s * rotate(m.bodies.rotation[b], g.point_local[k]).squaredNorm();
        }
      }
    });
    for (const auto& tr : m.deformable.trusses) {
      const double s = tr.axial_stiffness();
      for (const auto& e : tr.end) {
        if (e.node >= 0) {
          k_node[static_cast<std::size_t>(e.node)] += s;
        } else {
          k_translation[e.block] += s;
          k_rotation[e.block] += s * e.body_point.squaredNorm();
        }
      }
    }
  }

  /// Adds the elements and the node contacts to an upper bound on omega_max (the trusses are the caller's).
  template <class Bound>
  void add_to(const model::Model& m, Bound& bound) const {
    const auto& te = m.deformable.tetrahedra;
    const auto& materials = m.deformable.materials;
    for (std::size_t t = 0; t < te.size(); ++t) {
      const auto& mat = materials[te.material[t]];
      bound.tetrahedron(te.node[t], te.gradient[t], te.volume[t], mat.bulk(), mat.shear(),
                        element_pair_norm.size() == te.size() ? &element_pair_norm[t] : nullptr);
    }
    const auto& x = m.deformable.nodes.position;
    for_each_group([&](const auto& g) {
      using G = std::remove_cvref_t<decltype(g)>;
      using L = typename G::LawType;
      for (std::size_t k = 0; k < g.size(); ++k) {
        const auto& p = g.properties[g.property[k]];
        const double kn = L::normal_stiffness(p), ks = L::shear_stiffness(p);
        Vec3 n;
        if constexpr (G::FaceKinematics::deformable) {
          const auto& tri = g.triangle[k];
          n = (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).normalized();
        } else {
          n = rotate(m.bodies.rotation[g.face_block[k]], g.normal_local[k]);
        }
        const Mat3 nn = n * n.transpose();
        const Mat3 d = g.area[k] * (kn * nn + ks * (Mat3::Identity() - nn));
        const auto node = Bound::node_point(g.node[k]);
        if constexpr (G::FaceKinematics::deformable) {
          const auto& tri = g.triangle[k];
          const auto& w = g.weight[k];
          bound.spring({node}, {Bound::node_point(tri[0], w[0]), Bound::node_point(tri[1], w[1]), Bound::node_point(tri[2], w[2])}, d);
        } else {
          const std::size_t fb = g.face_block[k];
          bound.spring({node}, {Bound::block_point(fb, m.bodies.position[fb] + rotate(m.bodies.rotation[fb], g.point_local[k]))}, d);
        }
      }
    });
  }

  DeformableEnergy energy(const model::Model& m, const Damping& damping) const {
    DeformableEnergy e;
    e.slip = retired_slip;
    e.viscous = retired_viscous;
    for (std::size_t i = 0; i < node_kinetic.size(); ++i) {
      e.kinetic += node_kinetic[i];
      e.gravity_work += node_gravity_work[i];
      e.viscous += node_viscous[i];
      e.base_work += node_frame_work[i];
    }
    e.gravity_work += extra_work;
    for (double w : element_viscous) e.viscous += w;
    const auto& te = m.deformable.tetrahedra;
    for (std::size_t t = 0; t < te.size(); ++t) {
      const auto& s = te.stress[t];
      const auto& mat = m.deformable.materials[te.material[t]];
      const double bulk = mat.bulk(), shear = mat.shear();
      const double p = (s[0] + s[1] + s[2]) / 3.0;
      const double dev = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p) +
                         2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
      e.elastic += te.volume[t] * (0.5 * p * p / bulk + 0.25 * dev / shear);
      if constexpr (tensor_form) {
        const double branches = damping.element_stored_energy(element_branch_stress(t), bulk, shear);
        e.elastic += te.volume[t] * branches;
        e.viscous -= te.volume[t] * branches;
      } else if constexpr (damping::SpringEnergyDamping<Damping>) {
        const auto& st = element_state[t];
        double branches = damping.stored_energy(st[0], bulk);
        for (std::size_t c = 1; c < 4; ++c) branches += damping.stored_energy(st[c], 2.0 * shear);
        for (std::size_t c = 4; c < 7; ++c) branches += damping.stored_energy(st[c], shear);
        e.elastic += te.volume[t] * branches;
        e.viscous -= te.volume[t] * branches;
      }
    }
    for_each_group([&](const auto& g) {
      using L = typename std::remove_cvref_t<decltype(g)>::LawType;
      for (std::size_t k = 0; k < g.size(); ++k)
        add_contact_point_energy<L>(damping, g.properties[g.property[k]], g.history[k], g.spring_state[k], g.area[k],
                                    g.slip_dissipation[k], g.viscous_dissipation[k], e.elastic, e.slip, e.viscous);
    });
    for (std::size_t t = 0; t < m.deformable.trusses.size(); ++t) {
      // At the positions of the last force evaluation (truss_pass), as the contacts' and elements' energies: the ends
      // have moved on by a step since, and the energy there is a step ahead of the balance's other terms.
      const auto& tr = m.deformable.trusses[t];
      const Vec3 d = m.end_position(tr.end[1]) - m.end_position(tr.end[0]);
      const double axial = truss_force[t].dot(d) >= 0 ? truss_force[t].norm() : -truss_force[t].norm();
      const double stretch = (axial - tr.pretension) / tr.axial_stiffness();
      e.elastic += tr.pretension * stretch + 0.5 * tr.axial_stiffness() * stretch * stretch;
    }
    return e;
  }

  std::size_t contact_points() const {
    std::size_t n = 0;
    for_each_group([&](const auto& g) { n += g.size(); });
    return n;
  }

  /// Every array, for checkpoints (io/checkpoint.hpp), the gather lists too (those of the elements and trusses
  /// could be rebuilt from the model, those of the node contacts from the groups: loaded, nothing has to be).
  /// Not saved: material_moduli, a cache that every element pass fills before use.
  void save_state(io::CheckpointWriter& out) const { visit_state(*this, out); }
  void load_state(io::CheckpointReader& in) { visit_state(*this, in); }

  template <class Self, class Archive>
  static void visit_state(Self& d, Archive& ar) {
    std::apply([&](auto&... g) { (ar("node contact group", g), ...); }, d.groups);
    ar("element damping states", d.element_state);
    ar("element forces", d.element_force);
    ar.same_size("element viscous work", d.element_viscous);
    ar("truss forces", d.truss_force);
    ar("node inverse masses", d.node_inverse_mass);
    ar("node kinetic energies", d.node_kinetic);
    ar("node gravity work", d.node_gravity_work);
    ar("node viscous work", d.node_viscous);
    ar("node frame work", d.node_frame_work);
    ar("forces on rigid blocks", d.extra_force);
    ar("moments on rigid blocks", d.extra_moment);
    ar("real rigid block masses", d.rigid_real_mass);
    ar("real rigid block inertias", d.rigid_real_inertia);
    ar("weight correction work", d.extra_work);
    ar("retired node contact slip", d.retired_slip);
    ar("retired node contact viscous work", d.retired_viscous);
    ar("node positions at the last detection", d.detected_node_position);
    ar("node contact gather list heads", d.node_first);
    ar("node contact gather list entries", d.node_entry);
    ar("node contact gather list coefficients", d.node_coefficient);
    ar("rigid block node contact gather list heads", d.rigid_first);
    ar("rigid block node contact gather list entries", d.rigid_entry);
    ar("element gather list heads", d.element_first);
    ar("element gather list entries", d.element_entry);
    ar("truss gather list heads", d.truss_first);
    ar("truss gather list entries", d.truss_entry);
    ar("rigid block truss gather list heads", d.rigid_truss_first);
    ar("rigid block truss gather list entries", d.rigid_truss_entry);
  }

  // Gather lists. Of the nodes, one list for all groups: per node its entries group after group, each the group
  // (node_entry_group_shift and up) and the CP index, with its coefficient (-1 for the node side, +w for a face
  // triangle's node); one loop per node with no branch on the group (six loops, one per group, each of zero to a
  // few entries, cost the node pass mispredicted branches). Of the rigid blocks, per group (CP index).
  static constexpr std::size_t group_count = 2 * sizeof...(Laws);
  static constexpr unsigned node_entry_group_shift = 28;
  static constexpr std::uint32_t node_entry_point_mask = (1u << node_entry_group_shift) - 1;
  static_assert(group_count <= (1u << (32 - node_entry_group_shift)), "the group fits the high bits of a node entry");
  std::vector<std::uint32_t> node_first, node_entry;
  std::vector<double> node_coefficient;
  std::array<std::vector<std::uint32_t>, group_count> rigid_first, rigid_entry;
  std::vector<std::array<double, 2>> material_moduli;  // Pa, bulk K and shear G per material (material_moduli_of)
  std::vector<std::uint32_t> element_first, element_entry, truss_first, truss_entry, rigid_truss_first, rigid_truss_entry;

  template <class OtherGroups, std::size_t... I>
  void copy_groups(const OtherGroups& other, std::index_sequence<I...>) {
    (copy_group(std::get<I>(other), std::get<I>(groups)), ...);
  }
  template <class From, class To>
  static void copy_group(const From& from, To& to) {
    to.properties = from.properties;
    to.node = from.node;
    to.node_block = from.node_block;
    to.face_block = from.face_block;
    to.property = from.property;
    to.area = from.area;
    to.point_local = from.point_local;
    to.normal_local = from.normal_local;
    to.tangent_local = from.tangent_local;
    to.triangle = from.triangle;
    to.weight = from.weight;
    to.history = from.history;
    to.spring_state.assign(from.size(), typename To::SpringState{});
    to.traction = from.traction;
    to.force = from.force;
    to.moment = from.moment;
    to.slip_dissipation.assign(from.size(), 0.0);
    to.viscous_dissipation.assign(from.size(), 0.0);
  }

  void build_contact_lists(const model::Model& m) {
    const std::size_t nodes = m.deformable.nodes.size(), blocks = m.bodies.size();
    // The nodes' list: (group, CP, coefficient) in group order, then in increasing CP order, per node.
    node_first.assign(nodes + 1, 0);
    for_each_group([&](const auto& g) {
      using G = std::remove_cvref_t<decltype(g)>;
      if (g.size() > node_entry_point_mask) throw InvalidArgument("a node contact group has more than 2^28 contact points");
      for (std::size_t k = 0; k < g.size(); ++k) {
        ++node_first[g.node[k] + 1];
        if constexpr (G::FaceKinematics::deformable)
          for (auto n : g.triangle[k]) ++node_first[n + 1];
      }
    });
    for (std::size_t i = 0; i < nodes; ++i) node_first[i + 1] += node_first[i];
    node_entry.assign(node_first.back(), 0);
    node_coefficient.assign(node_first.back(), 0.0);
    std::vector<std::uint32_t> next(node_first.begin(), node_first.end() - 1);
    std::uint32_t group_bits = 0;
    for_each_group([&](const auto& g) {
      using G = std::remove_cvref_t<decltype(g)>;
      for (std::size_t k = 0; k < g.size(); ++k) {
        auto put = [&](std::uint32_t n, double c) {
          node_entry[next[n]] = group_bits | static_cast<std::uint32_t>(k);
          node_coefficient[next[n]++] = c;
        };
        put(g.node[k], -1.0);
        if constexpr (G::FaceKinematics::deformable)
          for (std::size_t j = 0; j < 3; ++j) put(g.triangle[k][j], g.weight[k][j]);
      }
      group_bits += 1u << node_entry_group_shift;
    });
    std::size_t group = 0;
    for_each_group([&](const auto& g) {
      using G = std::remove_cvref_t<decltype(g)>;
      std::vector<std::uint32_t> rcount(blocks + 1, 0);
      if constexpr (!G::FaceKinematics::deformable)
        for (std::size_t k = 0; k < g.size(); ++k) ++rcount[g.face_block[k] + 1];
      for (std::size_t i = 0; i < blocks; ++i) rcount[i + 1] += rcount[i];
      rigid_entry[group].assign(rcount.back(), 0);
      std::vector<std::uint32_t> rnext(rcount.begin(), rcount.end() - 1);
      if constexpr (!G::FaceKinematics::deformable)
        for (std::size_t k = 0; k < g.size(); ++k) rigid_entry[group][rnext[g.face_block[k]]++] = static_cast<std::uint32_t>(k);
      rigid_first[group] = std::move(rcount);
      ++group;
    });
    const auto& trusses = m.deformable.trusses;
    rigid_truss_first.assign(blocks + 1, 0);
    for (const auto& t : trusses)
      for (const auto& e : t.end)
        if (e.node < 0) ++rigid_truss_first[e.block + 1];
    for (std::size_t i = 0; i < blocks; ++i) rigid_truss_first[i + 1] += rigid_truss_first[i];
    rigid_truss_entry.assign(rigid_truss_first.back(), 0);
    std::vector<std::uint32_t> tnext(rigid_truss_first.begin(), rigid_truss_first.end() - 1);
    for (std::size_t t = 0; t < trusses.size(); ++t)
      for (std::uint32_t s = 0; s < 2; ++s)
        if (trusses[t].end[s].node < 0) rigid_truss_entry[tnext[trusses[t].end[s].block]++] = static_cast<std::uint32_t>(2 * t + s);
    build_thread_ranges(m);
  }

  /// The threads' ranges (node_bounds, tile_bounds, contact_bounds): the deformable blocks cut into runs of about
  /// equal cost, counted from the benchmark's cost per item (ns per element, node and node contact point, one
  /// thread: 21.7, 23.5 and 31.6, benchmarks/README.md). A run's element tiles are those whose first element is one
  /// of its elements; its contact points in a group, those whose node is one of its nodes. A cut falls between two
  /// blocks, or inside a block bigger than a quarter of a run (a model of a few large blocks), at the same fraction
  /// of its nodes and of its elements. Left empty (even splits) for one thread, and when the blocks' nodes or
  /// elements are not in block order.
  void build_thread_ranges(const model::Model& m) {
    const int threads = parallel::available_threads();
    node_bounds.clear();
    tile_bounds.clear();
    for (auto& b : contact_bounds) b.clear();
    const auto& blocks = m.deformable.blocks;
    const std::size_t nodes = m.deformable.nodes.size(), elements = m.deformable.tetrahedra.size();
    if (threads <= 1 || blocks.empty()) return;
    std::uint32_t next_node = 0, next_element = 0;
    for (const auto& blk : blocks) {  // in block order, each block's nodes and elements after the last one's
      if (blk.first_node != next_node || blk.first_tetrahedron != next_element) return;
      next_node = blk.end_node;
      next_element = blk.end_tetrahedron;
    }
    if (next_node != nodes || next_element != elements) return;
    std::vector<double> contacts_of_node(nodes, 0.0);
    for_each_group([&](const auto& g) {
      for (std::uint32_t n : g.node) contacts_of_node[n] += 1.0;
    });
    std::vector<double> cost(blocks.size(), 0.0);
    double total = 0.0;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const auto& blk = blocks[b];
      cost[b] = 21.7 * (blk.end_tetrahedron - blk.first_tetrahedron) + 23.5 * (blk.end_node - blk.first_node);
      for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) cost[b] += 31.6 * contacts_of_node[i];
      total += cost[b];
    }
    const double run = total / threads;
    std::size_t b = 0;
    double before = 0.0;  // cost of the blocks before b
    node_bounds.push_back(0);
    std::vector<std::uint32_t> element_bounds{0};
    for (int t = 1; t < threads; ++t) {
      const double target = run * t;
      while (b + 1 < blocks.size() && before + cost[b] <= target) before += cost[b++];
      const auto& blk = blocks[b];
      std::uint32_t node_cut = blk.first_node, element_cut = blk.first_tetrahedron;
      if (cost[b] > 0.25 * run) {  // inside the block
        const double f = std::clamp((target - before) / cost[b], 0.0, 1.0);
        node_cut += static_cast<std::uint32_t>(std::lround(f * (blk.end_node - blk.first_node)));
        element_cut += static_cast<std::uint32_t>(std::lround(f * (blk.end_tetrahedron - blk.first_tetrahedron)));
      } else if (target - before > 0.5 * cost[b]) {  // after the block: the nearer of its two ends
        node_cut = blk.end_node;
        element_cut = blk.end_tetrahedron;
      }
      node_bounds.push_back(std::max(node_cut, node_bounds.back()));
      element_bounds.push_back(std::max(element_cut, element_bounds.back()));
    }
    node_bounds.push_back(static_cast<std::uint32_t>(nodes));
    element_bounds.push_back(static_cast<std::uint32_t>(elements));
    for (std::uint32_t e : element_bounds) tile_bounds.push_back(static_cast<std::uint32_t>(element_tiles(e)));
    std::size_t group = 0;
    for_each_group([&](const auto& g) {
      auto& bounds = contact_bounds[group++];
      if (!std::is_sorted(g.node.begin(), g.node.end())) return;
      for (std::uint32_t n : node_bounds)
        bounds.push_back(static_cast<std::uint32_t>(std::lower_bound(g.node.begin(), g.node.end(), n) - g.node.begin()));
    });
  }
};

/// Moves the rigid entry of each deformable block with the mean motion of its nodes: the detection runs on the
/// blocks' rigid entries.
inline void move_proxies(model::Model& m) {
  auto& b = m.bodies;
  const auto& x = m.deformable.nodes.position;
  for (const auto& blk : m.deformable.blocks) {
    Vec3 shift = Vec3::Zero();
    for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) shift += x[i] - blk.reference_position[i - blk.first_node];
    b.position[blk.body] = blk.reference_centroid + shift / static_cast<double>(blk.end_node - blk.first_node);
  }
}

}  // namespace blockdem
