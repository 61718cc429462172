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
  // The library stays loaded for the life of the process.
  return static_cast<const GraphicsModule*>(
      openSiblingLibrary("libmillsim_graphics.so", "MILLSIM_GRAPHICS_LIBRARY", "millsim_graphics_module",
                         kGraphicsAbiVersion, "graphics", "graphics needs Mesa's OSMesa: Debian package libosmesa6",
                         error));
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
