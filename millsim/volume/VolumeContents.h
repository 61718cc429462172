#pragma once
// VolumeContents: what a loaded VolumeObject holds — its voxels, their
// tissues and the point shells built from them. The node (libmillsim_scene)
// sees it only through this interface; libmillsim, which links OpenVDB,
// makes it (VolumeModule.h), so that a process that loads no volume never
// maps OpenVDB.
#include <string>

#include <glm/vec3.hpp>

namespace millsim {

class PointShell;
class TissueMap;
class VoxelVolume;

class VolumeContents {
public:
  virtual ~VolumeContents() = default;
  virtual VoxelVolume& voxels() = 0;
  virtual const VoxelVolume& voxels() const = 0;
  // The format the url was read as ("vdb", "nrrd", "phantom", ...).
  virtual const std::string& format() const = 0;
  // The volume's extent in its local frame (m): dimensions × voxel size.
  virtual glm::dvec3 size() const = 0;
  // The voxel's edges along x, y and z in its local frame (m).
  virtual glm::dvec3 voxelEdges() const = 0;
  // The point shell at an integer scale, built on first request.
  virtual PointShell& pointShell(int scale) = 0;
  virtual bool hasPointShell(int scale) const = 0;
  // The voxels' tissues; null when the volume has no Tissue nodes.
  virtual const TissueMap* tissueMap() const = 0;
};

}  // namespace millsim
