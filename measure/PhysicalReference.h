#pragma once
// The physical reference (docs/accuracy.md, "Physical reference"): the pose a
// rigid MillTool takes when an ideal virtual coupling holds it against rigid
// material — the non-penetrating pose nearest the device pose in the coupling
// metric ½k|Δx|² + ½kr|Δθ|² — and the wrench that pose renders. One truth for
// every renderer, computed from exact signed distances, with no voxels.
#include <functional>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "millsim/haptics/MillTool.h"
#include "millsim/math/Pose.h"

namespace millsim::measure {

// Material as a union of pieces, each an exact signed distance (m, < 0 inside).
// The distance to the union is the least of the pieces'; keeping them apart lets
// the solver see a concave corner (the bottom and wall of a hole) as two smooth
// contacts instead of one kinked one. Outside its piece each distance must be
// the exact Euclidean distance (it is C¹ there for the scenes used).
struct Material {
  std::vector<std::function<double(const glm::dvec3&)>> pieces;
  double distance(const glm::dvec3& p) const;
};

struct CouplingMetric {
  double k = 2000.0;  // N/m
  // N·m/rad; infinity holds the orientation at the device's (the renderers
  // that draw the device's orientation and have no rotational coupling).
  double kr = std::numeric_limits<double>::infinity();
};

struct ReferenceTolerance {
  double violation = 1e-10;  // m: the deepest any tool point may stay inside material
  double step = 1e-11;       // m (and m-equivalent for rotation): converged when the last step is smaller
  double stationarity = 1e-6;  // KKT residual, relative (PhysicalPose::stationarity)
  int maxIterations = 200;
  int shaftSamples = 400;    // samples along the shaft axis between which each local minimum is refined
};

struct ReferenceContact {
  glm::dvec3 point{0.0};   // on the material surface (m)
  glm::dvec3 normal{0.0};  // outward normal of the material there
  double force = 0.0;      // N along normal, on the tool
  bool onShaft = false;
  int piece = 0;
};

struct PhysicalPose {
  Pose pose;                 // the constrained tool pose
  glm::dvec3 force{0.0};     // on the hand: k·(x_c − x_d), N
  glm::dvec3 torque{0.0};    // on the hand, about the burr centre: kr·rotvec(R_c R_dᵀ) (BarbicRenderer's sign), or
                             // with kr = ∞ the contact forces' moment about the constrained burr centre, N·m
  std::vector<ReferenceContact> contacts;
  // Stiffness-free: the wrench's line of action (the point of it nearest the
  // constrained burr centre, and its direction) and moment arm |T|/|F| (m).
  glm::dvec3 actionPoint{0.0}, actionAxis{0.0};
  double momentArm = 0.0;
  // Other poses exactly as near in the coupling metric (a burr pressed past an
  // edge along its bisector may slide onto either face): a renderer that took
  // one of them is measured against it.
  std::vector<PhysicalPose> alternatives;
  // Solver report: deepest remaining penetration (m, ≥ 0), KKT residual
  // |k·Δx − ΣF_i n_i| / max(|F|, 1 mN) (1), iterations, and whether both
  // tolerances were met.
  double violation = 0.0, stationarity = 0.0;
  int iterations = 0;
  bool converged = false;
};

// The constrained pose of `tool` at device pose `device` against `material`.
// The shaft is the capsule of its axis segment (the far end's flat face is
// rounded; exact for contacts on the burr and the shaft's side).
PhysicalPose constrainedPose(const Material& material, const ToolGeometry& tool, const Pose& device,
                             const CouplingMetric& metric, const ReferenceTolerance& tolerance = {});

// The rotation vector of q (angle·axis, the short way round).
glm::dvec3 rotationVector(const glm::dquat& q);

}  // namespace millsim::measure
