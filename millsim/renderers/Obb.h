#pragma once
// An oriented box and its separating-axis test against an axis-aligned box
// (Gottschalk et al. 1996, "OBBTree"; Ericson, Real-Time Collision Detection
// §4.4): the culling test of Algorithm #3's point-shell hierarchy (§6.2).
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "millsim/haptics/PointShellQuery.h"

namespace millsim {

class Obb {
public:
  // axes: unit and orthogonal; half: half extents along them.
  Obb(const glm::dvec3& centre, const glm::dvec3 (&axes)[3], const glm::dvec3& half)
      : centre_(centre), axis_{axes[0], axes[1], axes[2]}, half_(half) {
    // |axis[j] · e_i| with an epsilon against parallel edges: the same for
    // every box tested, so computed once (the hierarchy's culling tests every
    // super-bucket, twice a frame: 15 % of #3's instructions over the §8.2
    // procedure went to this test, a fifth of it to these nine terms).
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r_[i][j] = std::abs(axis_[j][i]) + 1e-9;
    // The box's world bounds in float, rounded outwards: a cheap first reject
    // in the boxes' own precision (below). Most boxes tested are far from
    // the tool, and the full test converted each to double first.
    for (int i = 0; i < 3; ++i) {
      const double extent = half_.x * r_[i][0] + half_.y * r_[i][1] + half_.z * r_[i][2];
      boundLo_[i] = std::nextafter(float(centre_[i] - extent), -std::numeric_limits<float>::infinity());
      boundHi_[i] = std::nextafter(float(centre_[i] + extent), std::numeric_limits<float>::infinity());
    }
  }

  bool contains(const glm::dvec3& p) const {
    const glm::dvec3 d = p - centre_;
    return std::abs(glm::dot(d, axis_[0])) <= half_.x && std::abs(glm::dot(d, axis_[1])) <= half_.y &&
           std::abs(glm::dot(d, axis_[2])) <= half_.z;
  }

  // Separating-axis test against an axis-aligned box: the 3 box axes, the 3
  // OBB axes and their 9 cross products. Conservative by a tiny epsilon.
  bool overlaps(const Aabb& box) const {
    if (box.empty()) return false;
    // Apart along a world axis by more than float rounding: the world-axis
    // tests below would say so too, so this never changes the answer.
    if (box.hi.x < boundLo_.x || box.lo.x > boundHi_.x || box.hi.y < boundLo_.y || box.lo.y > boundHi_.y ||
        box.hi.z < boundLo_.z || box.lo.z > boundHi_.z)
      return false;
    const glm::dvec3 bc = (glm::dvec3(box.lo) + glm::dvec3(box.hi)) * 0.5;
    const glm::dvec3 be = (glm::dvec3(box.hi) - glm::dvec3(box.lo)) * 0.5;
    const glm::dvec3 t = centre_ - bc;
    const auto& R = r_;
    for (int i = 0; i < 3; ++i)  // world axes
      if (std::abs(t[i]) > be[i] + half_.x * R[i][0] + half_.y * R[i][1] + half_.z * R[i][2]) return false;
    for (int j = 0; j < 3; ++j)  // OBB axes
      if (std::abs(glm::dot(t, axis_[j])) > be.x * R[0][j] + be.y * R[1][j] + be.z * R[2][j] + half_[j]) return false;
    for (int i = 0; i < 3; ++i)  // e_i × axis[j]
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double ra = be[i1] * R[i2][j] + be[i2] * R[i1][j];
        const double rb = half_[j1] * R[i][j2] + half_[j2] * R[i][j1];
        const double proj = t[i2] * axis_[j][i1] - t[i1] * axis_[j][i2];
        if (std::abs(proj) > ra + rb) return false;
      }
    return true;
  }

private:
  glm::dvec3 centre_;
  glm::dvec3 axis_[3];
  glm::dvec3 half_;
  double r_[3][3];
  glm::vec3 boundLo_, boundHi_;  // the box's world bounds, float, rounded outwards
};

}  // namespace millsim
