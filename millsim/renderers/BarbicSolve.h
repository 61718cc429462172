#pragma once
// The linearised quasi-static step of Algorithm #3 (§6.3, after Barbič &
// James 2008): penalty contacts between the tool's distance field and fixed
// shell points, a 6-DOF virtual coupling to the device, and the 6×6 solve for
// the tool's change of pose. Generalised coordinates of the tool: position x
// (the burr centre) and a small world-frame rotation θ about x. The wrench
// w = (F, τ) is what acts ON THE TOOL (τ about the burr centre); the stiffness
// is K = −∂w/∂(x, θ). The derivation is in docs/algorithms.md.
#include <Eigen/Core>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "millsim/math/Pose.h"

namespace millsim {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

struct Wrench6 {
  Vec6 w = Vec6::Zero();    // (F, τ) on the tool
  Mat6 K = Mat6::Zero();    // −∂w/∂(x, θ), exact
  Mat6 Kgn = Mat6::Zero();  // its Gauss–Newton part Σ k·J·Jᵀ (+ coupling): always positive semi-definite
  void clear() { w.setZero(), K.setZero(), Kgn.setZero(); }
};

// One contact: a shell point at arm r = p − x (world) with tool distance d < 0,
// world gradient n and world Hessian H of the tool's SDF there. Penalty energy
// ½·k·d², so F = k·d·n (pushes the tool off the point) and τ = r × F.
void addContact(Wrench6& acc, const glm::dvec3& r, double d, const glm::dvec3& n, const glm::dmat3& H, double k);

// Adds a wrench and its stiffnesses accumulated in the tool's frame (arms,
// normals and Hessians in tool coordinates) to `acc` in the world frame: w by
// R, each 3×3 block X by R·X·Rᵀ (a rotation does not change the sums, so it is
// applied once a frame rather than to each contact's Hessian and normal).
void addRotated(Wrench6& acc, const Wrench6& inToolFrame, const glm::dmat3& R);

struct Coupling {
  double k = 0, b = 0;    // linear stiffness (N/m) and damping (N·s/m)
  double kr = 0, br = 0;  // angular stiffness (N·m/rad) and damping (N·m·s/rad)
};

// The coupling's spring wrench on the tool at `tool` towards `device`, and its
// stiffness (k·I, kr·I: the exact derivative at zero rotation error).
void addCouplingSpring(Wrench6& acc, const Coupling& c, const Pose& tool, const Pose& device);

// World-frame rotation vector θ with device = exp(θ)·tool (|θ| ≤ π).
glm::dvec3 rotationError(const glm::dquat& tool, const glm::dquat& device);
// Applies a step (Δx, Δθ) to a pose: x += Δx, q = exp(Δθ)·q.
Pose applyStep(const Pose& p, const Vec6& step);

struct SolveResult {
  Vec6 step = Vec6::Zero();
  bool dropped = false;  // the full K was not positive definite: solved with the Gauss–Newton part
};

// Solves (K_sym + D/dt)·Δ = w + D·v_device for the step Δ of the tool over
// one frame of dt, where D = diag(b, b, b, br, br, br) is the coupling damping
// acting on the tool's velocity relative to the device's (v_device, 6-vector).
// K is symmetrised; if LDLT finds it indefinite, the Gauss–Newton part
// (positive definite with the coupling) is used instead.
SolveResult solveStep(const Wrench6& total, const Coupling& c, const Vec6& deviceVelocity, double dt);

}  // namespace millsim
