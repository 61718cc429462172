#pragma once
// MeshVolume: a surface mesh's closed parts voxelised into the density and
// label volumes the CT readers and the phantom make, so that every renderer,
// milling, tissues, regions and the report work on a scanned or designed
// tooth unchanged. OpenVDB's mesh-to-volume gives each part's signed
// distance; a voxel's share of a part is its coverage (½ on the surface, as
// the phantom's), the parts layered from the largest inwards: nested parts
// (pulp in dentin in enamel) take the innermost's label, and a soft part's
// voxels a density below the isoValue (the burr passes through it).
//
// A part that is not closed is refused, naming it, how many open edges and
// where — unless its holes are narrower than half a voxel (cracks between
// faces that meet), which the voxelisation seals. A part whose voxels hold
// far less than its surface encloses (a leak) is refused too.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "millsim/volume/MeshFile.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

struct MeshVoxelOptions {
  double voxelSize = 0.0;  // m, cubic voxels
  double unit = 1.0;       // m per unit of the file's coordinates
  float isoValue = 700.f, airValue = -1000.f;
  std::set<std::string> softParts;  // by part name
  std::set<int> softLabels;         // by label (part i + 1)
};

struct MeshVolume {
  VoxelVolume density;
  VoxelVolume labels;  // part i is label i + 1; air 0
  std::vector<std::string> parts;
  std::vector<double> enclosed;  // each part's enclosed volume by its surface (m³)
  std::vector<std::size_t> triangles;
  glm::dvec3 size{0.0};          // the mesh's bounding box (m)
  // The voxel box's centre in the mesh's coordinates (m): where the volume's
  // local origin is. Voxel centres lie on multiples of the voxel size there.
  glm::dvec3 centre{0.0};
  std::string format;
};

// `name` for messages (the file). Throws VolumeError.
MeshVolume voxeliseMesh(const SurfaceMesh& mesh, const std::string& name, const MeshVoxelOptions& options);
// readSurfaceMesh, then voxeliseMesh.
MeshVolume loadMeshVolume(const std::filesystem::path& file, const MeshVoxelOptions& options);

}  // namespace millsim
