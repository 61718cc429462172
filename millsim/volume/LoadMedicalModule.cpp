// loadMedicalModule() (MedicalModule.h) and the VolumeIO.h entry points of the
// readers it holds. Part of libmillsim, which only dlopens libmillsim_medical:
// it never links it, VTK or GDCM.
#include <mutex>
#include <string>

#include "millsim/core/SiblingLibrary.h"
#include "millsim/volume/MedicalModule.h"
#include "millsim/volume/VolumeIO.h"

namespace millsim {

namespace {

const MedicalModule* openMedicalModule(std::string& error) {
  // The library stays loaded for the life of the process.
  return static_cast<const MedicalModule*>(openSiblingLibrary(
      "libmillsim_medical.so", "MILLSIM_MEDICAL_LIBRARY", "millsim_medical_module", kMedicalAbiVersion,
      "medical-image",
      "MetaImage, VTI, DICOM and TIFF-slice reading needs VTK 9.1, GDCM 3.0 and libtiff: Debian packages "
      "libvtk9.1, libgdcm3.0 and libtiff6",
      error));
}

}  // namespace

const MedicalModule& loadMedicalModule() {
  static std::mutex mutex;
  static const MedicalModule* module = nullptr;
  static std::string error;
  std::lock_guard lock(mutex);
  if (!module && error.empty()) module = openMedicalModule(error);
  if (!module) throw VolumeError(error);
  return *module;
}

namespace {

// The module, or a VolumeError that names the file it was opened for, as every reader's errors do.
const MedicalModule& moduleFor(const std::filesystem::path& file) {
  try {
    return loadMedicalModule();
  } catch (const VolumeError& e) {
    throw VolumeError(file.string() + ": " + e.what());
  }
}

}  // namespace

VoxelVolume readMetaImage(const std::filesystem::path& file, float airValue) {
  return moduleFor(file).readMetaImage(file, airValue);
}

VoxelVolume readVti(const std::filesystem::path& file, float airValue) {
  return moduleFor(file).readVti(file, airValue);
}

VoxelVolume readDicom(const std::filesystem::path& fileOrFolder, float airValue) {
  return moduleFor(fileOrFolder).readDicom(fileOrFolder, airValue);
}

VoxelVolume readSliceStack(const std::filesystem::path& source, float airValue, glm::dvec3 voxelSize) {
  return moduleFor(source).readSliceStack(source, airValue, voxelSize);
}

}  // namespace millsim
