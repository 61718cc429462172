#include "measure/PhysicalReference.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace millsim::measure {

namespace {

using Fn = std::function<double(const glm::dvec3&)>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

glm::dvec3 gradient(const Fn& f, const glm::dvec3& p) {
  const double e = 1e-8;
  const glm::dvec3 g(f(p + glm::dvec3(e, 0, 0)) - f(p - glm::dvec3(e, 0, 0)),
                     f(p + glm::dvec3(0, e, 0)) - f(p - glm::dvec3(0, e, 0)),
                     f(p + glm::dvec3(0, 0, e)) - f(p - glm::dvec3(0, 0, e)));
  const double n = glm::length(g);
  return n > 0.0 ? g / n : glm::dvec3(0.0, 1.0, 0.0);
}

glm::dquat expMap(const glm::dvec3& phi) {
  const double a = glm::length(phi);
  return a < 1e-300 ? glm::dquat(1.0, 0.0, 0.0, 0.0) : glm::angleAxis(a, phi / a);
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return k;
}

// exp(φ + δ) ≈ exp(J_l(φ)·δ)·exp(φ): the left Jacobian of SO(3).
Eigen::Matrix3d leftJacobian(const glm::dvec3& phi) {
  const double a = glm::length(phi);
  const Eigen::Matrix3d k = skew({phi.x, phi.y, phi.z});
  if (a < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * k + k * k / 6.0;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(a)) / (a * a) * k + (a - std::sin(a)) / (a * a * a) * k * k;
}

// One linearised constraint g + aᵀ(v' − v) ≥ 0 in the scaled variables v = (Δx, s·φ).
struct Constraint {
  double g = 0.0;
  Vec6 a = Vec6::Zero();
  glm::dvec3 centre{0.0}, normal{0.0};  // the tool sphere's centre (burr centre or shaft axis point), material normal
  double radius = 0.0;
  double t = 0.0;  // where along the shaft axis (0: the burr centre)
  bool shaft = false;
  int piece = 0;
};

struct Frame {
  glm::dvec3 x{0.0}, phi{0.0};
  glm::dquat R{1.0, 0.0, 0.0, 0.0};
};

Frame frameOf(const Vec6& v, const Pose& device, double s, bool rotate) {
  Frame fr;
  fr.x = device.position + glm::dvec3(v(0), v(1), v(2));
  fr.phi = rotate ? glm::dvec3(v(3), v(4), v(5)) / s : glm::dvec3(0.0);
  fr.R = glm::normalize(expMap(fr.phi) * device.orientation);
  return fr;
}

// Minimum of f on [lo, hi] by golden-section search (f is unimodal near a sampled local minimum).
double refineMinimum(const std::function<double(double)>& f, double lo, double hi) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  for (int i = 0; i < 80 && b - a > 1e-13; ++i) {
    if (fc < fd) b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    else a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
  }
  return 0.5 * (a + b);
}

// Every tool sphere that is a local minimum of clearance per piece, the burr and
// the shaft axis's local minima (plus its ends), within `margin` of contact.
std::vector<Constraint> gather(const Material& m, const ToolGeometry& tool, const Frame& fr, double s, bool rotate,
                               const ReferenceTolerance& tol, double margin, double* deepest) {
  std::vector<Constraint> out;
  const glm::dvec3 dir = fr.R * glm::dvec3(0.0, 1.0, 0.0);
  const Eigen::Matrix3d jlT = leftJacobian(fr.phi).transpose();
  auto add = [&](int piece, double t, double radius, bool shaft) {
    const glm::dvec3 c = fr.x + dir * t;
    const Fn& f = m.pieces[std::size_t(piece)];
    Constraint k;
    k.g = f(c) - radius;
    if (deepest) *deepest = std::min(*deepest, k.g);
    if (k.g >= margin) return;
    k.centre = c, k.radius = radius, k.t = t, k.shaft = shaft, k.piece = piece;
    k.normal = gradient(f, c);
    k.a.head<3>() << k.normal.x, k.normal.y, k.normal.z;
    if (rotate) {
      const glm::dvec3 m3 = glm::cross(c - fr.x, k.normal);
      k.a.tail<3>() = jlT * Eigen::Vector3d(m3.x, m3.y, m3.z) / s;
    }
    out.push_back(k);
  };
  const int n = std::max(2, tol.shaftSamples);
  std::vector<double> v(std::size_t(n) + 1);
  for (std::size_t i = 0; i < m.pieces.size(); ++i) {
    const Fn& f = m.pieces[i];
    add(int(i), 0.0, tool.tipRadius, false);
    for (int j = 0; j <= n; ++j) {
      v[std::size_t(j)] = f(fr.x + dir * (tool.shaftLength * j / n));
      if (deepest) *deepest = std::min(*deepest, v[std::size_t(j)] - tool.shaftRadius);
    }
    for (int j = 0; j <= n; ++j) {
      const double here = v[std::size_t(j)];
      const bool left = j == 0 || here <= v[std::size_t(j - 1)], right = j == n || here < v[std::size_t(j + 1)];
      if (!(left && right) && j != 0 && j != n) continue;
      if (here - tool.shaftRadius >= margin) continue;
      double t = tool.shaftLength * j / n;
      if (left && right && j != 0 && j != n)
        t = refineMinimum([&](double u) { return f(fr.x + dir * u); }, tool.shaftLength * (j - 1) / n,
                          tool.shaftLength * (j + 1) / n);
      add(int(i), t, tool.shaftRadius, true);
    }
  }
  return out;
}

// The clearance of one constraint's tool sphere at the scaled pose w: the burr, or
// the shaft's local minimum near the constraint's axis position (re-found at w).
double clearanceAt(const Material& m, const ToolGeometry& tool, const Constraint& c, const Vec6& w,
                   const Pose& device, double s, bool rotate, const ReferenceTolerance& tol) {
  const Frame fr = frameOf(w, device, s, rotate);
  const Fn& f = m.pieces[std::size_t(c.piece)];
  if (!c.shaft) return f(fr.x) - c.radius;
  const glm::dvec3 dir = fr.R * glm::dvec3(0.0, 1.0, 0.0);
  const double half = 2.0 * tool.shaftLength / std::max(2, tol.shaftSamples);
  const double t = refineMinimum([&](double u) { return f(fr.x + dir * u); }, std::max(0.0, c.t - half),
                                 std::min(tool.shaftLength, c.t + half));
  return f(fr.x + dir * t) - c.radius;
}

// The Hessian of that clearance in the scaled variables, by central differences.
Eigen::Matrix<double, 6, 6> clearanceHessian(const Material& m, const ToolGeometry& tool, const Constraint& c,
                                             const Vec6& v, const Pose& device, double s, bool rotate,
                                             const ReferenceTolerance& tol) {
  const double e = 1e-6;  // m: well below the curvature radii (≥ 0.1 mm), well above round-off
  const int n = rotate ? 6 : 3;
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  auto g = [&](int i, double di, int j, double dj) {
    Vec6 w = v;
    w(i) += di, w(j) += dj;
    return clearanceAt(m, tool, c, w, device, s, rotate, tol);
  };
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) {
      H(i, j) = (g(i, e, j, e) - g(i, e, j, -e) - g(i, -e, j, e) + g(i, -e, j, -e)) / (4.0 * e * e);
      H(j, i) = H(i, j);
    }
  return H;
}

// min ½|w|² subject to Aw ≥ b through its dual: min ½λᵀQλ − bᵀλ, λ ≥ 0, Q = AAᵀ
// (Lawson–Hanson active set; Q must be positive definite); w = Aᵀλ.
Eigen::VectorXd solveDual(const Eigen::MatrixXd& Q, const Eigen::VectorXd& b) {
  const int m = int(b.size());
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
  std::vector<bool> free(std::size_t(m), false);
  for (int outer = 0; outer < 10 * m + 10; ++outer) {
    const Eigen::VectorXd w = b - Q * lambda;
    int best = -1;
    for (int j = 0; j < m; ++j)
      if (!free[std::size_t(j)] && w(j) > 1e-16 && (best < 0 || w(j) > w(best))) best = j;
    if (best < 0) break;
    free[std::size_t(best)] = true;
    for (int inner = 0; inner < 10 * m + 10; ++inner) {
      std::vector<int> idx;
      for (int j = 0; j < m; ++j)
        if (free[std::size_t(j)]) idx.push_back(j);
      Eigen::MatrixXd qpp(idx.size(), idx.size());
      Eigen::VectorXd bp(idx.size());
      for (std::size_t r = 0; r < idx.size(); ++r) {
        bp(Eigen::Index(r)) = b(idx[r]);
        for (std::size_t c = 0; c < idx.size(); ++c) qpp(Eigen::Index(r), Eigen::Index(c)) = Q(idx[r], idx[c]);
      }
      const Eigen::VectorXd zp = qpp.completeOrthogonalDecomposition().solve(bp);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(m);
      bool positive = true;
      for (std::size_t r = 0; r < idx.size(); ++r) {
        z(idx[r]) = zp(Eigen::Index(r));
        if (zp(Eigen::Index(r)) <= 0.0) positive = false;
      }
      if (positive) {
        lambda = z;
        break;
      }
      double alpha = 1.0;
      for (int j : idx)
        if (z(j) <= 0.0) alpha = std::min(alpha, lambda(j) / (lambda(j) - z(j)));
      lambda += alpha * (z - lambda);
      for (int j : idx)
        if (lambda(j) <= 1e-300) free[std::size_t(j)] = false, lambda(j) = 0.0;
    }
  }
  return lambda;
}

}  // namespace

double Material::distance(const glm::dvec3& p) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& f : pieces) d = std::min(d, f(p));
  return d;
}

glm::dvec3 rotationVector(const glm::dquat& q0) {
  glm::dquat q = q0;
  if (q.w < 0.0) q = -q;
  const glm::dvec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (s < 1e-12) return 2.0 * v;
  return v * (2.0 * std::atan2(s, q.w) / s);
}

PhysicalPose constrainedPose(const Material& material, const ToolGeometry& tool, const Pose& device,
                             const CouplingMetric& metric, const ReferenceTolerance& tol) {
  const bool rotate = std::isfinite(metric.kr);
  const double s = rotate ? std::sqrt(metric.kr / metric.k) : 1.0;  // m: the metric's length scale
  // Constraints further than this from contact stay out of the QP (an iteration whose
  // step brings one closer takes it in next time; the line search sees every one).
  const double margin = 0.5 * tool.tipRadius + 1e-4;
  int iterations = 0;  // of the last run
  Vec6 v = Vec6::Zero();
  Eigen::VectorXd lambda;
  std::vector<Constraint> cons, active;
  std::vector<double> activeLambda;
  bool stepConverged = false;
  auto violationAt = [&](const Vec6& w) {
    double deepest = std::numeric_limits<double>::infinity();
    gather(material, tool, frameOf(w, device, s, rotate), s, rotate, tol, 1.0, &deepest);
    return std::max(0.0, -deepest);
  };
  // One SQP run from `start` (the local minimum it reaches).
  auto solveFrom = [&](const Vec6& start) {
    v = start, active.clear(), activeLambda.clear(), stepConverged = false;
    for (int it = 0; it < tol.maxIterations; ++it) {
      iterations = it + 1;
      cons = gather(material, tool, frameOf(v, device, s, rotate), s, rotate, tol, margin, nullptr);
      const int m = int(cons.size());
      Eigen::MatrixXd A(m, 6);
      Eigen::VectorXd b(m);
      for (int j = 0; j < m; ++j) A.row(j) = cons[std::size_t(j)].a.transpose();
      // The QP's Hessian: the Lagrangian's, I − Σλ∇²g with the last multipliers (the surfaces'
      // curvature; without it a tool wedged against curved walls overshoots), kept positive definite.
      Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Identity();
      for (std::size_t j = 0; j < active.size(); ++j)
        H -= activeLambda[j] * clearanceHessian(material, tool, active[j], v, device, s, rotate, tol);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(H);
      const Eigen::Matrix<double, 6, 6> Hpd =
          eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.05).asDiagonal() * eig.eigenvectors().transpose();
      const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(Hpd);
      const Eigen::Matrix<double, 6, 6> L = llt.matrixL();
      // With e = Lᵀd and w = e + L⁻¹v the QP min vᵀd + ½dᵀHd, g + Ad ≥ 0 is the projection
      // min ½|w|², Ãw ≥ b̃ with Ã = AL⁻ᵀ, b̃ = ÃL⁻¹v − g.
      const Vec6 linv_v = L.triangularView<Eigen::Lower>().solve(v);
      Eigen::MatrixXd At(m, 6);
      for (int j = 0; j < m; ++j) {
        At.row(j) = L.triangularView<Eigen::Lower>().solve(Vec6(A.row(j).transpose())).transpose();
        b(j) = At.row(j).dot(linv_v) - cons[std::size_t(j)].g;
      }
      // A tiny ridge keeps the dual strictly convex when more contacts than degrees of freedom
      // are active (a tool wedged in a hole); it lets each constraint miss by 1e-12·λ (≈1e-15 m).
      const Eigen::MatrixXd Q = At * At.transpose() + 1e-12 * Eigen::MatrixXd::Identity(m, m);
      lambda = m > 0 ? solveDual(Q, b) : Eigen::VectorXd();
      const Vec6 wq = m > 0 ? Vec6(At.transpose() * lambda) : Vec6::Zero();
      const Vec6 next = v + Vec6(L.transpose().triangularView<Eigen::Upper>().solve(Vec6(wq - linv_v)));
      active.clear(), activeLambda.clear();
      for (int j = 0; j < m; ++j)
        if (lambda(j) > 0.0) active.push_back(cons[std::size_t(j)]), activeLambda.push_back(lambda(j));
      // Backtrack on the exact-penalty merit ½|v|² + μ·(deepest penetration), μ above the
      // multipliers' sum: a safeguard where the clamped Hessian still misjudges the
      // curvature (a convex rim) or a constraint outside the margin comes into play.
      const double mu = 2.0 * (m > 0 ? lambda.sum() : 0.0) + 1e-12;
      auto merit = [&](const Vec6& w) { return 0.5 * w.squaredNorm() + mu * violationAt(w); };
      const double m0 = merit(v);
      Vec6 trial = next;
      for (double alpha = 1.0; alpha > 1e-6; alpha *= 0.5) {
        trial = v + alpha * (next - v);
        if (merit(trial) <= m0 + 1e-20) break;
      }
      const double step = (trial - v).norm();
      v = trial;
      if (step < tol.step) {
        stepConverged = true;
        break;
      }
    }
  };
  struct Run {
    Vec6 v;
    Eigen::VectorXd lambda;
    std::vector<Constraint> cons;
    bool stepConverged;
    int iterations;
  };
  auto keep = [&] { return Run{v, lambda, cons, stepConverged, iterations}; };
  solveFrom(Vec6::Zero());
  std::vector<Run> runs{keep()};
  // A start on a symmetry plane can end on a saddle of the coupling energy: a
  // burr pressed past a convex edge along its bisector is held on the bisector
  // (|Δx| = r + √2·a for a depth a along each face), though sliding onto either
  // face costs less (r + a). So from a pose in contact the solve starts again
  // a little off it along each axis, and the feasible result of least energy
  // ½|v|² is the reference; others as near (the other face) are its alternatives.
  if (!active.empty()) {
    const Vec6 first = v;
    const double delta = 0.25 * std::max(first.norm(), 1e-5);
    for (int axis = 0; axis < 3; ++axis)  // the translation: where the saddles are
      for (const double sign : {1.0, -1.0}) {
        Vec6 start = first;
        start(axis) += sign * delta;
        solveFrom(start);
        if (stepConverged && violationAt(v) <= tol.violation) runs.push_back(keep());
      }
  }
  std::size_t best = 0;
  for (std::size_t r = 1; r < runs.size(); ++r)
    if (runs[r].v.squaredNorm() < runs[best].v.squaredNorm() * (1.0 - 1e-9)) best = r;
  auto report = [&](const Run& run) {
    PhysicalPose out;
    out.iterations = run.iterations;
    out.violation = violationAt(run.v);

    const Frame fr = frameOf(run.v, device, s, rotate);
    out.pose = Pose{fr.x, fr.R};
    out.force = metric.k * (fr.x - device.position);
    glm::dvec3 sumF(0.0), sumT(0.0);
    for (std::size_t j = 0; j < run.cons.size(); ++j) {
      const double mu = metric.k * run.lambda(Eigen::Index(j));
      if (!(mu > 0.0)) continue;
      const Constraint& c = run.cons[j];
      ReferenceContact rc;
      rc.normal = c.normal;
      rc.point = c.centre - material.pieces[std::size_t(c.piece)](c.centre) * c.normal;
      rc.force = mu, rc.onShaft = c.shaft, rc.piece = c.piece;
      out.contacts.push_back(rc);
      sumF += mu * c.normal;
      sumT += glm::cross(rc.point - fr.x, mu * c.normal);
    }
    out.torque = rotate ? metric.kr * fr.phi : sumT;
    const double fn = glm::length(out.force);
    out.stationarity = (glm::length(out.force - sumF) + glm::length(out.torque - sumT) / tool.shaftLength) /
                       std::max(fn, 1e-3);
    out.converged = run.stepConverged && out.violation <= tol.violation &&
                    out.stationarity <= tol.stationarity;
    if (fn > 0.0) {
      out.actionAxis = out.force / fn;
      out.actionPoint = fr.x + glm::cross(out.force, out.torque) / (fn * fn);
      out.momentArm = glm::length(out.torque) / fn;
    }
    return out;
  };
  PhysicalPose result = report(runs[best]);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (r == best || runs[r].v.squaredNorm() > runs[best].v.squaredNorm() * (1.0 + 1e-6)) continue;
    PhysicalPose alt = report(runs[r]);
    bool fresh = glm::length(alt.pose.position - result.pose.position) > 1e-7;
    for (const PhysicalPose& seen : result.alternatives)
      fresh = fresh && glm::length(alt.pose.position - seen.pose.position) > 1e-7;
    if (fresh) result.alternatives.push_back(std::move(alt));
  }
  return result;
}

}  // namespace millsim::measure
