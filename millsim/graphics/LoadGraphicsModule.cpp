// loadGraphicsModule() (GraphicsModule.h). Part of libmillsim, which only
// dlopens the graphics library: it never links it or OSMesa.
#include <cstdlib>
#include <mutex>
#include <string>

#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/GraphicsModule.h"
#include "millsim/core/SiblingLibrary.h"

namespace millsim {

namespace {

const GraphicsModule* openGraphicsModule(std::string& error) {
  const auto* module = static_cast<const GraphicsModule*>(
      openSiblingLibrary("libmillsim_graphics.so", "MILLSIM_GRAPHICS_LIBRARY", "millsim_graphics_module", "graphics",
                         "graphics needs Mesa's OSMesa: Debian package libosmesa6", error));
  if (module && module->abiVersion != kGraphicsAbiVersion) {
    error = "the graphics library is not of MillSim graphics ABI version " + std::to_string(kGraphicsAbiVersion);
    return nullptr;
  }
  return module;  // the library stays loaded for the life of the process
}

}  // namespace

const GraphicsModule& loadGraphicsModule() {
  static std::mutex mutex;
  static const GraphicsModule* module = nullptr;
  static std::string error;
  std::lock_guard lock(mutex);
  if (!module && error.empty()) module = openGraphicsModule(error);
  if (!module) throw GraphicsError(error);
  return *module;
}

}  // namespace millsim
