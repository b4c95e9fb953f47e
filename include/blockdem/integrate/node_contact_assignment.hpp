#pragma once
// Contact assignment for the node contacts of deformable blocks (3DEC's sub-contacts): for each block pair with a
// deformable block among a detection's candidates, the overlap polygon on the pair's common plane, the node side
// (the deformable one; of two, the one with more nodes on the joint, kept from the first detection on), one contact
// point per node of the node side's facing triangles with the node's tributary area on the overlap, against the face
// of the other side. At a re-detection every CP inherits the old state by the rule of rigid contacts
// (integrate/contact_history.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/type_list.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/geometry/polygon.hpp"
#include "blockdem/integrate/contact_frame.hpp"
#include "blockdem/integrate/contact_history.hpp"
#include "blockdem/integrate/deformable_state.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// The assignment of detected contact points to the node contact groups of a DeformableState, with the scratch of
/// a detection (the old CPs by node and face block, and by block pair; the node side of each pair).
template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
class NodeContactAssignment {
 public:
  using State = DeformableState<Damping, Laws...>;
  using Groups = typename State::Groups;

  /// Builds the node contact points of the block pairs with a deformable block among `candidates` (CPs of one pair
  /// contiguous, from the detection on the blocks' rigid entries). `choose(tag_a, tag_b)` gives the law's parameters
  /// as a variant over Laws::Parameters. With keep_history, a CP of the same node against the same block takes over
  /// the old history and damping state.
  template <class Choose>
  void assign(State& state, const model::Model& m, const std::vector<model::ContactCandidate>& candidates, Choose&& choose,
              const model::ContactSettings& settings, bool keep_history) {
    Groups old = std::move(state.groups);
    state.groups = Groups{};
    std::apply([&](auto&... g) { ((g.properties = std::get<std::remove_cvref_t<decltype(g)>>(old).properties), ...); }, state.groups);
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
      // One joint per plane: the detection gives the CPs of every face pair of two blocks together, and two blocks
      // may touch on two faces at an angle (the webs of the vault at its groins). Measured on one plane, the nodes of
      // the other face came in centimetres off their joint, as contact points overlapped by that much.
      rest_.assign(candidates.begin() + static_cast<std::ptrdiff_t>(begin), candidates.begin() + static_cast<std::ptrdiff_t>(end));
      while (!rest_.empty()) {
        const Vec3 n0 = rest_.front().normal, p0 = rest_.front().position;
        plane_.clear();
        other_.clear();
        for (const auto& cp : rest_)
          (cp.normal.dot(n0) >= same_plane_cos && std::abs((cp.position - p0).dot(n0)) <= settings.tolerance ? plane_ : other_).push_back(cp);
        std::visit([&](const auto& p) {
          pair_contacts(state, m, p, plane_.data(), plane_.data() + plane_.size(), da, db, cos_max, settings.tolerance, old,
                        keep_history, carried_slip, carried_viscous);
        }, params);
        rest_.swap(other_);
      }
    }
    state.retired_slip += old_slip - carried_slip;
    state.retired_viscous += old_viscous - carried_viscous;
    state.for_each_group([](auto& g) { g.sort_by_node(); });
    state.build_contact_lists(m);
    state.detected_node_position = m.deformable.nodes.position;
    for (auto& p : previous_contacts) p.clear();
    for (auto& p : previous_pairs) p.clear();
    previous_sides.clear();
  }

  /// Two CPs of a pair are on one joint when their normals are within 0.01 rad and their positions within the
  /// contact tolerance of one plane.
  static constexpr double same_plane_cos = 0.99995;  // cos(0.01)

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
   private:
  std::vector<model::ContactCandidate> rest_, plane_, other_;  // a pair's CPs still to place, on this plane, on others
  struct TrianglePiece {
    std::array<std::uint32_t, 3> node;  // a facing triangle's nodes, counter-clockwise on the common plane
    std::array<double, 3> share;        // of its area on the overlap: A N_j(centroid), m^2
  };
  std::vector<TrianglePiece> pieces_;  // a pair's facing triangles clipped to its overlap

  static std::uint64_t contact_key(std::uint64_t node, std::uint64_t face_block) { return (node << 32) | face_block; }

  static double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
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
  void pair_contacts(State& state, const model::Model& m, const Params& params, const model::ContactCandidate* first,
                     const model::ContactCandidate* last, bool da, bool db, double cos_max, double settings_tolerance, Groups& old,
                     bool keep_history, double& carried_slip, double& carried_viscous) {
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
    geometry::Polygon2 points;
    for (auto c = first; c != last; ++c) {
      const Vec3 d = c->position - origin;
      points.push_back({d.dot(t1), d.dot(t2)});
    }
    const auto overlap = geometry::convex_hull(points);
    if (overlap.size() < 3) return;
    // Tributary areas: each facing triangle of the node side clipped to the overlap; the clipped area A goes to the
    // triangle's nodes as A N_j(centroid) = the integral of the linear shape function N_j over it, but only to nodes
    // on the overlap: a node outside it (beyond the edge of the other block's face) would push on that face's plane
    // extended past its edge, and a block rocking about that edge would then press the plane into the node, a
    // restoring moment that holds the rocking back (a block tipping on a deformable one moved 0.8 mm instead of 11 mm).
    // A straddling triangle's share goes to its nodes on the overlap, in proportion to theirs. This needs nodes that
    // span the overlap: if those on it enclose less than half of its area (a small face on a coarse mesh), every
    // triangle keeps the shape-function split, or the joint would stand on a point or a line.
    const auto& nblk = m.deformable.blocks[static_cast<std::size_t>(m.deformable.block_of_body[ns])];
    pieces_.clear();
    geometry::Polygon2 on_overlap;
    for (std::size_t k : facing_triangles(m, ns, n, cos_max)) {
      const auto& tri = nblk.boundary[k];
      geometry::Polygon2 p2;
      for (auto v : tri) {
        const Vec3 d = x[v] - origin;
        p2.push_back({d.dot(t1), d.dot(t2)});
      }
      std::array<std::uint32_t, 3> order = tri;
      if (geometry::polygon_area(p2) < 0) {
        std::swap(p2[1], p2[2]);
        std::swap(order[1], order[2]);
      }
      const auto clipped = geometry::clip_convex(p2, overlap);
      if (clipped.size() < 3) continue;
      const auto [area, centre] = geometry::area_centroid(clipped);
      if (!(area > 0)) continue;
      const auto l = geometry::barycentric2(p2, centre);
      pieces_.push_back({order, {area * l[0], area * l[1], area * l[2]}});
      for (std::size_t j = 0; j < 3; ++j)
        if (geometry::inside_convex(overlap, p2[j], settings_tolerance)) on_overlap.push_back(p2[j]);
    }
    const auto span = geometry::convex_hull(on_overlap);
    const bool spanned = span.size() >= 3 && geometry::polygon_area(span) >= 0.5 * geometry::polygon_area(overlap);
    std::map<std::uint32_t, double> tributary;
    for (const auto& piece : pieces_) {
      std::array<bool, 3> on{};
      double on_share = 0;
      for (std::size_t j = 0; j < 3; ++j) {
        const Vec3 d = x[piece.node[j]] - origin;
        on[j] = spanned && geometry::inside_convex(overlap, {d.dot(t1), d.dot(t2)}, settings_tolerance);
        if (on[j]) on_share += piece.share[j];
      }
      const bool moved = on_share > 0 && !(on[0] && on[1] && on[2]);  // a share to move to the nodes on the overlap
      const double scale = moved ? (piece.share[0] + piece.share[1] + piece.share[2]) / on_share : 1.0;
      for (std::size_t j = 0; j < 3; ++j) {
        const double share = moved ? (on[j] ? piece.share[j] * scale : 0.0) : piece.share[j];
        if (share > 0) tributary[piece.node[j]] += share;
      }
    }
    using L = std::tuple_element_t<index_in<Params, typename Laws::Parameters...>(), std::tuple<Laws...>>;
    auto add = [&](auto& g, auto& og, const std::unordered_map<std::uint64_t, std::size_t>& previous,
                   const std::unordered_map<std::uint64_t, std::vector<std::size_t>>& pairs) {
      const auto pair = pairs.find(contact_key(ns, fs));
      std::size_t property = 0;
      while (property < g.properties.size() && !(g.properties[property] == params)) ++property;
      if (property == g.properties.size()) g.properties.push_back(params);
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
        if (!(area > 1e-12 * geometry::polygon_area(overlap))) continue;
        const Vec3 xn = x[node];
        const typename L::History h{};
        const typename G::SpringState spring{};
        Vec3 tt1 = t1;
        double gap = 0, slip = 0, viscous = 0;
        // The point of the face side: the triangle the node's projection lies the most inside of (deformable), or
        // the face of the rigid block that faces the node; the gap along the joint's normal.
        std::array<std::uint32_t, 3> triangle{};
        std::array<double, 3> weight{};
        Vec3 point = Vec3::Zero();
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
              triangle = tri;
              weight = w;
              gap = s;
              tt1 = e1.normalized();
            }
          }
          if (!(best > -1e300)) continue;  // no face of the other block faces the node
        } else {
          const Vec3 nf = face_world.face_normal(face_index);
          const double s = nf.dot(face_world.face_centroid(face_index) - xn) / nf.dot(n);
          point = xn + s * n;
          gap = s;
        }
        // A node farther than twice the contact tolerance from the other block's face is not on this joint: the
        // faces of a joint are within the tolerance of each other when it is detected, and between two detections
        // nothing moves more than half of it. Such a node lies on a face next to the joint's that faces the same
        // way within the normal angle and projects onto a sliver of the overlap (where the webs of the vault meet
        // at its groins); with a contact point, it came in overlapped by centimetres.
        if (std::abs(gap) > 2.0 * settings_tolerance) continue;
        const std::size_t k = g.size();
        g.add(node, static_cast<std::uint32_t>(ns), static_cast<std::uint32_t>(fs), static_cast<std::uint16_t>(property), area, h,
              spring, 0, 0);
        if constexpr (G::FaceKinematics::deformable) {
          g.triangle[k] = triangle;
          g.weight[k] = weight;
        } else {
          const Mat3& r = m.bodies.rotation[fs];
          g.point_local[k] = r.transpose() * (point - m.bodies.position[fs]);
          g.normal_local[k] = r.transpose() * n;
          g.tangent_local[k] = r.transpose() * t1;
        }
        // The state the CP inherits (integrate/contact_history.hpp): the same node against the same block, else the
        // joint of the pair where it is (the closest old CP of the pair), else none: a new contact.
        Inheritance from = keep_history ? Inheritance::new_contact : Inheritance::first_detection;
        std::size_t source = 0;
        if (keep_history) {
          if (const auto it = previous.find(contact_key(node, fs)); it != previous.end()) {
            from = Inheritance::same_point;
            source = it->second;
          } else if (pair != pairs.end()) {
            from = Inheritance::same_joint;
            source = pair->second.front();
            for (std::size_t j : pair->second)
              if ((x[og.node[j]] - xn).squaredNorm() < (x[og.node[source]] - xn).squaredNorm()) source = j;
          }
        }
        const bool inherits = from == Inheritance::same_point || from == Inheritance::same_joint;
        contact::ShearTurn turn;
        if (inherits) {
          const auto [ot1, ot2] = old_tangents(m, og, source);
          turn = shear_turn(ot1, ot2, tt1, n.cross(tt1));
        }
        g.history[k] = inherited_history<L>(from, inherits ? &og.history[source] : nullptr, gap, turn);
        if (from == Inheritance::same_point) {
          g.spring_state[k] = inherited_spring_state(og.spring_state[source], turn);
          slip = og.slip_dissipation[source];
          viscous = og.viscous_dissipation[source];
          g.slip_dissipation[k] = slip;
          g.viscous_dissipation[k] = viscous;
          carried_slip += slip;
          carried_viscous += viscous;
        }
      }
    };
    constexpr std::size_t rigid_face = index_in<Params, typename Laws::Parameters...>(), deformable_face = sizeof...(Laws) + rigid_face;
    if (m.deformable.is_deformable(fs))
      add(std::get<deformable_face>(state.groups), std::get<deformable_face>(old), previous_contacts[deformable_face],
          previous_pairs[deformable_face]);
    else
      add(std::get<rigid_face>(state.groups), std::get<rigid_face>(old), previous_contacts[rigid_face], previous_pairs[rigid_face]);
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

  /// The old CPs of each group by (node, face block), built once per detection (per block pair it cost the whole
  /// detection's time: some 4 s for the deformable vault's 3,000 pairs and 16,000 CPs).
  std::array<std::unordered_map<std::uint64_t, std::size_t>, 2 * sizeof...(Laws)> previous_contacts;
  std::unordered_set<std::uint64_t> previous_sides;  // (node block, face block) of the old CPs: the side kept
  /// The old CPs of each group by (node block, face block): the joint a CP that the pair adds belongs to.
  std::array<std::unordered_map<std::uint64_t, std::vector<std::size_t>>, 2 * sizeof...(Laws)> previous_pairs;
};

}  // namespace blockdem
