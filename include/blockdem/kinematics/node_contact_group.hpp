#pragma once
// Contact points on deformable blocks (3DEC's sub-contacts): one CP per face node of the deformable (node) side that
// lies on the overlap of the joint, with the node's tributary area, against the face of the other (face) side.
// Face side Rigid: a material point of the rigid block, with the contact frame fixed in that block. Face side
// Deformable: a point of one boundary triangle with fixed barycentric weights, the frame fixed to that triangle
// (normal against the triangle's outward normal, t1 along its first edge). The normal n points from the node side
// to the face side; the traction acts on the face side, its opposite on the node.

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <type_traits>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/kinematics/concepts.hpp"

namespace blockdem::kinematics {

template <contact::ContactLaw Law, damping::DampingPolicy Damping, Kinematics FaceSide>
struct NodeContactGroup {
  using LawType = Law;
  using FaceKinematics = FaceSide;
  using Parameters = typename Law::Parameters;
  using History = typename Law::History;
  using SpringState = std::array<typename Damping::ContactState, 3>;
  using Traction = std::array<double, 3>;

  std::vector<Parameters> properties;

  // Per contact point.
  std::vector<std::uint32_t> node;         // node side: the node
  std::vector<std::uint32_t> node_block;   // its block
  std::vector<std::uint32_t> face_block;   // face side: the block
  std::vector<std::uint16_t> property;
  std::vector<double> area;                // m^2, the node's tributary area on the overlap
  // Face side Rigid: point, normal and t1 in the block's body frame (from its centroid).
  std::vector<Vec3> point_local, normal_local, tangent_local;
  // Face side Deformable: the triangle's nodes and the barycentric weights of the point.
  std::vector<std::array<std::uint32_t, 3>> triangle;
  std::vector<std::array<double, 3>> weight;
  std::vector<History> history;
  std::vector<SpringState> spring_state;
  std::vector<Traction> traction;          // Pa: normal (compression +), t1, t2
  std::vector<Vec3> force;                 // N, world, on the face side (the node gets the opposite)
  std::vector<Vec3> moment;                // N m, on a rigid face side about its centroid
  std::vector<double> slip_dissipation;    // J
  std::vector<double> viscous_dissipation; // J

  std::size_t size() const { return area.size(); }

  /// Every array, for checkpoints (io/checkpoint.hpp).
  void save_state(io::CheckpointWriter& out) const { visit_state(*this, out); }
  void load_state(io::CheckpointReader& in) { visit_state(*this, in); }
  template <class Self, class Archive>
  static void visit_state(Self& g, Archive& ar) {
    ar("node contact property sets", g.properties);
    ar("node contact nodes", g.node);
    ar("node contact node blocks", g.node_block);
    ar("node contact face blocks", g.face_block);
    ar("node contact property indices", g.property);
    ar("node contact areas", g.area);
    ar("node contact face points", g.point_local);
    ar("node contact face normals", g.normal_local);
    ar("node contact face tangents", g.tangent_local);
    ar("node contact face triangles", g.triangle);
    ar("node contact face weights", g.weight);
    ar("node contact histories", g.history);
    ar("node contact spring states", g.spring_state);
    ar("node contact tractions", g.traction);
    ar("node contact forces", g.force);
    ar("node contact moments", g.moment);
    ar("node contact slip dissipation", g.slip_dissipation);
    ar("node contact viscous dissipation", g.viscous_dissipation);
  }

  void add(std::uint32_t n, std::uint32_t nb, std::uint32_t fb, std::uint16_t p, double a, const History& h,
           const SpringState& s, double slip, double viscous) {
    node.push_back(n);
    node_block.push_back(nb);
    face_block.push_back(fb);
    property.push_back(p);
    area.push_back(a);
    history.push_back(h);
    spring_state.push_back(s);
    traction.push_back({0, 0, 0});
    force.push_back(Vec3::Zero());
    moment.push_back(Vec3::Zero());
    slip_dissipation.push_back(slip);
    viscous_dissipation.push_back(viscous);
    if constexpr (FaceSide::deformable) {
      triangle.push_back({0, 0, 0});
      weight.push_back({0, 0, 0});
    } else {
      point_local.push_back(Vec3::Zero());
      normal_local.push_back(Vec3::Zero());
      tangent_local.push_back(Vec3::Zero());
    }
  }

  /// Orders the points by their node, stably (the points of one node keep their order). The passes split the nodes,
  /// the elements and the points over the threads by ranges of their indices: with the points in node order, a
  /// point's node, its gather entries and most of its face side's nodes fall in its own thread's range, so that
  /// little of what a thread reads was written by another (which costs a trip between caches, docs/performance.md).
  void sort_by_node() {
    if (std::is_sorted(node.begin(), node.end())) return;
    std::vector<std::uint32_t> order(size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return node[a] < node[b]; });
    const auto permute = [&](auto& v) {
      if (v.empty()) return;
      std::remove_cvref_t<decltype(v)> sorted;
      sorted.reserve(v.size());
      for (std::uint32_t k : order) sorted.push_back(v[k]);
      v.swap(sorted);
    };
    permute(node), permute(node_block), permute(face_block), permute(property), permute(area);
    permute(point_local), permute(normal_local), permute(tangent_local), permute(triangle), permute(weight);
    permute(history), permute(spring_state), permute(traction), permute(force), permute(moment);
    permute(slip_dissipation), permute(viscous_dissipation);
  }
};

}  // namespace blockdem::kinematics
