// loadGraphicsModule() (GraphicsModule.h) and openSiblingLibrary()
// (SiblingLibrary.h). Part of libmillsim, which only dlopens the graphics and
// window libraries: it never links them, OSMesa, SDL2 or libGL.
#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/GraphicsModule.h"
#include "millsim/graphics/SiblingLibrary.h"

namespace millsim {

namespace {

// The folder this library (libmillsim) was loaded from.
std::filesystem::path ownFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&openSiblingLibrary), &info) && info.dli_fname)
    return std::filesystem::path(info.dli_fname).parent_path();
  return {};
}

const GraphicsModule* open(std::string& error) {
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

const void* openSiblingLibrary(const char* fileName, const char* overrideVar, const char* entry, const char* what,
                               const char* hint, std::string& error) {
  std::filesystem::path library;
  if (const char* env = std::getenv(overrideVar); env && *env)
    library = env;
  else
    library = ownFolder() / fileName;
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    error = std::string("cannot load the ") + what + " library " + library.string() + ": " +
            (why ? why : "unknown error") + " (" + hint + ")";
    return nullptr;
  }
  using Entry = const void* (*)();
  auto function = reinterpret_cast<Entry>(dlsym(handle, entry));
  const void* module = function ? function() : nullptr;
  if (!module) error = library.string() + " is not a MillSim " + what + " library (no " + entry + ")";
  return module;
}

const GraphicsModule& loadGraphicsModule() {
  static std::mutex mutex;
  static const GraphicsModule* module = nullptr;
  static std::string error;
  std::lock_guard lock(mutex);
  if (!module && error.empty()) module = open(error);
  if (!module) throw GraphicsError(error);
  return *module;
}

}  // namespace millsim
