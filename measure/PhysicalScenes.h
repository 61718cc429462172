#pragma once
// The scenes and poses of the physical accuracy suite (docs/accuracy.md,
// "Physical reference"): each scene's material both as one exact signed
// distance (voxelised for the renderers) and as exact pieces (for the
// reference solver), and the device poses pressed into it. Depths are physical
// (mm), the same at every voxel size, so errors at different h are comparable.
#include <memory>
#include <string>
#include <vector>

#include "measure/AnalyticScene.h"
#include "measure/PhysicalReference.h"
#include "millsim/volume/MeshFile.h"

namespace millsim::measure {

struct PhysicalScene {
  std::string name;
  Shape shape;        // the whole material, exact signed distance (for voxelise)
  Material material;  // the same material as a union of exact pieces (for constrainedPose)
  bool shaftContact = false;  // the poses press the shaft, not the burr
  // Voxelised from a surface mesh of the shape (MeshVolume.h, as a scene's
  // mesh url is) rather than from its exact distance: "mesh-ball".
  bool fromMesh = false;
};

// half-space, ball, bowl, edge, plate, shaft-on-edge, hole.
std::vector<std::string> physicalSceneNames();
// Also by name, not in the suite's set: "mesh-ball", the ball as a closed
// mesh of 20 480 triangles voxelised the way a mesh url is — it checks the
// mesh path against the ball's exact voxelisation, not the renderers.
bool isPhysicalSceneName(const std::string& name);
PhysicalScene physicalScene(const std::string& name);
// The scene's material voxelised at h: from its exact distance, or from its
// mesh (fromMesh).
std::unique_ptr<AnalyticScene> voxelisePhysical(const PhysicalScene& scene, double h);
// A sphere of radius R at the origin: an icosahedron subdivided `levels` times,
// its vertices on the sphere (20 · 4^levels triangles).
MeshPart icosphere(double R, int levels);

struct PhysicalProbe {
  Pose device;         // the held device pose
  glm::dvec3 start{0.0};  // where the approach starts, in free space
  double depth = 0.0;  // how far the pressed part (burr or shaft surface) is pushed past the surface (m)
};

// Depths 0.05, 0.1, 0.2, 0.3, 0.6 mm of the burr (0.05–0.3 mm in the hole, 0.05–0.2 mm of the shaft) × tilts ×
// `phases` sub-voxel shifts of the whole pose (0, 0.37h, ... along (1, 0, ½)).
std::vector<PhysicalProbe> physicalProbes(const PhysicalScene& scene, const ToolGeometry& tool, double h, int phases);

}  // namespace millsim::measure
