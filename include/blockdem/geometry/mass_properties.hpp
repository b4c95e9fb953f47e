#pragma once
// Volume, centroid and inertia tensor of a convex polyhedron, by decomposition into tetrahedra.

#include <Eigen/Eigenvalues>

#include "blockdem/geometry/convex_polyhedron.hpp"

namespace blockdem::geometry {

struct MassProperties {
  double volume = 0;                      // m^3
  Vec3 centroid = Vec3::Zero();           // m
  Mat3 inertia = Mat3::Zero();            // about the centroid, per unit density: m^5 (multiply by kg/m^3)
  Vec3 principal_moments = Vec3::Zero();  // eigenvalues of `inertia`, ascending, m^5
  Mat3 principal_axes = Mat3::Identity(); // columns: the principal directions (a rotation, det +1)
};

/// Exact for any closed polyhedron with outward faces: each face is fanned into triangles that form tetrahedra
/// with a reference point; a tetrahedron with vertices w_i has volume V = det[w1-w0, w2-w0, w3-w0] / 6 and second
/// moment int x x^T dV = V/20 (sum_i w_i w_i^T + s s^T), s = sum_i w_i.
inline MassProperties mass_properties(const ConvexPolyhedron& p) {
  MassProperties m;
  const Vec3 o = p.centroid_of_vertices();  // reference point, for accuracy far from the origin
  Mat3 second = Mat3::Zero();
  Vec3 first = Vec3::Zero();
  for (const auto& face : p.faces) {
    const Vec3 a = p.vertices[static_cast<std::size_t>(face[0])] - o;
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      const Vec3 b = p.vertices[static_cast<std::size_t>(face[i])] - o;
      const Vec3 c = p.vertices[static_cast<std::size_t>(face[i + 1])] - o;
      const double v = a.dot(b.cross(c)) / 6.0;  // tetrahedron (0, a, b, c)
      m.volume += v;
      const Vec3 s = a + b + c;
      first += v * s / 4.0;
      second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
  }
  const Vec3 c = first / m.volume;  // relative to o
  m.centroid = o + c;
  const Mat3 covariance = second - m.volume * c * c.transpose();
  m.inertia = covariance.trace() * Mat3::Identity() - covariance;
  Eigen::SelfAdjointEigenSolver<Mat3> eigen(m.inertia);
  m.principal_moments = eigen.eigenvalues();
  m.principal_axes = eigen.eigenvectors();
  if (m.principal_axes.determinant() < 0) m.principal_axes.col(2) *= -1.0;
  return m;
}

}  // namespace blockdem::geometry
