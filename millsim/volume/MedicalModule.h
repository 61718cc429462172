#pragma once
// The medical-image library, libmillsim_medical: the readers that need VTK
// (MetaImage, VTI), GDCM (DICOM) or libtiff (micro-CT slice stacks), and the
// iso-surface mesher (VTK's flying edges). libmillsim does not link it: readMetaImage(), readVti() and
// readDicom() (VolumeIO.h) open it on first use through loadMedicalModule(),
// so that a process that reads no such file — `millsim --version`, `millsim
// nodes`, a scene of a .vdb, .nrrd or phantom volume — never maps VTK or GDCM.
// Graphics (which meshes volumes), the iso-surface tests and benchmarks link
// it directly (MillSim::medical).
// Internal to millsim/volume (listed in cmake/private-headers.txt).
#include <filesystem>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

// Bumped whenever this table changes incompatibly.
inline constexpr int kMedicalAbiVersion = 2;

struct MedicalModule {
  int abiVersion;
  VoxelVolume (*readMetaImage)(const std::filesystem::path& file, float airValue);
  VoxelVolume (*readVti)(const std::filesystem::path& file, float airValue);
  VoxelVolume (*readDicom)(const std::filesystem::path& fileOrFolder, float airValue);
  VoxelVolume (*readSliceStack)(const std::filesystem::path& source, float airValue, glm::dvec3 voxelSize);
};

// Opens the library once per process (MILLSIM_MEDICAL_LIBRARY overrides its
// path; by default it is looked for next to libmillsim). Throws VolumeError
// with the loader's message when it cannot.
const MedicalModule& loadMedicalModule();

// The readers themselves, defined in libmillsim_medical. Named apart from
// VolumeIO.h's entry points, which libmillsim defines and which would
// otherwise interpose on them (both libraries export their symbols).
namespace medical {
VoxelVolume readMetaImage(const std::filesystem::path& file, float airValue);
VoxelVolume readVti(const std::filesystem::path& file, float airValue);
VoxelVolume readDicom(const std::filesystem::path& fileOrFolder, float airValue);
VoxelVolume readSliceStack(const std::filesystem::path& source, float airValue, glm::dvec3 voxelSize);
}  // namespace medical

}  // namespace millsim
