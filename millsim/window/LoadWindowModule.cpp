// loadWindowModule() and displayAvailable() (WindowModule.h). Part of
// libmillsim, which only dlopens the window library.
#include <cstdlib>
#include <mutex>
#include <string>

#include "millsim/graphics/GraphicsError.h"
#include "millsim/core/SiblingLibrary.h"
#include "millsim/window/WindowModule.h"

namespace millsim {

const WindowModule& loadWindowModule() {
  static std::mutex mutex;
  static const WindowModule* module = nullptr;
  static std::string error;
  std::lock_guard lock(mutex);
  if (!module && error.empty()) {
    module = static_cast<const WindowModule*>(
        openSiblingLibrary("libmillsim_window.so", "MILLSIM_WINDOW_LIBRARY", "millsim_window_module",
                           kWindowAbiVersion, "window",
                           "the window needs SDL2 and OpenGL: Debian packages libsdl2-2.0-0 and libgl1", error));
  }
  if (!module) throw GraphicsError(error);
  return *module;  // the library stays loaded for the life of the process
}

bool displayAvailable() {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
    if (const char* v = std::getenv(name); v && *v) return true;
  return false;
}

}  // namespace millsim
