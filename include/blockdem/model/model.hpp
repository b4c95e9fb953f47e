#pragma once
// The model: rigid blocks in struct-of-arrays storage, their shapes in body frames, fixity and base motion, gravity.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/mass_properties.hpp"

namespace blockdem::model {

/// How a block moves: free (equations of motion), fixed (never moves), or base (follows the prescribed base
/// velocity history, like a shake table; rotation none).
enum class Motion : std::uint8_t { free, fixed, base };

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
    const Quaternion q(props.principal_axes);
    bodies.orientation.push_back(q.normalized());
    bodies.rotation.push_back(q.normalized().toRotationMatrix());
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
    return bodies.size() - 1;
  }

  double volume(std::size_t i) const { return volume_[i]; }
  double total_mass(Motion which = Motion::free) const {
    double m = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies.motion[i] == which) m += bodies.mass[i];
    return m;
  }

  RigidBodies bodies;
  Vec3 gravity = Vec3(0, 0, -9.81);  // m/s^2
  /// Velocity of base blocks at time t (s), m/s; zero unless set.
  std::function<Vec3(double)> base_velocity = [](double) { return Vec3::Zero(); };

 private:
  std::vector<double> volume_;
};

}  // namespace blockdem::model
