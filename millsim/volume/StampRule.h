#pragma once
// The milling rule (Milling.h) in one place: how much of a voxel a stamp
// covers and the density that leaves it. The Miller writes it; the sampler
// reads a stamp the Miller has not walked yet (VolumeSampler::setPendingCuts).
// Both call these, so the two give the same value bit for bit.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "millsim/haptics/BurrHead.h"

namespace millsim::stamp {

// A round burr of `radius` covering a voxel centre `distance` from its centre (m).
inline double roundCoverage(double distance, double radius, double ramp) {
  return std::clamp(0.5 + (radius - distance) / ramp, 0.0, 1.0);
}

// A head along the unit `axis` covering a voxel centre at offset d from its centre (m).
inline double headCoverage(const glm::dvec3& d, const glm::dvec3& axis, const BurrHead& head, double ramp) {
  const double y = glm::dot(d, axis);
  const double rho = std::sqrt(std::max(0.0, glm::dot(d, d) - y * y));
  return std::clamp(0.5 - headProfileDistance(head, rho, y) / ramp, 0.0, 1.0);
}

// The density that leaves a (1 − coverage) material fraction: on the burr's
// surface (coverage ½) exactly the iso-value.
inline float densityLeft(double air, double iso, double coverage) {
  return static_cast<float>(air + 2.0 * (iso - air) * (1.0 - coverage));
}

}  // namespace millsim::stamp
