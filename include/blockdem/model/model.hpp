#pragma once
// The model: rigid blocks in struct-of-arrays storage, their shapes in body frames, fixity and base motion, gravity.

#include <cstdint>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/rotation.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/tetrahedral_mesh.hpp"
#include "blockdem/model/deformable.hpp"
#include "blockdem/motion/base_motion.hpp"

namespace blockdem::model {

/// How a block moves: free (equations of motion), fixed (never moves), or base (follows the prescribed base
/// velocity history, like a shake table; rotation none).
enum class Motion : std::uint8_t { free, fixed, base };
constexpr bool valid_enumerator(Motion m) noexcept { return m == Motion::free || m == Motion::fixed || m == Motion::base; }

/// Degrees of freedom a free block may not use (bit i: translation i, bit 3 + i: rotation about world axis i).
enum Fixity : std::uint8_t {
  none = 0,
  translation_x = 1, translation_y = 2, translation_z = 4,
  rotation_x = 8, rotation_y = 16, rotation_z = 32,
  all_rotations = rotation_x | rotation_y | rotation_z,
};

/// Rigid blocks, one entry per block in each array. Body frame: origin at the centroid, axes along the principal
/// axes of inertia; `orientation` rotates body-frame vectors into the world frame.
struct RigidBodies {
  std::vector<Vec3> position;          // m, centroid in the world frame
  std::vector<Quaternion> orientation;
  std::vector<Mat3> rotation;          // orientation as a matrix, refreshed after every update
  std::vector<Vec3> velocity;          // m/s (at the half step in the central-difference scheme)
  std::vector<Vec3> angular_velocity;  // rad/s, world frame
  std::vector<double> mass;            // kg
  std::vector<Vec3> principal_inertia; // kg m^2, body frame
  std::vector<Vec3> force;             // N, world frame (contacts + gravity, before damping)
  std::vector<Vec3> moment;            // N m, world frame
  std::vector<Motion> motion;
  std::vector<std::uint8_t> fixity;    // Fixity bits
  std::vector<int> joint_tag;          // chooses the contact law between two blocks
  std::vector<std::string> name;
  std::vector<geometry::ConvexPolyhedron> shape;  // in the body frame

  std::size_t size() const { return position.size(); }

  /// World coordinates of the shape of block i.
  geometry::ConvexPolyhedron world_shape(std::size_t i) const { return shape[i].transformed(rotation[i], position[i]); }
  /// World position of a point given in block i's body frame.
  Vec3 to_world(std::size_t i, const Vec3& body_point) const { return position[i] + rotation[i] * body_point; }
};

class Model {
 public:
  /// Adds a block from its shape in world coordinates; density in kg/m^3 (> 0). Returns its index.
  /// Throws InvalidArgument naming the block if the shape is invalid or the density not positive.
  std::size_t add_block(const geometry::ConvexPolyhedron& world_shape, double density, std::string name,
                        int joint_tag = 0, Motion motion = Motion::free) {
    if (name.empty()) name = "block " + std::to_string(bodies.size());
    world_shape.validate(name);
    if (!(density > 0.0) || !std::isfinite(density))
      throw InvalidArgument("block '" + name + "': density must be > 0 kg/m^3, got " + std::to_string(density));
    const auto props = geometry::mass_properties(world_shape);
    bodies.position.push_back(props.centroid);
    const Quaternion q = Quaternion(props.principal_axes).normalized();
    bodies.orientation.push_back(q);
    bodies.rotation.push_back(rotation_matrix(q));  // exactly what the step computes from the orientation
    bodies.velocity.push_back(Vec3::Zero());
    bodies.angular_velocity.push_back(Vec3::Zero());
    bodies.mass.push_back(density * props.volume);
    bodies.principal_inertia.push_back(density * props.principal_moments);
    bodies.force.push_back(Vec3::Zero());
    bodies.moment.push_back(Vec3::Zero());
    bodies.motion.push_back(motion);
    bodies.fixity.push_back(Fixity::none);
    bodies.joint_tag.push_back(joint_tag);
    bodies.name.push_back(std::move(name));
    bodies.shape.push_back(world_shape.transformed(props.principal_axes.transpose(),
                                                   -props.principal_axes.transpose() * props.centroid));
    volume_.push_back(props.volume);
    deformable.block_of_body.push_back(-1);
    return bodies.size() - 1;
  }

  /// Makes free block i deformable: meshes its current shape into constant-strain tetrahedra with edges of at most
  /// max_edge (m), lumps its density to the nodes (a quarter of each tetrahedron's mass to each of its nodes) and
  /// fixes all degrees of freedom of its rigid entry (which keeps naming it and serves the contact detection).
  /// Returns the number of tetrahedra. Throws InvalidArgument naming the block on bad input or a degenerate mesh.
  std::size_t make_deformable(std::size_t i, double max_edge, const IsotropicElastic& material) {
    if (i >= bodies.size()) throw InvalidArgument("make_deformable: no block " + std::to_string(i));
    const std::string& name = bodies.name[i];
    if (bodies.motion[i] != Motion::free) throw InvalidArgument("block '" + name + "': only free blocks can be deformable");
    if (deformable.is_deformable(i)) throw InvalidArgument("block '" + name + "' is already deformable");
    const IsotropicElastic checked(material.young, material.poisson);
    const auto mesh = geometry::mesh_convex_polyhedron(bodies.world_shape(i), max_edge, name);
    if (deformable.materials.size() >= 65535) throw InvalidArgument("make_deformable: more than 65535 materials");
    auto& nd = deformable.nodes;
    auto& te = deformable.tetrahedra;
    DeformableBodies::Block blk;
    blk.body = i;
    blk.reference_centroid = bodies.position[i];
    blk.first_node = static_cast<std::uint32_t>(nd.size());
    blk.first_tetrahedron = static_cast<std::uint32_t>(te.size());
    const double density = bodies.mass[i] / volume_[i];
    const auto material_index = static_cast<std::uint16_t>(deformable.materials.size());
    deformable.materials.push_back(checked);
    for (const auto& x : mesh.nodes) {
      nd.position.push_back(x);
      nd.velocity.push_back(bodies.velocity[i] + bodies.angular_velocity[i].cross(x - bodies.position[i]));
      nd.force.push_back(Vec3::Zero());
      nd.mass.push_back(0.0);
      nd.real_mass.push_back(0.0);
      nd.fixity.push_back(bodies.fixity[i] & 7);
      nd.block.push_back(static_cast<std::uint32_t>(i));
      blk.reference_position.push_back(x);
    }
    for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
      geometry::Tetrahedron global = mesh.tetrahedra[t];
      std::array<Vec3, 4> x;
      for (std::size_t k = 0; k < 4; ++k) {
        x[k] = mesh.nodes[global[k]];
        global[k] += blk.first_node;
      }
      Mat3 j;
      j.col(0) = x[1] - x[0];
      j.col(1) = x[2] - x[0];
      j.col(2) = x[3] - x[0];
      const double volume = j.determinant() / 6.0;
      const Mat3 inverse = j.inverse();  // rows: grad N_1, grad N_2, grad N_3
      std::array<Vec3, 4> g;
      for (std::size_t k = 1; k < 4; ++k) g[k] = inverse.row(static_cast<Eigen::Index>(k - 1)).transpose();
      g[0] = -(g[1] + g[2] + g[3]);
      // (K + 4G/3)(3A/h) with A the largest face area and h = 3V/A the shortest height: (K + 4G/3) A^2 / V (eq. 2).
      double largest_face = 0;
      for (std::size_t k = 0; k < 4; ++k) largest_face = std::max(largest_face, 3.0 * volume * g[k].norm());  // |grad N_k| = A_k / (3V)
      te.node.push_back(global);
      te.gradient.push_back(g);
      te.volume.push_back(volume);
      te.stiffness.push_back(checked.p_wave() * largest_face * largest_face / volume);
      te.material.push_back(material_index);
      te.stress.push_back({0, 0, 0, 0, 0, 0});
      for (std::size_t k = 0; k < 4; ++k) {
        nd.mass[global[k]] += 0.25 * density * volume;
        nd.real_mass[global[k]] += 0.25 * density * volume;
      }
    }
    blk.end_node = static_cast<std::uint32_t>(nd.size());
    blk.end_tetrahedron = static_cast<std::uint32_t>(te.size());
    for (std::size_t k = 0; k < mesh.boundary.size(); ++k) {
      auto tri = mesh.boundary[k];
      for (auto& n : tri) n += blk.first_node;
      blk.boundary.push_back(tri);
      blk.boundary_face.push_back(mesh.boundary_face[k]);
    }
    deformable.block_of_body[i] = static_cast<int>(deformable.blocks.size());
    deformable.blocks.push_back(std::move(blk));
    bodies.fixity[i] = Fixity::translation_x | Fixity::translation_y | Fixity::translation_z | Fixity::all_rotations;
    bodies.velocity[i].setZero();
    bodies.angular_velocity[i].setZero();
    return mesh.tetrahedra.size();
  }

  /// A truss end at node n.
  TrussEnd node_end(std::size_t n) const { return {static_cast<std::int64_t>(n), 0, Vec3::Zero()}; }
  /// A truss end at the world point x fixed on rigid block i.
  TrussEnd block_end(std::size_t i, const Vec3& x) const {
    return {-1, i, bodies.rotation[i].transpose() * (x - bodies.position[i])};
  }
  /// World position of a truss end.
  Vec3 end_position(const TrussEnd& e) const {
    return e.node >= 0 ? deformable.nodes.position[static_cast<std::size_t>(e.node)] : bodies.to_world(e.block, e.body_point);
  }
  /// The deformable node of block i nearest to the world point x.
  std::size_t nearest_node(std::size_t i, const Vec3& x) const {
    if (!deformable.is_deformable(i)) throw InvalidArgument("nearest_node: block '" + bodies.name[i] + "' is not deformable");
    const auto& blk = deformable.blocks[static_cast<std::size_t>(deformable.block_of_body[i])];
    std::size_t best = blk.first_node;
    for (std::size_t n = blk.first_node; n < blk.end_node; ++n)
      if ((deformable.nodes.position[n] - x).squaredNorm() < (deformable.nodes.position[best] - x).squaredNorm()) best = n;
    return best;
  }

  /// Adds a truss (steel tie) between two ends: area (m^2), Young's modulus (Pa), density (kg/m^3, half its mass
  /// lumped to each end), pretension (N, tension positive). Throws InvalidArgument on non-positive area, modulus or
  /// density, a negative pretension or coincident ends. Add trusses before building the Simulation.
  std::size_t add_truss(const TrussEnd& a, const TrussEnd& b, double area, double young, double density,
                        double pretension = 0, std::string name = {}) {
    if (name.empty()) name = "truss " + std::to_string(deformable.trusses.size());
    auto check = [&](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument("truss '" + name + "': " + what);
    };
    check(area > 0 && std::isfinite(area), "area must be > 0 m^2, got " + std::to_string(area));
    check(young > 0 && std::isfinite(young), "Young's modulus must be > 0 Pa, got " + std::to_string(young));
    check(density > 0 && std::isfinite(density), "density must be > 0 kg/m^3, got " + std::to_string(density));
    check(pretension >= 0 && std::isfinite(pretension), "pretension must be >= 0 N, got " + std::to_string(pretension));
    for (const auto* e : {&a, &b}) {
      if (e->node >= 0) check(static_cast<std::size_t>(e->node) < deformable.nodes.size(), "no node " + std::to_string(e->node));
      else check(e->block < bodies.size() && !deformable.is_deformable(e->block), "an end on a block must be on a rigid block");
    }
    Truss t;
    t.end[0] = a;
    t.end[1] = b;
    t.area = area;
    t.young = young;
    t.density = density;
    t.pretension = pretension;
    t.length0 = (end_position(b) - end_position(a)).norm();
    check(t.length0 > 0, "its ends coincide");
    t.name = std::move(name);
    const double half = 0.5 * density * area * t.length0;
    for (const auto* e : {&a, &b}) {
      if (e->node >= 0) {
        deformable.nodes.mass[static_cast<std::size_t>(e->node)] += half;
        deformable.nodes.real_mass[static_cast<std::size_t>(e->node)] += half;
      } else {
        bodies.mass[e->block] += half;
      }
    }
    deformable.trusses.push_back(std::move(t));
    return deformable.trusses.size() - 1;
  }

  double volume(std::size_t i) const { return volume_[i]; }
  double total_mass(Motion which = Motion::free) const {
    double m = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies.motion[i] == which) m += bodies.mass[i];
    return m;
  }

  RigidBodies bodies;
  DeformableBodies deformable;  // nodes, tetrahedra and trusses (empty for a rigid model)
  Vec3 gravity = Vec3(0, 0, -9.81);  // m/s^2
  /// The motion of the base blocks (the shake table): at rest unless set. Not saved in checkpoints: a model loaded
  /// from one gets its base motion from the caller, who sets it again as when the checkpoint was written.
  motion::BaseMotion base_motion;
  /// Velocity of the base blocks at time t (s), m/s: what the engine moves them with.
  Vec3 base_velocity(double t) const { return base_motion.velocity(t); }

  /// The state a simulation changes (or a user may change between steps), for checkpoints (io/checkpoint.hpp):
  /// load_state() into a model built the same way gives it back bitwise. Throws InvalidArgument if the counts of
  /// blocks, nodes or tetrahedra differ.
  template <class Writer>
  void save_state(Writer& out) const { visit_state(*this, out); }
  template <class Reader>
  void load_state(Reader& in) { visit_state(*this, in); }

 private:
  /// The one list of the saved fields, for both directions. Not saved, because the model is built again from its
  /// description before loading: the blocks' names, shapes, joint tags and volumes; the deformable blocks' meshes
  /// (nodes' real masses and owners, the tetrahedra but their stresses, materials, boundaries, reference positions);
  /// the trusses; base_motion (the caller's input, a function of the time, which is in the simulation's state).
  template <class Self, class Archive>
  static void visit_state(Self& m, Archive& ar) {
    auto& b = m.bodies;
    ar.same_size("block positions", b.position);
    ar.same_size("block orientations", b.orientation);
    ar.same_size("block rotations", b.rotation);
    ar.same_size("block velocities", b.velocity);
    ar.same_size("block angular velocities", b.angular_velocity);
    ar.same_size("block masses", b.mass);  // as scaled
    ar.same_size("block principal inertias", b.principal_inertia);
    ar.same_size("block forces", b.force);
    ar.same_size("block moments", b.moment);
    ar.same_size("block motions", b.motion);
    ar.same_size("block fixities", b.fixity);
    auto& nd = m.deformable.nodes;
    ar.same_size("node positions", nd.position);
    ar.same_size("node velocities", nd.velocity);
    ar.same_size("node forces", nd.force);
    ar.same_size("node masses", nd.mass);  // as scaled
    ar.same_size("node fixities", nd.fixity);
    ar.same_size("tetrahedron stresses", m.deformable.tetrahedra.stress);
    ar.check("the number of trusses", static_cast<std::uint64_t>(m.deformable.trusses.size()));
    ar("gravity", m.gravity);
  }

  std::vector<double> volume_;
};

}  // namespace blockdem::model
