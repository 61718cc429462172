// loadAudioModule() (AudioModule.h). Part of libmillsim, which only dlopens
// the audio library: it never links it or SDL2.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

#include "millsim/audio/AudioModule.h"

namespace millsim {

namespace {

std::filesystem::path ownFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&loadAudioModule), &info) && info.dli_fname)
    return std::filesystem::path(info.dli_fname).parent_path();
  return {};
}

const AudioModule* open(std::string& error) {
  std::filesystem::path library;
  if (const char* env = std::getenv("MILLSIM_AUDIO_LIBRARY"); env && *env)
    library = env;
  else
    library = ownFolder() / "libmillsim_audio.so";
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    error = "cannot load the audio library " + library.string() + ": " + (why ? why : "unknown error") +
            " (live sound needs SDL2: Debian package libsdl2-2.0-0)";
    return nullptr;
  }
  using Entry = const AudioModule* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, "millsim_audio_module"));
  const AudioModule* module = entry ? entry() : nullptr;
  if (!module || module->abiVersion != kAudioAbiVersion) {
    error = library.string() + " is not a MillSim audio library of ABI version " + std::to_string(kAudioAbiVersion);
    return nullptr;
  }
  return module;  // the library stays loaded for the life of the process
}

}  // namespace

const AudioModule& loadAudioModule() {
  static std::mutex mutex;
  static const AudioModule* module = nullptr;
  static std::string error;
  std::lock_guard lock(mutex);
  if (!module && error.empty()) module = open(error);
  if (!module) throw std::runtime_error(error);
  return *module;
}

}  // namespace millsim
