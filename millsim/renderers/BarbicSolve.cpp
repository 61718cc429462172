#include "millsim/renderers/BarbicSolve.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <glm/geometric.hpp>

namespace millsim {

namespace {

Eigen::Matrix3d toEigen(const glm::dmat3& m) {
  Eigen::Matrix3d e;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) e(r, c) = m[c][r];  // glm is column-major: m[column][row]
  return e;
}
Eigen::Vector3d toEigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace

void addContact(Wrench6& acc, const glm::dvec3& rg, double d, const glm::dvec3& ng, const glm::dmat3& Hg, double k) {
  const Eigen::Vector3d r = toEigen(rg), n = toEigen(ng);
  const Eigen::Matrix3d H = toEigen(Hg), R = skew(r), N = skew(n);
  const Eigen::Vector3d F = k * d * n, rn = r.cross(n);
  acc.w.head<3>() += F;
  acc.w.tail<3>() += r.cross(F);
  // K = −∂(F, τ)/∂(x, θ); see docs/algorithms.md for the derivation.
  const Eigen::Matrix3d Kxx = k * (n * n.transpose() + d * H);
  const Eigen::Matrix3d Kxt = k * (n * rn.transpose() + d * (N - H * R));
  acc.K.block<3, 3>(0, 0) += Kxx;
  acc.K.block<3, 3>(0, 3) += Kxt;
  acc.K.block<3, 3>(3, 0) += R * Kxx - skew(F);
  acc.K.block<3, 3>(3, 3) += R * Kxt;
  // Gauss–Newton part k·J·Jᵀ with J = ∂d/∂(x, θ) = −(n, r × n), its lower
  // triangle only (what solveStep reads), by hand: Eigen's rankUpdate was a
  // tenth of a contact's cost at pointShellScale 1.
  const double J[6] = {n.x(), n.y(), n.z(), rn.x(), rn.y(), rn.z()};
  for (int c = 0; c < 6; ++c) {
    const double kj = k * J[c];
    for (int r6 = c; r6 < 6; ++r6) acc.Kgn(r6, c) += kj * J[r6];
  }
}

void addRotated(Wrench6& acc, const Wrench6& t, const glm::dmat3& Rg) {
  const Eigen::Matrix3d R = toEigen(Rg), Rt = R.transpose();
  acc.w.head<3>() += R * t.w.head<3>();
  acc.w.tail<3>() += R * t.w.tail<3>();
  const Mat6 gn = t.Kgn.selfadjointView<Eigen::Lower>();  // only its lower triangle is kept
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      acc.K.block<3, 3>(3 * r, 3 * c) += R * t.K.block<3, 3>(3 * r, 3 * c) * Rt;
      if (c <= r) {
        const Eigen::Matrix3d b = R * gn.block<3, 3>(3 * r, 3 * c) * Rt;
        for (int j = 0; j < 3; ++j)
          for (int i = (r == c ? j : 0); i < 3; ++i) acc.Kgn(3 * r + i, 3 * c + j) += b(i, j);
      }
    }
}

glm::dvec3 rotationError(const glm::dquat& tool, const glm::dquat& device) {
  glm::dquat e = device * glm::inverse(tool);
  if (e.w < 0.0) e = -e;  // the short way round
  const glm::dvec3 v(e.x, e.y, e.z);
  const double s = glm::length(v);
  if (s < 1e-12) return 2.0 * v;  // small-angle limit
  return v * (2.0 * std::atan2(s, e.w) / s);
}

Pose applyStep(const Pose& p, const Vec6& step) {
  Pose out = p;
  out.position += glm::dvec3(step(0), step(1), step(2));
  const glm::dvec3 th(step(3), step(4), step(5));
  const double a = glm::length(th);
  if (a > 0.0) out.orientation = glm::normalize(glm::angleAxis(a, th / a) * p.orientation);
  return out;
}

void addCouplingSpring(Wrench6& acc, const Coupling& c, const Pose& tool, const Pose& device) {
  acc.w.head<3>() += c.k * toEigen(device.position - tool.position);
  acc.w.tail<3>() += c.kr * toEigen(rotationError(tool.orientation, device.orientation));
  for (int i = 0; i < 3; ++i) {
    acc.K(i, i) += c.k, acc.K(i + 3, i + 3) += c.kr;
    acc.Kgn(i, i) += c.k, acc.Kgn(i + 3, i + 3) += c.kr;
  }
}

SolveResult solveStep(const Wrench6& total, const Coupling& c, const Vec6& deviceVelocity, double dt) {
  // Fixed-size 6×6 LDLT (Eigen): no allocation, ~1 µs, and it reports whether
  // the matrix is positive definite — hand-written code would gain nothing.
  Vec6 D;
  D << c.b, c.b, c.b, c.br, c.br, c.br;
  const Vec6 rhs = total.w + D.cwiseProduct(deviceVelocity);
  const Vec6 damping = D / dt;
  SolveResult res;
  Mat6 A = 0.5 * (total.K + total.K.transpose());
  A.diagonal() += damping;
  Eigen::LDLT<Mat6> ldlt(A);
  if (ldlt.info() == Eigen::Success && ldlt.isPositive() && ldlt.vectorD().minCoeff() > 0.0) {
    res.step = ldlt.solve(rhs);
    if (res.step.allFinite()) return res;
  }
  // The curvature and torque-arm terms can make K indefinite deep in contact;
  // the Gauss–Newton part plus the coupling is positive definite by construction.
  res.dropped = true;
  A = total.Kgn.selfadjointView<Eigen::Lower>();
  A.diagonal() += damping;
  Eigen::LLT<Mat6> llt(A);
  res.step = llt.info() == Eigen::Success ? Vec6(llt.solve(rhs)) : Vec6::Zero();
  if (!res.step.allFinite()) res.step.setZero();
  return res;
}

}  // namespace millsim
