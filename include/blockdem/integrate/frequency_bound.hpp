#pragma once
// An upper bound on the highest eigenfrequency omega_max of a model of rigid blocks, nodes of deformable blocks and
// the elastic springs between them (contact points, trusses, constant-strain tetrahedra): eq. 1's omega_max "an
// upper bound to the highest eigenfrequency of the linear elastic system".
//
// The linearised system is M u'' + K u = 0 with six degrees of freedom per free rigid block (translation, rotation
// in the world frame) and three per node. omega_max^2 is the largest eigenvalue of A = M^-1/2 K M^-1/2, and the
// block Gershgorin theorem (Feingold and Varga 1962) bounds it by the largest row of blocks:
//
//     omega_max^2 <= max_i ( lambda_max(A_ii) + sum_j ||A_ij||_2 ),   A_ij = M_i^-1/2 K_ij M_j^-1/2.
//
// A spring of stiffness D (3 x 3) stretches by d = sum_p c_p B_p u_p over the points it joins (c_p = -w_p on its
// first side and +w_p on its second, w the weights of a point inside a triangle of nodes), B = [I, -[x - c]x] for a
// world point x of a block (its velocity v + w x r) and B = I for a node; it adds c_p c_q B_p^T D B_q to K_pq. A
// tetrahedron adds V (lambda g_i g_j^T + G g_j g_i^T + G (g_i . g_j) I) to K_ij (g the gradients of its shape
// functions). A fixed block's motion is prescribed: its springs count on the diagonal of the free side only, and
// fixed degrees of freedom are left out (M_i^-1/2 restricted to the free ones). Summing ||A_ij|| per spring or per
// element instead of per pair only raises the bound. Unlike the per-block and per-node estimate of eq. 1-3, exact
// for one block or node on fixed supports but not a bound for a chain of them (two blocks on one spring vibrate at
// sqrt(2 k / m)), this holds for any assembly, so the timestep needs no margin for the assembly (on the rigid cross
// vault as built it lies 10.3 % above the highest eigenfrequency found by power iteration: tests/models/
// test_cross_vault.cpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

namespace detail {

/// Eigenvalues (returned) and eigenvectors (columns of `vectors`) of a symmetric N x N matrix by cyclic Jacobi
/// rotations (Golub and Van Loan, Sect. 8.5): small, exact to rounding, free of the vectorised paths of a general
/// solver.
template <int N>
Eigen::Matrix<double, N, 1> symmetric_eigen(Eigen::Matrix<double, N, N> a, Eigen::Matrix<double, N, N>* vectors = nullptr) {
  Eigen::Matrix<double, N, N> v = Eigen::Matrix<double, N, N>::Identity();
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0, scale = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) (i == j ? scale : off) += a(i, j) * a(i, j);
    if (off <= 1e-30 * scale || off == 0) break;
    for (int p = 0; p < N - 1; ++p)
      for (int q = p + 1; q < N; ++q) {
        if (a(p, q) == 0) continue;
        const double theta = (a(q, q) - a(p, p)) / (2 * a(p, q));
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < N; ++k) {  // a <- a J
          const double akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < N; ++k) {  // a <- J^T a
          const double apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
        for (int k = 0; k < N; ++k) {
          const double vkp = v(k, p), vkq = v(k, q);
          v(k, p) = c * vkp - s * vkq;
          v(k, q) = s * vkp + c * vkq;
        }
      }
  }
  if (vectors) *vectors = v;
  return a.diagonal();
}

/// The spectral norm ||a||_2 of a small matrix: the root of the largest eigenvalue of its smaller Gram matrix.
template <int R, int C>
double spectral_norm(const Eigen::Matrix<double, R, C>& a) {
  if constexpr (R <= C) {
    const Eigen::Matrix<double, R, R> gram = a * a.transpose();
    return std::sqrt(std::max(symmetric_eigen<R>(gram).maxCoeff(), 0.0));
  } else {
    const Eigen::Matrix<double, C, C> gram = a.transpose() * a;
    return std::sqrt(std::max(symmetric_eigen<C>(gram).maxCoeff(), 0.0));
  }
}

}  // namespace detail

class FrequencyBound {
 public:
  using Mat6 = Eigen::Matrix<double, 6, 6>;

  /// One end point of a spring: a world point x of rigid block `index`, or node `index`, with weight w.
  struct Point {
    bool node = false;
    std::size_t index = 0;
    double weight = 1.0;
    Vec3 x = Vec3::Zero();
  };
  static Point block_point(std::size_t block, const Vec3& x) { return {false, block, 1.0, x}; }
  static Point node_point(std::size_t node, double weight = 1.0) { return {true, node, weight, Vec3::Zero()}; }

  /// For the present masses, inertias, orientations and fixities of the free rigid blocks and of the nodes.
  explicit FrequencyBound(const model::Model& m)
      : bodies_(&m.bodies),
        scale_(m.bodies.size(), Mat6::Zero()),
        own_(m.bodies.size(), Mat6::Zero()),
        coupled_(m.bodies.size(), 0.0),
        node_scale_(m.deformable.nodes.size(), Vec3::Zero()),
        node_own_(m.deformable.nodes.size(), Mat3::Zero()),
        node_coupled_(m.deformable.nodes.size(), 0.0) {
    const auto& b = m.bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.motion[i] != model::Motion::free || m.deformable.is_deformable(i)) continue;
      Mat6 mass = Mat6::Zero();
      mass.topLeftCorner<3, 3>() = b.mass[i] * Mat3::Identity();
      mass.bottomRightCorner<3, 3>() = b.rotation[i] * b.principal_inertia[i].asDiagonal() * b.rotation[i].transpose();
      for (int d = 0; d < 6; ++d)
        if (b.fixity[i] & (1u << d)) {  // a fixed degree of freedom: left out
          mass.row(d).setZero();
          mass.col(d).setZero();
          mass(d, d) = 1.0;
        }
      Mat6 vectors;
      const Eigen::Matrix<double, 6, 1> values = detail::symmetric_eigen<6>(mass, &vectors);
      scale_[i] = vectors * values.cwiseInverse().cwiseSqrt().asDiagonal() * vectors.transpose();
      for (int d = 0; d < 6; ++d)
        if (b.fixity[i] & (1u << d)) {
          scale_[i].row(d).setZero();
          scale_[i].col(d).setZero();
        }
    }
    const auto& nd = m.deformable.nodes;
    for (std::size_t n = 0; n < nd.size(); ++n)
      for (int d = 0; d < 3; ++d)
        if (!(nd.fixity[n] & (1u << d))) node_scale_[n][d] = 1.0 / std::sqrt(nd.mass[n]);
  }

  /// One connection between rigid blocks a and b (a contact's CPs): calls each(spring) where spring(x_a, x_b, D)
  /// adds a spring of stiffness D (N/m, world frame) between the world points x_a on a and x_b on b. The
  /// connection's springs make one K_ab (a tighter bound than one per spring).
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
    const double norm = detail::spectral_norm<6, 6>(a_ab);
    coupled_[a] += norm;
    coupled_[b] += norm;
  }

  /// A spring of stiffness D (N/m, world frame) from the weighted sum of the points `from` to that of `to` (a truss
  /// between blocks or nodes, a node's contact point on a block or inside a triangle of nodes).
  void spring(std::initializer_list<Point> from, std::initializer_list<Point> to, const Mat3& d) {
    std::array<Point, 8> p{};
    std::array<double, 8> c{};
    std::size_t count = 0;
    for (const auto& x : from) p[count] = x, c[count++] = -x.weight;
    for (const auto& x : to) p[count] = x, c[count++] = x.weight;
    double d_norm = -1;  // ||D||_2, once per spring for the pairs of nodes free on all axes
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t j = i; j < count; ++j) {
        const double cc = c[i] * c[j];
        if (i == j || same(p[i], p[j])) {
          add_own(p[i], p[j], (i == j ? 1.0 : 2.0) * cc, d);
          continue;
        }
        double coupling;
        if (p[i].node && p[j].node && isotropic(node_scale_[p[i].index]) && isotropic(node_scale_[p[j].index])) {
          if (d_norm < 0) d_norm = detail::spectral_norm<3, 3>(d);
          coupling = node_scale_[p[i].index][0] * node_scale_[p[j].index][0] * d_norm;
        } else {
          coupling = coupling_norm(p[i], p[j], d);
        }
        const double norm = std::abs(cc) * coupling;
        (p[i].node ? node_coupled_ : coupled_)[p[i].index] += norm;
        (p[j].node ? node_coupled_ : coupled_)[p[j].index] += norm;
      }
  }

  /// The stiffness block K_ij (N/m) of a constant-strain tetrahedron between its nodes i and j, from its
  /// shape-function gradients g (1/m), volume (m^3), bulk and shear moduli (Pa): K_ij = V (lambda g_i g_j^T +
  /// G g_j g_i^T + G (g_i . g_j) I), lambda = K - 2 G / 3.
  static Mat3 tetrahedron_block(const std::array<Vec3, 4>& g, double volume, double bulk, double shear, std::size_t i,
                                std::size_t j) {
    const double lambda = bulk - 2.0 * shear / 3.0;
    return volume * (lambda * g[i] * g[j].transpose() + shear * g[j] * g[i].transpose() + shear * g[i].dot(g[j]) * Mat3::Identity());
  }

  /// The node pairs (i, j), i < j, of a tetrahedron in the order of tetrahedron_pair_norms().
  static constexpr std::array<std::array<std::size_t, 2>, 6> tetrahedron_pairs{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

  /// ||K_ij||_2 (N/m) of a tetrahedron's six node pairs (tetrahedron_pairs): fixed by its shape and material, so a
  /// model keeps them and the bound does not solve their eigenproblems again each time it is formed.
  static std::array<double, 6> tetrahedron_pair_norms(const std::array<Vec3, 4>& g, double volume, double bulk, double shear) {
    std::array<double, 6> norms{};
    for (std::size_t p = 0; p < 6; ++p)
      norms[p] = detail::spectral_norm<3, 3>(tetrahedron_block(g, volume, bulk, shear, tetrahedron_pairs[p][0], tetrahedron_pairs[p][1]));
    return norms;
  }

  /// A constant-strain tetrahedron on `nodes` (see tetrahedron_block).
  void tetrahedron(const std::array<std::uint32_t, 4>& nodes, const std::array<Vec3, 4>& g, double volume, double bulk,
                   double shear) {
    tetrahedron(nodes, g, volume, bulk, shear, nullptr);
  }
  /// The same with its tetrahedron_pair_norms(): a pair of nodes free on all three axes (or fixed on all three)
  /// scales its block by one number per node, ||s_i K_ij s_j|| = s_i s_j ||K_ij||, and only a pair with a node
  /// fixed on some axes solves its eigenproblem here.
  void tetrahedron(const std::array<std::uint32_t, 4>& nodes, const std::array<Vec3, 4>& g, double volume, double bulk,
                   double shear, const std::array<double, 6>* pair_norms) {
    for (std::size_t i = 0; i < 4; ++i) node_own_[nodes[i]] += tetrahedron_block(g, volume, bulk, shear, i, i);
    for (std::size_t p = 0; p < 6; ++p) {
      const std::size_t i = tetrahedron_pairs[p][0], j = tetrahedron_pairs[p][1];
      const Vec3 &si = node_scale_[nodes[i]], &sj = node_scale_[nodes[j]];
      const double norm = pair_norms && isotropic(si) && isotropic(sj)
                              ? si[0] * sj[0] * (*pair_norms)[p]
                              : detail::spectral_norm<3, 3>(Mat3(si.asDiagonal() * tetrahedron_block(g, volume, bulk, shear, i, j) * sj.asDiagonal()));
      node_coupled_[nodes[i]] += norm;
      node_coupled_[nodes[j]] += norm;
    }
  }

  /// A block's or a node's row of the bound, for its present mass: lambda_max(A_ii) and sum_j ||A_ij||_2
  /// (rad^2/s^2). Scaling its mass (and a block's inertia) by s divides the first by s and the second by sqrt(s)
  /// (partial density scaling).
  struct Row {
    double own = 0, coupled = 0;
    double omega_squared() const { return own + coupled; }
  };
  Row row(std::size_t i) const {
    if (scale_[i].isZero(0.0)) return {};
    const Mat6 a = scale_[i] * own_[i] * scale_[i];
    return {std::max(detail::symmetric_eigen<6>(a).maxCoeff(), 0.0), coupled_[i]};
  }
  Row node_row(std::size_t n) const {
    const Vec3& s = node_scale_[n];
    const Mat3 a = s.asDiagonal() * node_own_[n] * s.asDiagonal();
    return {std::max(detail::symmetric_eigen<3>(a).maxCoeff(), 0.0), node_coupled_[n]};
  }

  /// The bound on omega_max (rad/s); 0 if nothing free has a spring.
  double omega_max() const {
    double largest = 0;
    for (std::size_t i = 0; i < scale_.size(); ++i) largest = std::max(largest, row(i).omega_squared());
    for (std::size_t n = 0; n < node_scale_.size(); ++n) largest = std::max(largest, node_row(n).omega_squared());
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
  static bool same(const Point& a, const Point& b) { return a.node == b.node && a.index == b.index; }
  static bool isotropic(const Vec3& s) { return s[0] == s[1] && s[1] == s[2]; }

  /// Adds c (B_a^T D B_b + B_b^T D B_a) / 2 to the diagonal block of the point's block or node (a and b on it).
  void add_own(const Point& a, const Point& b, double c, const Mat3& d) {
    if (a.node) {
      node_own_[a.index] += c * d;
      return;
    }
    const Eigen::Matrix<double, 3, 6> ba = motion_of(a.index, a.x), bb = motion_of(b.index, b.x);
    const Mat6 k = ba.transpose() * d * bb;
    own_[a.index] += 0.5 * c * (k + k.transpose());
  }

  /// ||M_a^-1/2 B_a^T D B_b M_b^-1/2||_2.
  double coupling_norm(const Point& a, const Point& b, const Mat3& d) const {
    if (a.node && b.node) return detail::spectral_norm<3, 3>(Mat3(node_scale_[a.index].asDiagonal() * d * node_scale_[b.index].asDiagonal()));
    if (a.node) return coupling_norm(b, a, d);
    const Eigen::Matrix<double, 3, 6> sa = motion_of(a.index, a.x) * scale_[a.index];
    if (b.node) return detail::spectral_norm<6, 3>(Eigen::Matrix<double, 6, 3>(sa.transpose() * d * node_scale_[b.index].asDiagonal()));
    const Eigen::Matrix<double, 3, 6> sb = motion_of(b.index, b.x) * scale_[b.index];
    return detail::spectral_norm<6, 6>(Mat6(sa.transpose() * d * sb));
  }

  const model::RigidBodies* bodies_;
  std::vector<Mat6> scale_;  // M_i^-1/2 on the free degrees of freedom, 0 for fixed and deformable blocks
  std::vector<Mat6> own_;    // K_ii
  std::vector<double> coupled_;
  std::vector<Vec3> node_scale_;  // 1 / sqrt(m) on the free axes, 0 on the fixed ones
  std::vector<Mat3> node_own_;
  std::vector<double> node_coupled_;
};

}  // namespace blockdem
