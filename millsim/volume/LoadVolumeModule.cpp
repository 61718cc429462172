// loadVolumeModule() (VolumeModule.h). Part of libmillsim_scene, which only
// dlopens libmillsim: it never links it or OpenVDB.
#include <mutex>

#include "millsim/core/SiblingLibrary.h"
#include "millsim/volume/VolumeModule.h"

namespace millsim {

const VolumeModule* loadVolumeModule(std::string& error) {
  static std::mutex mutex;
  static const VolumeModule* module = nullptr;
  static std::string failure;
  std::lock_guard lock(mutex);
  if (!module && failure.empty()) {
    module = static_cast<const VolumeModule*>(openSiblingLibrary(
        MILLSIM_VOLUME_LIBRARY_NAME, "MILLSIM_VOLUME_LIBRARY", "millsim_volume_module", kVolumeAbiVersion, "volume",
        "it is built and installed with libmillsim_scene", failure));
  }
  error = failure;
  return module;  // the library stays loaded for the life of the process
}

}  // namespace millsim
