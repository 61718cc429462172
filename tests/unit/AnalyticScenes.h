#pragma once
// Analytic test volumes shared by the renderer, Barbič and HandDevice suites:
// n³ voxels of 0.1 mm centred on the origin, material (density 1000, air 0,
// iso 500) where dist(p) < 0, with a one-voxel anti-aliased edge so the
// trilinear iso-surface lies on dist = 0.
#include <algorithm>
#include <functional>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "millsim/haptics/MillTool.h"
#include "millsim/math/Pose.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim::test {

constexpr double kH = 0.1e-3;  // voxel size
constexpr float kIso = 500.f;
inline const ToolGeometry kTool{0.5e-3, 0.25e-3, 3.0e-3};

inline VoxelVolume analytic(int n, const std::function<double(const glm::dvec3&)>& dist) {
  std::vector<float> v(std::size_t(n) * n * n);
  const double c = (n - 1) * 0.5;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = (glm::dvec3(i, j, k) - c) * kH;
        v[(std::size_t(k) * n + j) * n + i] = float(1000.0 * std::clamp(0.5 - dist(p) / kH, 0.0, 1.0));
      }
  return VoxelVolume::fromDense(v.data(), {n, n, n}, glm::dvec3(kH), 0.f);
}

// Material below y = 0.
inline VoxelVolume slab() { return analytic(64, [](const glm::dvec3& p) { return p.y; }); }

inline Pose vertical(glm::dvec3 at) { return Pose{at, glm::dquat(1, 0, 0, 0)}; }
// Shaft tilted from +Y towards +X by `angle` (rotation about −Z).
inline Pose tilted(glm::dvec3 at, double angle) { return Pose{at, glm::angleAxis(angle, glm::dvec3(0, 0, -1))}; }

}  // namespace millsim::test
