#pragma once
// An oriented box and its separating-axis test against an axis-aligned box
// (Gottschalk et al. 1996, "OBBTree"; Ericson, Real-Time Collision Detection
// §4.4): the culling test of Algorithm #3's point-shell hierarchy (§6.2).
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "millsim/volume/PointShell.h"

namespace millsim {

struct Obb {
  glm::dvec3 centre{0.0};
  glm::dvec3 axis[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // unit, orthogonal
  glm::dvec3 half{0.0};

  bool contains(const glm::dvec3& p) const {
    const glm::dvec3 d = p - centre;
    return std::abs(glm::dot(d, axis[0])) <= half.x && std::abs(glm::dot(d, axis[1])) <= half.y &&
           std::abs(glm::dot(d, axis[2])) <= half.z;
  }

  // Separating-axis test against an axis-aligned box: the 3 box axes, the 3
  // OBB axes and their 9 cross products. Conservative by a tiny epsilon.
  bool overlaps(const Aabb& box) const {
    if (box.empty()) return false;
    const glm::dvec3 bc = (glm::dvec3(box.lo) + glm::dvec3(box.hi)) * 0.5;
    const glm::dvec3 be = (glm::dvec3(box.hi) - glm::dvec3(box.lo)) * 0.5;
    const glm::dvec3 t = centre - bc;
    // R[i][j] = |axis[j] · e_i|, with an epsilon against parallel edges.
    double R[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R[i][j] = std::abs(axis[j][i]) + 1e-9;
    for (int i = 0; i < 3; ++i)  // world axes
      if (std::abs(t[i]) > be[i] + half.x * R[i][0] + half.y * R[i][1] + half.z * R[i][2]) return false;
    for (int j = 0; j < 3; ++j)  // OBB axes
      if (std::abs(glm::dot(t, axis[j])) > be.x * R[0][j] + be.y * R[1][j] + be.z * R[2][j] + half[j]) return false;
    for (int i = 0; i < 3; ++i)  // e_i × axis[j]
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double ra = be[i1] * R[i2][j] + be[i2] * R[i1][j];
        const double rb = half[j1] * R[i][j2] + half[j2] * R[i][j1];
        const double proj = t[i2] * axis[j][i1] - t[i1] * axis[j][i2];
        if (std::abs(proj) > ra + rb) return false;
      }
    return true;
  }
};

}  // namespace millsim
