#pragma once
// Analytic reference geometry for the stability and accuracy suites: a shape
// is an exact signed distance (metres, negative inside material), voxelised
// at spacing h into a VoxelVolume whose iso-surface (density 500 of 1000) is
// the shape's surface up to the sampling error the renderers must live with.
#include <functional>
#include <memory>
#include <numbers>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "millsim/volume/MeshFile.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim::measure {

inline constexpr float kIso = 500.f;  // the iso value every analytic volume uses
inline constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;

struct Shape {
  std::string name;
  std::function<double(const glm::dvec3&)> distance;  // exact signed distance (< 0 inside)
  glm::dvec3 lo{0.0}, hi{0.0};                          // world box the volume must cover
};

// Material below the plane through the origin with outward normal +Y.
Shape halfSpace(glm::dvec3 lo, glm::dvec3 hi);
// A ball of radius R at the origin (convex).
Shape ball(double R);
// Material outside a spherical hole of radius R at the origin (concave).
Shape cavity(double R);
// A right-angled edge along Z: material where x < 0 and y < 0.
Shape edge(glm::dvec3 lo, glm::dvec3 hi);
// A plate |y| < thickness/2.
Shape plate(double thickness, glm::dvec3 lo, glm::dvec3 hi);

// A shape voxelised at spacing h with a one-voxel linear ramp
// (density = 1000·clamp(½ − d/h)), voxel centres on the lattice h·ℤ³ so planes
// through the origin fall exactly on the iso-surface; placed in a VoxelScene.
struct AnalyticScene {
  Shape shape;
  double h;
  std::unique_ptr<VoxelVolume> volume;
  std::unique_ptr<VoxelScene> scene;
  glm::dmat4 localToWorld{1.0};
};
std::unique_ptr<AnalyticScene> voxelise(const Shape& shape, double h);
// The shape as a scene author's mesh url gives it: `mesh` (in metres)
// voxelised at h by MeshVolume (millsim/volume/MeshVolume.h), whose coverage
// ramp is the same ½ − d/h; the iso-surface at kIso again. `shape` is kept
// for the reference.
std::unique_ptr<AnalyticScene> voxeliseMesh(const Shape& shape, const SurfaceMesh& mesh, double h);

}  // namespace millsim::measure
