#pragma once
// An upper bound on the highest eigenfrequency omega_max of a model of rigid blocks on elastic springs (contact
// points, trusses): eq. 1's omega_max "an upper bound to the highest eigenfrequency of the linear elastic system".
//
// The linearised system is M u'' + K u = 0 with six degrees of freedom per free block (translation, rotation in
// the world frame). omega_max^2 is the largest eigenvalue of A = M^-1/2 K M^-1/2, and the block Gershgorin theorem
// (Feingold and Varga 1962) bounds it by the largest row of blocks:
//
//     omega_max^2 <= max_i ( lambda_max(A_ii) + sum_j ||A_ij||_2 ),   A_ij = M_i^-1/2 K_ij M_j^-1/2 (6 x 6).
//
// A spring of stiffness D (3 x 3) between a point x_a of block a and x_b of block b stretches by
// d = B_b u_b - B_a u_a with B = [I, -[x - c]x] (the point's velocity v + w x r); it adds B_a^T D B_a to K_aa,
// B_b^T D B_b to K_bb and -B_a^T D B_b to K_ab. A fixed block's motion is prescribed: its springs count on the
// diagonal of the free one only. Degrees of freedom fixed by a block's fixity are left out (M_i^-1/2 restricted to
// the free ones). Unlike the per-block estimate max(k / m, k r^2 / I_min), which is exact for one block on fixed
// supports but not a bound for a chain of blocks (two blocks on one spring vibrate at sqrt(2 k / m)), this one holds
// for any assembly, so the timestep needs no margin for the assembly (on the rigid cross vault it lies 8 % above the
// highest eigenfrequency found by power iteration).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

namespace detail {

/// Eigenvalues (returned) and eigenvectors (columns of `vectors`) of a symmetric 6 x 6 matrix by cyclic Jacobi
/// rotations (Golub and Van Loan, Sect. 8.5): small, exact to rounding, free of the vectorised paths of a general
/// solver.
inline Eigen::Matrix<double, 6, 1> symmetric_eigen(Eigen::Matrix<double, 6, 6> a, Eigen::Matrix<double, 6, 6>* vectors = nullptr) {
  Eigen::Matrix<double, 6, 6> v = Eigen::Matrix<double, 6, 6>::Identity();
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0, scale = 0;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) (i == j ? scale : off) += a(i, j) * a(i, j);
    if (off <= 1e-30 * scale || off == 0) break;
    for (int p = 0; p < 5; ++p)
      for (int q = p + 1; q < 6; ++q) {
        if (a(p, q) == 0) continue;
        const double theta = (a(q, q) - a(p, p)) / (2 * a(p, q));
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 6; ++k) {  // a <- a J
          const double akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < 6; ++k) {  // a <- J^T a
          const double apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
        for (int k = 0; k < 6; ++k) {
          const double vkp = v(k, p), vkq = v(k, q);
          v(k, p) = c * vkp - s * vkq;
          v(k, q) = s * vkp + c * vkq;
        }
      }
  }
  if (vectors) *vectors = v;
  return a.diagonal();
}

}  // namespace detail

class FrequencyBound {
 public:
  using Mat6 = Eigen::Matrix<double, 6, 6>;

  /// For the blocks' present masses, inertias, orientations and fixities.
  explicit FrequencyBound(const model::RigidBodies& b)
      : bodies_(&b), scale_(b.size(), Mat6::Zero()), own_(b.size(), Mat6::Zero()), coupled_(b.size(), 0.0) {
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free) continue;
      Mat6 m = Mat6::Zero();
      m.topLeftCorner<3, 3>() = b.mass[i] * Mat3::Identity();
      m.bottomRightCorner<3, 3>() = b.rotation[i] * b.principal_inertia[i].asDiagonal() * b.rotation[i].transpose();
      for (int d = 0; d < 6; ++d)
        if (b.fixity[i] & (1u << d)) {  // a fixed degree of freedom: left out
          m.row(d).setZero();
          m.col(d).setZero();
          m(d, d) = 1.0;
        }
      Mat6 vectors;
      const Eigen::Matrix<double, 6, 1> values = detail::symmetric_eigen(m, &vectors);
      scale_[i] = vectors * values.cwiseInverse().cwiseSqrt().asDiagonal() * vectors.transpose();
      for (int d = 0; d < 6; ++d)
        if (b.fixity[i] & (1u << d)) {
          scale_[i].row(d).setZero();
          scale_[i].col(d).setZero();
        }
    }
  }

  /// One connection between blocks a and b (a contact's CPs, a truss): calls each(spring) where spring(x_a, x_b, D)
  /// adds a spring of stiffness D (N/m, world frame) between the world points x_a on a and x_b on b.
  template <class Each>
  void connect(std::size_t a, std::size_t b, Each&& each) {
    Mat6 k_ab = Mat6::Zero();
    each([&](const Vec3& x_a, const Vec3& x_b, const Mat3& d) {
      const Eigen::Matrix<double, 3, 6> ba = motion_of(a, x_a), bb = motion_of(b, x_b);
      const Eigen::Matrix<double, 6, 3> dba = ba.transpose() * d, dbb = bb.transpose() * d;
      own_[a] += dba * ba;
      own_[b] += dbb * bb;
      k_ab -= dba * bb;
    });
    const Mat6 a_ab = scale_[a] * k_ab * scale_[b];
    if (a_ab.isZero(0.0)) return;
    const double norm = std::sqrt(std::max(detail::symmetric_eigen(a_ab.transpose() * a_ab).maxCoeff(), 0.0));
    coupled_[a] += norm;
    coupled_[b] += norm;
  }

  /// A block's row of the bound, for its present mass: lambda_max(A_ii) and sum_j ||A_ij||_2 (rad^2/s^2). Scaling
  /// the block's mass and inertia by s divides the first by s and the second by sqrt(s) (partial density scaling).
  struct Row {
    double own = 0, coupled = 0;
    double omega_squared() const { return own + coupled; }
  };
  Row row(std::size_t i) const {
    if (bodies_->motion[i] != model::Motion::free) return {};
    const Mat6 a = scale_[i] * own_[i] * scale_[i];
    const double own = detail::symmetric_eigen(a).maxCoeff();
    return {std::max(own, 0.0), coupled_[i]};
  }

  /// The bound on omega_max (rad/s); 0 if no free block has a spring.
  double omega_max() const {
    double largest = 0;
    for (std::size_t i = 0; i < scale_.size(); ++i) largest = std::max(largest, row(i).omega_squared());
    return std::sqrt(largest);
  }

 private:
  /// B: the velocity of the world point x of block i from its six velocities, v + w x (x - c).
  Eigen::Matrix<double, 3, 6> motion_of(std::size_t i, const Vec3& x) const {
    const Vec3 r = x - bodies_->position[i];
    Eigen::Matrix<double, 3, 6> m;
    m.leftCols<3>() = Mat3::Identity();
    m.rightCols<3>() << 0, r.z(), -r.y(), -r.z(), 0, r.x(), r.y(), -r.x(), 0;
    return m;
  }

  const model::RigidBodies* bodies_;
  std::vector<Mat6> scale_;  // M_i^-1/2 on the free degrees of freedom, 0 for fixed blocks
  std::vector<Mat6> own_;    // K_ii
  std::vector<double> coupled_;
};

}  // namespace blockdem
