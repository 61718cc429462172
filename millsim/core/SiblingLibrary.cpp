// openSiblingLibrary() (SiblingLibrary.h).
#include "millsim/core/SiblingLibrary.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

namespace millsim {

namespace {

// The folder this library (libmillsim) was loaded from.
std::filesystem::path ownFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&openSiblingLibrary), &info) && info.dli_fname)
    return std::filesystem::path(info.dli_fname).parent_path();
  return {};
}

}  // namespace

const void* openSiblingLibrary(const char* fileName, const char* overrideVar, const char* entry, int abiVersion,
                               const char* what, const char* hint, std::string& error) {
  std::filesystem::path library;
  void* handle = nullptr;
  if (const char* env = std::getenv(overrideVar); env && *env) {
    library = env;
  } else {
    library = ownFolder() / fileName;
    // Already in the process (libmillsim is, as a dependency of the command's
    // verbs, when a VolumeObject asks for it): that copy, wherever it was
    // found, never a second one from next to this library.
    handle = dlopen(fileName, RTLD_NOW | RTLD_NOLOAD);
  }
  if (!handle) handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    error = std::string("cannot load the ") + what + " library " + library.string() + ": " +
            (why ? why : "unknown error") + " (" + hint + ")";
    return nullptr;
  }
  using Entry = const void* (*)();
  auto function = reinterpret_cast<Entry>(dlsym(handle, entry));
  const void* module = function ? function() : nullptr;
  if (!module) {
    error = library.string() + " is not a MillSim " + what + " library (no " + entry + ")";
    return nullptr;
  }
  // Every module table starts with its ABI version (an int).
  if (*static_cast<const int*>(module) != abiVersion) {
    error = std::string("the ") + what + " library is not of MillSim " + what + " ABI version " +
            std::to_string(abiVersion);
    return nullptr;
  }
  return module;
}

}  // namespace millsim
