#pragma once
// The field #1's burr proxy is held out of when it holds the whole tool
// (LineProxyRenderer's holdWholeTool; docs/algorithms.md, Algorithm #1): the
// scene dilated by the burr sphere (BurrField) together with the shaft's
// contact, linearised as a plane at the pose where it was found this frame.
// A burr-centre position p (the tool keeps the device's orientation) is in
// material when either part is, so the proxy stops, slides and settles on
// whichever constrains it, and in the crease between them (the burr on a
// hole's wall, the shaft on the far rim) as a two-plane god object does.
//
// Why a plane per frame, not the shaft's deepest line searched at every
// evaluation: the proxy evaluates its field some hundred times a frame, a
// line search costs some hundred samples, and the plane is found where the
// proxy rested last frame, out of material, so it is exact to first order
// where the proxy goes next.
#include <glm/vec3.hpp>

#include "millsim/renderers/ProxyPoint.h"

namespace millsim {

class WholeToolField final : public ProxyField {
public:
  explicit WholeToolField(const BurrField& burr) : burr_(burr) {}

  // The shaft, found with the burr centre at `at`: `depth` (m, > 0 in
  // material) past the surface along the unit `into`, the way that deepens it.
  void setShaftPlane(const glm::dvec3& at, const glm::dvec3& into, double depth) {
    at_ = at, into_ = into, depth_ = depth, hasPlane_ = true;
  }
  void clearShaftPlane() { hasPlane_ = false; }
  bool hasShaftPlane() const { return hasPlane_; }

  // The shaft's depth (m) with the burr centre at p; −∞ without a plane.
  double shaftDepth(const glm::dvec3& p) const;
  // The burr's depth (m, first order: BurrField's value over its slope; ±∞
  // off its one-voxel ramp).
  double burrDepth(const glm::dvec3& p) const;
  // The shaft's outward normal (−into).
  glm::dvec3 shaftNormal() const { return -into_; }

  // The part that is deeper (in metres) answers, in its own units: a Newton
  // step value/gradient then stays within one part.
  double value(const glm::dvec3& p) const override;
  glm::dvec3 gradient(const glm::dvec3& p) const override;
  glm::dvec3 contactNormal(const glm::dvec3& p) const override;
  double voxelSize() const override { return burr_.voxelSize(); }
  // Onto the whole tool's surface: out of both parts where either is in
  // (into the crease, as the two contacts' nearest translation out, where
  // leaving one enters the other: a wedge), else onto the nearer. Newton
  // steps on whichever part answers alternated between the two in a wedge
  // and left the burr half a voxel in a hole's wall.
  glm::dvec3 projectToSurface(glm::dvec3 p, double maxStep) const override;
  bool maySaddle(const glm::dvec3& probe) const override { return burr_.maySaddle(probe); }

private:
  bool shaftAnswers(const glm::dvec3& p) const { return hasPlane_ && shaftDepth(p) > burrDepth(p); }

  const BurrField& burr_;
  glm::dvec3 at_{0.0}, into_{0.0, -1.0, 0.0};
  double depth_ = 0.0;
  bool hasPlane_ = false;
};

}  // namespace millsim
