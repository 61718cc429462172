// loadGraphicsModule() (GraphicsModule.h). Part of libmillsim, which only
// dlopens the graphics library: it never links it or OSMesa.
#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/GraphicsModule.h"

namespace millsim {

namespace {

// The folder this library (libmillsim) was loaded from.
std::filesystem::path ownFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&loadGraphicsModule), &info) && info.dli_fname)
    return std::filesystem::path(info.dli_fname).parent_path();
  return {};
}

const GraphicsModule* open(std::string& error) {
  std::filesystem::path library;
  if (const char* env = std::getenv("MILLSIM_GRAPHICS_LIBRARY"); env && *env)
    library = env;
  else
    library = ownFolder() / "libmillsim_graphics.so";
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    error = "cannot load the graphics library " + library.string() + ": " + (why ? why : "unknown error") +
            " (graphics needs Mesa's OSMesa: Debian package libosmesa6)";
    return nullptr;
  }
  using Entry = const GraphicsModule* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, "millsim_graphics_module"));
  const GraphicsModule* module = entry ? entry() : nullptr;
  if (!module || module->abiVersion != kGraphicsAbiVersion) {
    error = library.string() + " is not a MillSim graphics library of ABI version " +
            std::to_string(kGraphicsAbiVersion);
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
  if (!module && error.empty()) module = open(error);
  if (!module) throw GraphicsError(error);
  return *module;
}

}  // namespace millsim
