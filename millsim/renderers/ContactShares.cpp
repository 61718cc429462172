#include "millsim/renderers/ContactShares.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace millsim {

void contactShares(const glm::dvec3* normals, const double* depths, int n, double* shares) {
  n = std::clamp(n, 0, kMaxPointContacts);
  double cap[kMaxPointContacts], deepest = 0.0;
  for (int i = 0; i < n; ++i) {
    cap[i] = depths[i] > 0.0 && std::isfinite(depths[i]) ? depths[i] : 0.0;  // NaN or clear: no share
    shares[i] = cap[i];  // the sum's shares: the answer for contacts at right angles
    deepest = std::max(deepest, cap[i]);
  }
  if (!(deepest > 0.0)) return;
  // A normal that is not unit (or NaN) couples with nothing and keeps the sum's share.
  bool unit[kMaxPointContacts];
  for (int i = 0; i < n; ++i) {
    const double nn = glm::dot(normals[i], normals[i]);
    unit[i] = nn > 0.5 && nn < 2.0;
  }
  double g[kMaxPointContacts][kMaxPointContacts];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g[i][j] = unit[i] && unit[j] ? glm::dot(normals[i], normals[j]) : 0.0;
  // Each sweep minimises over one share at a time, the others held, and
  // clamps it to its box: the objective falls every step, and the box keeps
  // it bounded where the normals are parallel or opposed.
  for (int sweep = 0; sweep < 200; ++sweep) {
    double change = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!unit[i]) continue;
      double residual = cap[i];
      for (int j = 0; j < n; ++j) residual -= g[i][j] * shares[j];
      const double next = std::clamp(shares[i] + residual / g[i][i], 0.0, cap[i]);
      change = std::max(change, std::abs(next - shares[i]));
      shares[i] = next;
    }
    if (!(change > 1e-9 * deepest)) break;
  }
}

BurrShaftShares burrAndShaftShares(const glm::dvec3& burrPush, const glm::dvec3& shaftNormal, double shaftDepth) {
  const double burrDepth = glm::length(burrPush);
  if (!(burrDepth > 0.0)) return {0.0, shaftDepth};
  const glm::dvec3 normals[2] = {burrPush / burrDepth, shaftNormal};
  const double depths[2] = {burrDepth, shaftDepth + glm::dot(burrPush, shaftNormal)};
  double shares[2];
  contactShares(normals, depths, 2, shares);
  return {shares[0], shares[1]};
}

}  // namespace millsim
