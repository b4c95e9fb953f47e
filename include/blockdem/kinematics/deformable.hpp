#pragma once
// The deformable part of a step (DESIGN.md §4, paper Sect. 3.1-3.2): node contact groups (rigid face side and
// deformable face side, one specialised loop per law and kind), constant-strain tetrahedra (strain increment from the
// nodal velocities -> Hooke + damping -> nodal forces stored per element), trusses, and the node pass (gather in a
// fixed order, gravity, damped velocity update, position). No atomics: every node and block gathers its own
// contributions through lists built at detection, so results do not depend on the number of threads.
//
// Damping inside a tetrahedron: the policy's `spring_stress` is applied to seven independent strain components in
// parallel with the element's elastic stiffness: the volumetric strain with the bulk modulus K, the three deviatoric
// normal strains with 2G and the three engineering shear strains with G. Hooke's law is exactly K tr(e) I + 2G dev(e),
// so a Maxwell branch of fraction alpha (or a dashpot beta k) on each component is a branch alpha D (or beta D) on the
// whole element, and the branch energies s^2 / (2 alpha k) add up to the element's. Maxwell<N> does the same in tensor
// form (damping::Maxwell::element_stress: one branch stress tensor updated with the elastic stress increment), which
// is equivalent and cheaper (6 components instead of 7), applied across a tile of elements at once, one per SIMD lane
// (element_stress_tile, element_pass_tiles).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <variant>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/kinematics/node_contact_group.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::kinematics {

/// Energy terms of the deformable part (J), added to the simulation's report.
struct DeformableEnergy {
  double kinetic = 0, elastic = 0, gravity_work = 0, viscous = 0, slip = 0;
};

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
class DeformableState {
 public:
  template <contact::ContactLaw L>
  using RigidFaceGroup = NodeContactGroup<L, Damping, Rigid>;
  template <contact::ContactLaw L>
  using DeformableFaceGroup = NodeContactGroup<L, Damping, Deformable>;
  using Groups = std::tuple<RigidFaceGroup<Laws>..., DeformableFaceGroup<Laws>...>;
  /// Elements per tile of the tensor form: fixed, so that which elements share a vector does not depend on the
  /// number of threads. With 32, a tile's branch stresses (4.6 kB for Maxwell<3>), its increment buffers and the
  /// gradients it reads twice fit the L1 cache together. 64 was slower (22.7 against 19.9 ms per step on the
  /// benchmark wall with Maxwell<3>); 16 was not distinguishable from 32.
  static constexpr std::size_t element_tile = 32;
  /// Policies with a tensor form for whole elements (Maxwell<N>: element_stress_tile) keep their own element state,
  /// per tile of element_tile elements; the others act on the seven strain components (volumetric, 3 deviatoric
  /// normal, 3 shear), per element.
  static constexpr bool tensor_form = requires { typename Damping::template ElementTile<element_tile>; };
  using ElementState = typename decltype([] {
    if constexpr (tensor_form) return std::type_identity<typename Damping::template ElementTile<element_tile>>{};
    else return std::type_identity<std::array<typename Damping::ContactState, 7>>{};
  }())::type;

  Groups groups;
  std::vector<ElementState> element_state;  // per tile (tensor form) or per element
  std::vector<std::array<Vec3, 4>> element_force;  // N, on the element's nodes
  /// Elements per partial sum of element_viscous: a fixed number, so that the sums (and the energy report) do not
  /// depend on the number of threads. A per-element array cost 16 bytes read and written per element-step.
  static constexpr std::size_t viscous_chunk = 2048;
  static_assert(viscous_chunk % element_tile == 0, "a chunk of the viscous work is made of whole tiles");
  std::vector<double> element_viscous;              // J, work on the element dashpots / branches, per viscous_chunk
  std::vector<Vec3> truss_force;                    // N, on end 0 (end 1 gets the opposite)
  std::vector<double> node_inverse_mass;            // 1/kg
  std::vector<double> node_kinetic, node_gravity_work, node_viscous;
  std::vector<Vec3> extra_force, extra_moment;      // N, N m, on rigid blocks: node contacts, trusses, weight correction
  std::vector<double> rigid_real_mass;              // kg, before density scaling
  std::vector<Vec3> rigid_real_inertia;             // kg m^2, idem
  double extra_work = 0;                            // J, work of the weight correction of scaled rigid blocks
  double retired_slip = 0, retired_viscous = 0;
  std::vector<Vec3> detected_node_position;
  /// Scratch of assign(): the old CPs of each group by (node, face block), built once per detection (per block pair
  /// it cost the whole detection's time: some 4 s for the deformable vault's 3,000 pairs and 16,000 CPs).
  std::array<std::unordered_map<std::uint64_t, std::size_t>, 2 * sizeof...(Laws)> previous_contacts;
  std::unordered_set<std::uint64_t> previous_sides;  // (node block, face block) of the old CPs: the side kept
  /// The old CPs of each group by (node block, face block): the joint a CP that the pair adds belongs to.
  std::array<std::unordered_map<std::uint64_t, std::vector<std::size_t>>, 2 * sizeof...(Laws)> previous_pairs;

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
    element_viscous.assign((te.size() + viscous_chunk - 1) / viscous_chunk, 0.0);
    material_moduli.assign(m.deformable.materials.size(), {0.0, 0.0});
    truss_force.assign(m.deformable.trusses.size(), Vec3::Zero());
    node_inverse_mass.resize(nd.size());
    for (std::size_t i = 0; i < nd.size(); ++i) node_inverse_mass[i] = 1.0 / nd.mass[i];
    node_kinetic.assign(nd.size(), 0.0);
    for (std::size_t i = 0; i < nd.size(); ++i) node_kinetic[i] = 0.5 * nd.mass[i] * nd.velocity[i].squaredNorm();
    node_gravity_work.assign(nd.size(), 0.0);
    node_viscous.assign(nd.size(), 0.0);
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

  // ---- detection ----

  /// Builds the node contact points of the block pairs with a deformable block among `candidates` (CPs of one pair
  /// contiguous, from the detection on the blocks' rigid entries). `choose(tag_a, tag_b)` gives the law's parameters
  /// as a variant over Laws::Parameters. With keep_history, a CP of the same node against the same block takes over
  /// the old history and damping state.
  template <class Choose>
  void assign(const model::Model& m, const std::vector<model::ContactCandidate>& candidates, Choose&& choose,
              const model::ContactSettings& settings, bool keep_history) {
    Groups old = std::move(groups);
    groups = Groups{};
    std::apply([&](auto&... g) { ((g.properties = std::get<std::remove_cvref_t<decltype(g)>>(old).properties), ...); }, groups);
    double old_slip = 0, old_viscous = 0, carried_slip = 0, carried_viscous = 0;
    std::apply([&](const auto&... g) {
      ((old_slip += sum(g.slip_dissipation), old_viscous += sum(g.viscous_dissipation)), ...);
    }, old);
    if (keep_history) index_old_contacts(old, std::make_index_sequence<2 * sizeof...(Laws)>{});
    const double cos_max = std::cos(settings.max_normal_angle);
    for (std::size_t begin = 0, end = 0; begin < candidates.size(); begin = end) {
      const auto& c = candidates[begin];
      end = begin + 1;
      while (end < candidates.size() && candidates[end].a == c.a && candidates[end].b == c.b) ++end;
      const bool da = m.deformable.is_deformable(c.a), db = m.deformable.is_deformable(c.b);
      if (!da && !db) continue;
      const auto params = choose(m.bodies.joint_tag[c.a], m.bodies.joint_tag[c.b]);
      std::visit([&](const auto& p) {
        pair_contacts(m, p, candidates.data() + begin, candidates.data() + end, da, db, cos_max, old, keep_history,
                      carried_slip, carried_viscous);
      }, params);
    }
    retired_slip += old_slip - carried_slip;
    retired_viscous += old_viscous - carried_viscous;
    build_contact_lists(m);
    detected_node_position = m.deformable.nodes.position;
    for (auto& p : previous_contacts) p.clear();
    for (auto& p : previous_pairs) p.clear();
    previous_sides.clear();
  }

  template <std::size_t... I>
  void index_old_contacts(const Groups& old, std::index_sequence<I...>) {
    (
        [&] {
          const auto& og = std::get<I>(old);
          auto& index = previous_contacts[I];
          index.clear();
          index.reserve(og.size());
          for (std::size_t k = 0; k < og.size(); ++k) {
            index.emplace(contact_key(og.node[k], og.face_block[k]), k);
            previous_sides.insert(contact_key(og.node_block[k], og.face_block[k]));
            previous_pairs[I][contact_key(og.node_block[k], og.face_block[k])].push_back(k);
          }
        }(),
        ...);
  }
  static std::uint64_t contact_key(std::uint64_t node, std::uint64_t face_block) { return (node << 32) | face_block; }

  // ---- the passes ----

  /// Node contacts: relative velocity of the face point and the node -> increment -> law -> damping -> force.
  void contact_pass(const model::Model& m, const Damping& damping, double increment_dt) {
    for_each_group([&](auto& g) { node_contact_pass(g, m, damping, increment_dt); });
  }

  /// Constant-strain tetrahedra: strain increment from v(n-1/2) over the last move, stress, damping, nodal forces.
  void element_pass(model::Model& m, const Damping& damping, double increment_dt) {
    if constexpr (tensor_form) element_pass_tiles(m, damping, increment_dt);
    else element_pass_springs(m, damping, increment_dt);
  }

  /// Trusses: axial force pretension + EA (L - L0) / L0 along the current axis.
  void truss_pass(const model::Model& m) {
    const auto& trusses = m.deformable.trusses;
    for (std::size_t t = 0; t < trusses.size(); ++t) {
      const auto& tr = trusses[t];
      const Vec3 d = m.end_position(tr.end[1]) - m.end_position(tr.end[0]);
      const double length = d.norm();
      const double axial = tr.pretension + tr.axial_stiffness() * (length - tr.length0);
      truss_force[t] = axial / length * d;  // on end 0, toward end 1 in tension
    }
  }

  /// Forces of node contacts and trusses on rigid blocks, and the weight correction of density-scaled rigid blocks.
  void gather_rigid(const model::Model& m, double increment_dt) {
    const auto& b = m.bodies;
    const auto n = b.size();
    for (std::size_t i = 0; i < n; ++i) {
      Vec3 f = Vec3::Zero(), mo = Vec3::Zero();
      std::size_t group = 0;
      for_each_group([&](const auto& g) {
        if constexpr (!std::remove_cvref_t<decltype(g)>::FaceKinematics::deformable) {
          const auto& first = rigid_first[group];
          const auto& entry = rigid_entry[group];
          for (std::uint32_t e = first[i]; e < first[i + 1]; ++e) {
            f += g.force[entry[e]];
            mo += g.moment[entry[e]];
          }
        }
        ++group;
      });
      for (std::uint32_t e = rigid_truss_first[i]; e < rigid_truss_first[i + 1]; ++e) {
        const std::uint32_t code = rigid_truss_entry[e];
        const auto& tr = m.deformable.trusses[code >> 1];
        const Vec3 force = (code & 1u) ? Vec3(-truss_force[code >> 1]) : truss_force[code >> 1];
        f += force;
        mo += rotate(b.rotation[i], tr.end[code & 1u].body_point).cross(force);
      }
      if (b.motion[i] == model::Motion::free && rigid_real_mass[i] != b.mass[i]) {
        const Vec3 correction = (rigid_real_mass[i] - b.mass[i]) * m.gravity;
        f += correction;
        extra_work += correction.dot(b.velocity[i]) * increment_dt;
      }
      extra_force[i] = f;
      extra_moment[i] = mo;
    }
  }

  /// Gather (elements, contacts, trusses in a fixed order), gravity with the real mass, damped velocity update with
  /// the scaled mass, then positions. Returns whether a node moved more than `redetection` since the last detection.
  bool node_pass(model::Model& m, const Damping& damping, double dt, double increment_dt, bool move, double redetection) {
    auto& nd = m.deformable.nodes;
    const Vec3 gravity = m.gravity;
    const auto count = static_cast<std::ptrdiff_t>(nd.size());
    bool moved = false;
#pragma omp parallel for schedule(static) if (count > 1024) reduction(|| : moved)
    for (std::ptrdiff_t ii = 0; ii < count; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      Vec3 force = Vec3::Zero();
      for (std::uint32_t e = element_first[i]; e < element_first[i + 1]; ++e) {
        const std::uint32_t code = element_entry[e];
        force += element_force[code >> 2][code & 3u];
      }
      std::size_t group = 0;
      for_each_group([&](const auto& g) {
        const auto& first = node_first[group];
        const auto& entry = node_entry[group];
        const auto& coefficient = node_coefficient[group];
        for (std::uint32_t e = first[i]; e < first[i + 1]; ++e) force += coefficient[e] * g.force[entry[e]];
        ++group;
      });
      for (std::uint32_t e = truss_first[i]; e < truss_first[i + 1]; ++e) {
        const std::uint32_t code = truss_entry[e];
        force += (code & 1u) ? Vec3(-truss_force[code >> 1]) : truss_force[code >> 1];
      }
      force += nd.real_mass[i] * gravity;
      nd.force[i] = force;
      const damping::Inertia mass{nd.mass[i], node_inverse_mass[i]};
      const Vec3 v_old = nd.velocity[i];
      Vec3 v;
      double dissipated = 0.0;
      const std::uint8_t fixity = nd.fixity[i];
      for (int c = 0; c < 3; ++c) v[c] = (fixity & (1u << c)) ? 0.0 : damping.velocity_update(v_old[c], force[c], mass, dt, dissipated);
      nd.velocity[i] = v;
      node_kinetic[i] = 0.5 * mass.value * v_old.dot(v);
      node_viscous[i] += dissipated;
      node_gravity_work[i] += nd.real_mass[i] * gravity.dot(v_old) * increment_dt;
      if (move) {
        nd.position[i] += dt * v;
        moved = moved || (nd.position[i] - detected_node_position[i]).squaredNorm() > redetection * redetection;
      }
    }
    return moved;
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
      bound.tetrahedron(te.node[t], te.gradient[t], te.volume[t], mat.bulk(), mat.shear());
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
      } else if constexpr (requires { damping.stored_energy(element_state[t][0], 1.0); }) {
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
      const auto& tr = m.deformable.trusses[t];
      const double stretch = (m.end_position(tr.end[1]) - m.end_position(tr.end[0])).norm() - tr.length0;
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

 private:
  template <class Self, class Archive>
  static void visit_state(Self& d, Archive& ar) {
    std::apply([&](auto&... g) { (ar("node contact group", g), ...); }, d.groups);
    ar("element damping states", d.element_state);
    ar("element forces", d.element_force);
    ar("element viscous work", d.element_viscous);
    ar("truss forces", d.truss_force);
    ar("node inverse masses", d.node_inverse_mass);
    ar("node kinetic energies", d.node_kinetic);
    ar("node gravity work", d.node_gravity_work);
    ar("node viscous work", d.node_viscous);
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

  template <damping::DampingPolicy, contact::ContactLaw...>
  friend class DeformableState;

  // Gather lists, per group: node entries (CP index, coefficient -1 for the node side, +w for a face triangle's
  // node) and rigid-block entries (CP index).
  static constexpr std::size_t group_count = 2 * sizeof...(Laws);
  std::array<std::vector<std::uint32_t>, group_count> node_first, node_entry, rigid_first, rigid_entry;
  std::array<std::vector<double>, group_count> node_coefficient;
  std::vector<std::array<double, 2>> material_moduli;  // Pa, bulk K and shear G per material (material_moduli_of)
  std::vector<std::uint32_t> element_first, element_entry, truss_first, truss_entry, rigid_truss_first, rigid_truss_entry;

  static double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
  }

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
    std::size_t group = 0;
    for_each_group([&](const auto& g) {
      using G = std::remove_cvref_t<decltype(g)>;
      // (node, CP, coefficient) triples in increasing CP order per node.
      std::vector<std::uint32_t> count(nodes + 1, 0);
      for (std::size_t k = 0; k < g.size(); ++k) {
        ++count[g.node[k] + 1];
        if constexpr (G::FaceKinematics::deformable)
          for (auto n : g.triangle[k]) ++count[n + 1];
      }
      for (std::size_t i = 0; i < nodes; ++i) count[i + 1] += count[i];
      auto& entry = node_entry[group];
      auto& coefficient = node_coefficient[group];
      entry.assign(count.back(), 0);
      coefficient.assign(count.back(), 0.0);
      std::vector<std::uint32_t> next(count.begin(), count.end() - 1);
      for (std::size_t k = 0; k < g.size(); ++k) {
        auto put = [&](std::uint32_t n, double c) {
          entry[next[n]] = static_cast<std::uint32_t>(k);
          coefficient[next[n]++] = c;
        };
        put(g.node[k], -1.0);
        if constexpr (G::FaceKinematics::deformable)
          for (std::size_t j = 0; j < 3; ++j) put(g.triangle[k][j], g.weight[k][j]);
      }
      node_first[group] = std::move(count);
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
  }

  /// dt times the symmetric part of grad v = sum_i v_i (x) grad N_i: xx yy zz and the engineering shear strains
  /// xy yz zx. Summed component by component: through a 3 x 3 temporary, GCC packed pairs through the stack, a
  /// store-forwarding stall per node.
  static std::array<double, 6> strain_increment(const Vec3* __restrict velocity, const geometry::Tetrahedron& nodes,
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
  static void element_forces(double v, const std::array<double, 6>& total, const std::array<Vec3, 4>& g,
                             std::array<Vec3, 4>& f) {
    const double sxx = -v * total[0], syy = -v * total[1], szz = -v * total[2], sxy = -v * total[3],
                 syz = -v * total[4], szx = -v * total[5];
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3& b = g[k];
      f[k] = Vec3(sxx * b[0] + sxy * b[1] + szx * b[2], sxy * b[0] + syy * b[1] + syz * b[2], szx * b[0] + syz * b[1] + szz * b[2]);
    }
  }

  /// K and G (Pa) of every material, from E and nu once per pass: per element they cost two divisions.
  const std::array<double, 2>* material_moduli_of(const model::Model& m) {
    const auto& materials = m.deformable.materials;
    material_moduli.resize(materials.size());  // sized in setup: allocates only if materials were added since
    for (std::size_t i = 0; i < materials.size(); ++i) material_moduli[i] = {materials[i].bulk(), materials[i].shear()};
    return material_moduli.data();
  }

  /// The element pass of the other policies: the seven strain components' springs per element (spring_stress).
  void element_pass_springs(model::Model& m, const Damping& damping, double increment_dt) {
    auto& te = m.deformable.tetrahedra;
    const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
    const auto count = te.size();
    const auto chunks = static_cast<std::ptrdiff_t>(element_viscous.size());
    const auto* __restrict const moduli = material_moduli_of(m);
#pragma omp parallel for schedule(static) if (count > 1024)
    for (std::ptrdiff_t c = 0; c < chunks; ++c) {
      const std::size_t first = static_cast<std::size_t>(c) * viscous_chunk;
      const std::size_t last = std::min(first + viscous_chunk, count);
      double viscous = 0.0;  // J, on this chunk's dashpots
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
        if constexpr (!std::is_same_v<typename Damping::ContactState, damping::NoState>) {
          auto& st = element_state[t];
          const double p = damping.spring_stress(st[0], bulk, ev, increment_dt, true, dissipated);
          total[0] += p + damping.spring_stress(st[1], 2.0 * shear, dxx, increment_dt, true, dissipated);
          total[1] += p + damping.spring_stress(st[2], 2.0 * shear, dyy, increment_dt, true, dissipated);
          total[2] += p + damping.spring_stress(st[3], 2.0 * shear, dzz, increment_dt, true, dissipated);
          total[3] += damping.spring_stress(st[4], shear, gxy, increment_dt, true, dissipated);
          total[4] += damping.spring_stress(st[5], shear, gyz, increment_dt, true, dissipated);
          total[5] += damping.spring_stress(st[6], shear, gzx, increment_dt, true, dissipated);
        }
        const double v = te.volume[t];
        element_forces(v, total, g, element_force[t]);
        viscous += v * dissipated;
      }
      element_viscous[static_cast<std::size_t>(c)] += viscous;
    }
  }

  /// The element pass of the tensor form, one tile of element_tile elements at a time: the increments of the tile's
  /// elements (per element), the branch update (across the tile's elements, damping.element_stress_tile), then the
  /// forces (per element). Per element the same operations in the same order as element_stress.
  void element_pass_tiles(model::Model& m, const Damping& damping, double increment_dt) {
    constexpr std::size_t lanes = element_tile;
    using TileLanes = typename Damping::template ElementLanes<lanes>;
    auto& te = m.deformable.tetrahedra;
    const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
    const auto count = te.size();
    const auto chunks = static_cast<std::ptrdiff_t>(element_viscous.size());
    const auto* __restrict const moduli = material_moduli_of(m);
#pragma omp parallel for schedule(static) if (count > 1024)
    for (std::ptrdiff_t c = 0; c < chunks; ++c) {
      const std::size_t first = static_cast<std::size_t>(c) * viscous_chunk;
      const std::size_t last = std::min(first + viscous_chunk, count);
      alignas(64) TileLanes elastic, strain, branch;  // Pa, -, Pa: per component and element of the tile
      alignas(64) std::array<double, lanes> work;  // J/m^3
      double viscous = 0.0;  // J, on this chunk's branches
      for (std::size_t begin = first; begin < last; begin += lanes) {
        const std::size_t n = std::min(lanes, last - begin);
        // The next tile's branch stresses are fetched while this tile's increments are computed: the branch update
        // reads and writes a whole tile in a burst (4.6 kB for Maxwell<3>), faster than the hardware prefetcher
        // brings it in, and stalled on its loads.
        const std::size_t next = begin / lanes + 1;
        const char* const ahead = next < element_state.size() ? reinterpret_cast<const char*>(&element_state[next]) : nullptr;
        constexpr std::size_t ahead_step = (sizeof(ElementState) + lanes - 1) / lanes;  // bytes per element, <= 3 lines
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
        damping.element_stress_tile(element_state[begin / lanes], elastic, strain, increment_dt, branch, work);
        for (std::size_t l = 0; l < n; ++l) {
          const std::size_t t = begin + l;
          const auto& s = te.stress[t];
          const std::array<double, 6> total{s[0] + branch[0][l], s[1] + branch[1][l], s[2] + branch[2][l],
                                            s[3] + branch[3][l], s[4] + branch[4][l], s[5] + branch[5][l]};
          const double v = te.volume[t];
          element_forces(v, total, te.gradient[t], element_force[t]);
          viscous += v * work[l];
        }
      }
      element_viscous[static_cast<std::size_t>(c)] += viscous;
    }
  }

  template <class Params>
  static constexpr std::size_t law_index() {
    constexpr bool same[] = {std::is_same_v<Params, typename Laws::Parameters>...};
    for (std::size_t i = 0; i < sizeof...(Laws); ++i)
      if (same[i]) return i;
    return 0;
  }

  /// The boundary triangles of deformable block `body` whose outward normal is within the normal angle of `direction`.
  static std::vector<std::size_t> facing_triangles(const model::Model& m, std::size_t body, const Vec3& direction, double cos_max) {
    const auto& blk = m.deformable.blocks[static_cast<std::size_t>(m.deformable.block_of_body[body])];
    const auto& x = m.deformable.nodes.position;
    std::vector<std::size_t> out;
    for (std::size_t k = 0; k < blk.boundary.size(); ++k) {
      const auto& t = blk.boundary[k];
      const Vec3 n = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).normalized();
      if (n.dot(direction) >= cos_max) out.push_back(k);
    }
    return out;
  }

  /// The node CPs of one block pair.
  template <class Params>
  void pair_contacts(const model::Model& m, const Params& params, const model::ContactCandidate* first,
                     const model::ContactCandidate* last, bool da, bool db, double cos_max, Groups& old, bool keep_history,
                     double& carried_slip, double& carried_viscous) {
    const auto& x = m.deformable.nodes.position;
    const std::size_t a = first->a, b = first->b;
    const Vec3 n_ab = first->normal, t1 = first->tangent, t2 = n_ab.cross(t1);
    const Vec3 origin = first->position;
    // Node side: the deformable one; of two, the one with more nodes on the joint (the finer mesh), and once
    // chosen, the same at every later detection: the counts of facing triangles change as the blocks deform, and
    // a pair that changed sides would lose every CP's history (a bonded joint would come back as new contacts).
    bool node_is_a = da;
    if (da && db) {
      if (keep_history && previous_sides.contains(contact_key(a, b))) node_is_a = true;
      else if (keep_history && previous_sides.contains(contact_key(b, a))) node_is_a = false;
      else node_is_a = facing_triangles(m, a, n_ab, cos_max).size() >= facing_triangles(m, b, -n_ab, cos_max).size();
    }
    const std::size_t ns = node_is_a ? a : b, fs = node_is_a ? b : a;
    const Vec3 n = node_is_a ? n_ab : Vec3(-n_ab);  // from the node side to the face side
    // The overlap polygon: the convex hull of the pair's CPs on the common plane.
    model::detail::Polygon2 points;
    for (auto c = first; c != last; ++c) {
      const Vec3 d = c->position - origin;
      points.push_back({d.dot(t1), d.dot(t2)});
    }
    const auto overlap = convex_hull(points);
    if (overlap.size() < 3) return;
    // Tributary areas: each facing triangle of the node side clipped to the overlap; the clipped area A goes to the
    // triangle's nodes as A N_j(centroid) = the integral of the linear shape function N_j over it.
    std::map<std::uint32_t, double> tributary;
    const auto& nblk = m.deformable.blocks[static_cast<std::size_t>(m.deformable.block_of_body[ns])];
    for (std::size_t k : facing_triangles(m, ns, n, cos_max)) {
      const auto& tri = nblk.boundary[k];
      model::detail::Polygon2 p2;
      for (auto v : tri) {
        const Vec3 d = x[v] - origin;
        p2.push_back({d.dot(t1), d.dot(t2)});
      }
      if (model::detail::polygon_area(p2) < 0) std::swap(p2[1], p2[2]);
      const auto clipped = model::detail::clip_convex(p2, overlap);
      if (clipped.size() < 3) continue;
      const auto [area, centre] = area_centroid(clipped);
      if (!(area > 0)) continue;
      const auto l = barycentric2(p2, centre);
      // p2 may have been reordered: map back by position.
      for (std::size_t j = 0; j < 3; ++j) {
        for (auto v : tri) {
          const Vec3 d = x[v] - origin;
          if (std::abs(d.dot(t1) - p2[j][0]) < 1e-15 + 1e-12 * std::abs(p2[j][0]) &&
              std::abs(d.dot(t2) - p2[j][1]) < 1e-15 + 1e-12 * std::abs(p2[j][1])) {
            tributary[v] += area * l[j];
            break;
          }
        }
      }
    }
    using L = std::tuple_element_t<law_index<Params>(), std::tuple<Laws...>>;
    auto add = [&](auto& g, auto& og, const std::unordered_map<std::uint64_t, std::size_t>& previous,
                   const std::unordered_map<std::uint64_t, std::vector<std::size_t>>& pairs) {
      const auto pair = pairs.find(contact_key(ns, fs));
      std::size_t pi = 0;
      while (pi < g.properties.size() && !(g.properties[pi] == params)) ++pi;
      if (pi == g.properties.size()) g.properties.push_back(params);
      using G = std::remove_cvref_t<decltype(g)>;
      const auto& faces = [&]() {
        if constexpr (G::FaceKinematics::deformable) return facing_triangles(m, fs, -n, cos_max);
        else return std::vector<std::size_t>{};
      }();
      const auto face_world = m.bodies.world_shape(fs);
      std::size_t face_index = 0;
      if constexpr (!G::FaceKinematics::deformable) {
        double best = -2;
        for (std::size_t f = 0; f < face_world.faces.size(); ++f)
          if (face_world.face_normal(f).dot(-n) > best) {
            best = face_world.face_normal(f).dot(-n);
            face_index = f;
          }
      }
      for (const auto& [node, area] : tributary) {
        if (!(area > 1e-12 * model::detail::polygon_area(overlap))) continue;
        const Vec3 xn = x[node];
        typename L::History h{};
        typename G::SpringState spring{};
        Vec3 tt1 = t1;
        double gap = 0, slip = 0, viscous = 0;
        const std::size_t k = g.size();
        g.add(node, static_cast<std::uint32_t>(ns), static_cast<std::uint32_t>(fs), static_cast<std::uint16_t>(pi), area, h,
              spring, 0, 0);
        if constexpr (G::FaceKinematics::deformable) {
          const auto& fblk = m.deformable.blocks[static_cast<std::size_t>(m.deformable.block_of_body[fs])];
          double best = -1e300;
          for (std::size_t f : faces) {
            const auto& tri = fblk.boundary[f];
            const Vec3 e1 = x[tri[1]] - x[tri[0]], e2 = x[tri[2]] - x[tri[0]];
            const Vec3 nn = e1.cross(e2);
            const double s = nn.dot(x[tri[0]] - xn) / nn.dot(n);
            const Vec3 p = xn + s * n;
            const std::array<double, 3> w = barycentric3(x[tri[0]], x[tri[1]], x[tri[2]], p);
            const double inside = std::min({w[0], w[1], w[2]});
            if (inside > best) {
              best = inside;
              g.triangle[k] = tri;
              g.weight[k] = w;
              gap = s;
              tt1 = e1.normalized();
            }
          }
        } else {
          const Vec3 nf = face_world.face_normal(face_index);
          const double s = nf.dot(face_world.face_centroid(face_index) - xn) / nf.dot(n);
          const Vec3 p = xn + s * n;
          gap = s;
          const Mat3& r = m.bodies.rotation[fs];
          g.point_local[k] = r.transpose() * (p - m.bodies.position[fs]);
          g.normal_local[k] = r.transpose() * n;
          g.tangent_local[k] = r.transpose() * t1;
        }
        g.history[k].gap = gap;
        if (keep_history) {
          const auto it = previous.find(contact_key(node, fs));
          if (it == previous.end() && pair != pairs.end()) {
            // As for rigid blocks (Simulation::assign_contacts): a node that the pair's joint adds takes the state
            // of the joint where it is, that of the closest old CP of the pair (its own gap; no damping state).
            std::size_t closest = pair->second.front();
            for (std::size_t j : pair->second)
              if ((x[og.node[j]] - xn).squaredNorm() < (x[og.node[closest]] - xn).squaredNorm()) closest = j;
            g.history[k] = og.history[closest];
            g.history[k].gap = gap;
            if constexpr (requires { h.shear; }) {
              const auto [ot1, ot2] = old_tangents(m, og, closest);
              const Vec3 nt2 = n.cross(tt1);
              const Vec3 shear = g.history[k].shear[0] * ot1 + g.history[k].shear[1] * ot2;
              g.history[k].shear = {shear.dot(tt1), shear.dot(nt2)};
            }
          } else if (it == previous.end()) {
            // A CP where the pair had none (an impact, a new pair after sliding) was never part of a bonded joint
            // and starts from the law's failed state, as for rigid blocks.
            if constexpr (requires { h.failed; }) g.history[k].failed = contact::never_bonded;
            if constexpr (requires { h.damage; }) g.history[k].damage = 1.0;
          } else {
            const std::size_t o = it->second;
            g.history[k] = og.history[o];
            g.spring_state[k] = og.spring_state[o];
            slip = og.slip_dissipation[o];
            viscous = og.viscous_dissipation[o];
            g.slip_dissipation[k] = slip;
            g.viscous_dissipation[k] = viscous;
            carried_slip += slip;
            carried_viscous += viscous;
            if constexpr (requires { h.shear; }) {
              const auto [ot1, ot2] = old_tangents(m, og, o);
              const Vec3 nt2 = n.cross(tt1);
              const Vec3 shear = g.history[k].shear[0] * ot1 + g.history[k].shear[1] * ot2;
              g.history[k].shear = {shear.dot(tt1), shear.dot(nt2)};
            }
          }
        }
      }
    };
    constexpr std::size_t rigid_face = law_index<Params>(), deformable_face = sizeof...(Laws) + law_index<Params>();
    if (m.deformable.is_deformable(fs))
      add(std::get<deformable_face>(groups), std::get<deformable_face>(old), previous_contacts[deformable_face],
          previous_pairs[deformable_face]);
    else
      add(std::get<rigid_face>(groups), std::get<rigid_face>(old), previous_contacts[rigid_face], previous_pairs[rigid_face]);
  }

  template <class G>
  static std::pair<Vec3, Vec3> old_tangents(const model::Model& m, const G& g, std::size_t k) {
    const auto& x = m.deformable.nodes.position;
    if constexpr (G::FaceKinematics::deformable) {
      const auto& tri = g.triangle[k];
      const Vec3 n = -(x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).normalized();
      const Vec3 t1 = (x[tri[1]] - x[tri[0]]).normalized();
      return {t1, n.cross(t1)};
    } else {
      const Mat3& r = m.bodies.rotation[g.face_block[k]];
      const Vec3 n = r * g.normal_local[k], t1 = r * g.tangent_local[k];
      return {t1, n.cross(t1)};
    }
  }

  static std::array<double, 3> barycentric3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
    const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
    const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
    const double den = d00 * d11 - d01 * d01;
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    return {1.0 - v - w, v, w};
  }
  static std::array<double, 3> barycentric2(const model::detail::Polygon2& t, const model::detail::Point2& p) {
    const double den = model::detail::cross2(t[0], t[1], t[2]);
    return {model::detail::cross2(p, t[1], t[2]) / den, model::detail::cross2(t[0], p, t[2]) / den,
            model::detail::cross2(t[0], t[1], p) / den};
  }
  static std::pair<double, model::detail::Point2> area_centroid(const model::detail::Polygon2& p) {
    double a = 0, cx = 0, cy = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto& u = p[i];
      const auto& v = p[(i + 1) % p.size()];
      const double c = u[0] * v[1] - v[0] * u[1];
      a += c;
      cx += (u[0] + v[0]) * c;
      cy += (u[1] + v[1]) * c;
    }
    a *= 0.5;
    return {std::abs(a), {cx / (6 * a), cy / (6 * a)}};
  }
  /// Andrew's monotone chain, counter-clockwise, collinear points dropped.
  static model::detail::Polygon2 convex_hull(model::detail::Polygon2 p) {
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    double scale = 0;
    for (const auto& v : p) scale = std::max({scale, std::abs(v[0] - p[0][0]), std::abs(v[1] - p[0][1])});
    const double eps = 1e-12 * scale * scale;
    model::detail::Polygon2 h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      while (k >= 2 && model::detail::cross2(h[k - 2], h[k - 1], p[i]) <= eps) --k;
      h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
      while (k >= t && model::detail::cross2(h[k - 2], h[k - 1], p[i - 1]) <= eps) --k;
      h[k++] = p[i - 1];
    }
    h.resize(k - 1);
    return h;
  }

  template <class G>
  void node_contact_pass(G& g, const model::Model& m, const Damping& damping, double increment_dt) {
    using L = typename G::LawType;
    const auto& b = m.bodies;
    const Vec3* __restrict const x = m.deformable.nodes.position.data();
    const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
    const auto count = static_cast<std::ptrdiff_t>(g.size());
#pragma omp parallel for schedule(static) if (count > 256)
    for (std::ptrdiff_t kk = 0; kk < count; ++kk) {
      const auto k = static_cast<std::size_t>(kk);
      const std::uint32_t node = g.node[k];
      Vec3 n, t1, v_face, arm;
      if constexpr (G::FaceKinematics::deformable) {
        const auto& tri = g.triangle[k];
        const auto& w = g.weight[k];
        const Vec3 e1 = x[tri[1]] - x[tri[0]];
        n = -e1.cross(x[tri[2]] - x[tri[0]]).normalized();
        t1 = e1.normalized();
        v_face = w[0] * velocity[tri[0]] + w[1] * velocity[tri[1]] + w[2] * velocity[tri[2]];
      } else {
        const std::uint32_t fb = g.face_block[k];
        const Mat3& r = b.rotation[fb];
        n = rotate(r, g.normal_local[k]);
        t1 = rotate(r, g.tangent_local[k]);
        arm = rotate(r, g.point_local[k]);
        v_face = b.velocity[fb] + b.angular_velocity[fb].cross(arm);
      }
      const Vec3 t2 = n.cross(t1);
      const Vec3 du = increment_dt * (v_face - velocity[node]);
      const double du_n = du.dot(n);
      const contact::Shear du_s{du.dot(t1), du.dot(t2)};
      const auto& p = g.properties[g.property[k]];
      const double kn = L::normal_stiffness(p), ks = L::shear_stiffness(p);
      const contact::Response r = L::update(p, g.history[k], du_n, du_s);
      const bool active = r.damping_active;  // L::damping_active(p, g.history[k])
      double dissipated = 0.0;
      auto& spring = g.spring_state[k];
      const double sn = r.normal_stress + damping.spring_stress(spring[0], kn, -du_n, increment_dt, active, dissipated);
      const double s1 = r.shear_stress[0] + damping.spring_stress(spring[1], ks, -du_s[0], increment_dt, active, dissipated);
      const double s2 = r.shear_stress[1] + damping.spring_stress(spring[2], ks, -du_s[1], increment_dt, active, dissipated);
      g.traction[k] = {sn, s1, s2};
      const double area = g.area[k];
      const Vec3 f = area * (sn * n + s1 * t1 + s2 * t2);
      g.force[k] = f;
      if constexpr (!G::FaceKinematics::deformable) g.moment[k] = arm.cross(f);
      g.slip_dissipation[k] += area * r.dissipated;
      g.viscous_dissipation[k] += area * dissipated;
    }
  }
};

}  // namespace blockdem::kinematics
