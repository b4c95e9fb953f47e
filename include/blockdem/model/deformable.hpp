#pragma once
// Deformable blocks (paper Sect. 3.1-3.2): nodes with 3 degrees of freedom and lumped masses, constant-strain
// tetrahedra of an isotropic linear elastic material, in struct-of-arrays storage; and truss elements (steel ties:
// axial bars between two attachment points). Each deformable block keeps an entry in the rigid arrays (its
// undeformed shape, all degrees of freedom fixed there) that names it and serves the contact detection.

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/tetrahedral_mesh.hpp"

namespace blockdem::model {

/// Isotropic linear elasticity. Throws InvalidArgument unless E > 0 and -1 < nu < 0.5.
struct IsotropicElastic {
  double young = 0;    // Pa
  double poisson = 0;  // dimensionless

  IsotropicElastic() = default;
  IsotropicElastic(double e, double nu) : young(e), poisson(nu) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidArgument("elastic material: Young's modulus must be > 0 Pa, got " + std::to_string(e));
    if (!(nu > -1.0 && nu < 0.5)) throw InvalidArgument("elastic material: Poisson's ratio must be in (-1, 0.5), got " + std::to_string(nu));
  }
  double bulk() const { return young / (3.0 * (1.0 - 2.0 * poisson)); }   // K, Pa
  double shear() const { return young / (2.0 * (1.0 + poisson)); }        // G, Pa
  double p_wave() const { return bulk() + 4.0 / 3.0 * shear(); }           // K + 4G/3, Pa (eq. 2)
};

/// Nodes of all deformable blocks (each block's nodes contiguous).
struct Nodes {
  std::vector<Vec3> position;      // m
  std::vector<Vec3> velocity;      // m/s, at the half step
  std::vector<Vec3> force;         // N: elements, contacts, trusses, gravity
  std::vector<double> mass;        // kg, lumped, after density scaling (the inertia)
  std::vector<double> real_mass;   // kg, lumped, before density scaling (the weight)
  std::vector<std::uint8_t> fixity;  // bit i: translation i fixed
  std::vector<std::uint32_t> block;  // owning block
  std::size_t size() const { return position.size(); }
  double density_scaling_factor(std::size_t i) const { return mass[i] / real_mass[i]; }  // dsf = m_scaled / m_real
};

/// Constant-strain tetrahedra of all deformable blocks.
struct Tetrahedra {
  std::vector<geometry::Tetrahedron> node;         // global node indices
  std::vector<std::array<Vec3, 4>> gradient;       // 1/m, grad N_i of the linear shape functions (reference shape)
  std::vector<double> volume;                      // m^3
  std::vector<double> stiffness;                   // N/m, (K + 4G/3)(3A/h) with A the largest face, h the shortest height (eq. 2)
  std::vector<std::uint16_t> material;             // index into DeformableBodies::materials
  std::vector<std::array<double, 6>> stress;       // Pa, xx yy zz xy yz zx, tension positive (the elastic part)
  std::size_t size() const { return volume.size(); }
};

/// Where a truss end is attached: a node (node >= 0), or a point fixed on a rigid block (body point in its frame).
struct TrussEnd {
  std::int64_t node = -1;
  std::size_t block = 0;
  Vec3 body_point = Vec3::Zero();  // m, in the block's body frame
};

/// An axial bar: area (m^2), Young's modulus (Pa), density (kg/m^3, its mass lumped half to each end) and a
/// pretension (N, tension positive) at its initial length.
struct Truss {
  TrussEnd end[2];
  double area = 0;
  double young = 0;
  double density = 0;
  double pretension = 0;
  double length0 = 0;  // m
  std::string name;
  double axial_stiffness() const { return young * area / length0; }  // N/m
};

struct DeformableBodies {
  Nodes nodes;
  Tetrahedra tetrahedra;
  std::vector<IsotropicElastic> materials;
  /// Per deformable block: first node, first tetrahedron, mesh boundary triangles (global node ids) with the face of
  /// the block's shape (body frame of its rigid entry) each lies on.
  struct Block {
    std::size_t body = 0;
    std::uint32_t first_node = 0, end_node = 0;
    std::uint32_t first_tetrahedron = 0, end_tetrahedron = 0;
    std::vector<std::array<std::uint32_t, 3>> boundary;
    std::vector<int> boundary_face;
    std::vector<Vec3> reference_position;  // m, its nodes at the start (for the mean motion)
    Vec3 reference_centroid = Vec3::Zero();  // m, its rigid entry's centroid at the start
  };
  std::vector<Block> blocks;
  std::vector<int> block_of_body;  // -1 for rigid blocks
  std::vector<Truss> trusses;

  bool empty() const { return blocks.empty() && trusses.empty(); }
  bool is_deformable(std::size_t body) const { return body < block_of_body.size() && block_of_body[body] >= 0; }
};

}  // namespace blockdem::model
