#pragma once
// ToolSdf: the signed distance of the mill (Algorithm #3's "SPO", §6.1) in the
// tool's own frame — the burr head (a sphere of radius R at the origin, or a
// cylinder, taper or inverted cone centred on it: millsim/haptics/BurrHead.h),
// union a shaft cylinder of radius r from y = 0 to y = shaftLength. Negative
// inside.
//
// Two forms: the exact analytic distance (with its gradient and Hessian, which
// the 6×6 stiffness needs), and the paper's precomputed grid, sampled
// trilinearly at `voxelSize`. The grid is built once per tool shape; its error
// against the analytic form is measured in tests/unit/BarbicTest.cpp and
// docs/algorithms.md says which one the renderer uses by default and why.
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "millsim/haptics/MillTool.h"

namespace millsim {

struct SdfSample {
  double distance = 0.0;      // m, negative inside
  glm::dvec3 gradient{0.0};   // unit where defined
  glm::dmat3 hessian{0.0};    // ∂²d/∂q², zero where d is flat (or for the grid)
};

class ToolSdf {
public:
  ToolSdf(const ToolGeometry& tool, double gridVoxelSize);

  const ToolGeometry& tool() const { return tool_; }
  // Local bounding box of the tool (no margin).
  glm::dvec3 boxLo() const { return {-outer_, -headHalf(), -outer_}; }
  glm::dvec3 boxHi() const { return {outer_, std::max(headHalf(), tool_.shaftLength), outer_}; }

  // Exact distance alone (the cheap test for "is this point in contact").
  double distance(const glm::dvec3& q) const;
  // Distance, gradient and (if wanted) Hessian of the analytic form.
  SdfSample analytic(const glm::dvec3& q, bool withHessian) const;

  // The precomputed grid: trilinear distance and its gradient. Outside the grid
  // (more than a margin from the tool) it returns the analytic value.
  double sampledDistance(const glm::dvec3& q) const;
  SdfSample sampled(const glm::dvec3& q) const;

  double gridVoxelSize() const { return h_; }
  glm::ivec3 gridDims() const { return dims_; }
  std::size_t gridBytes() const { return grid_.size() * sizeof(float); }

private:
  // How far the head reaches along ±Y from the origin.
  double headHalf() const { return tool_.round() ? tool_.tipRadius : 0.5 * tool_.tipLength; }
  double headDistance(const glm::dvec3& q) const;
  bool cell(const glm::dvec3& q, glm::ivec3& i0, glm::dvec3& f) const;
  float at(int i, int j, int k) const { return grid_[(std::size_t(k) * dims_.y + j) * dims_.x + i]; }

  ToolGeometry tool_;
  double outer_;  // max(tipRadius, shaftRadius)
  double h_;
  glm::dvec3 origin_;  // local position of grid node (0, 0, 0)
  glm::ivec3 dims_;
  std::vector<float> grid_;
};

}  // namespace millsim
