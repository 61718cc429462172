// loadAudioModule() (AudioModule.h). Part of libmillsim, which only dlopens
// the audio library: it never links it or SDL2.
#include <mutex>
#include <stdexcept>
#include <string>

#include "millsim/audio/AudioModule.h"
#include "millsim/core/SiblingLibrary.h"

namespace millsim {

namespace {

const AudioModule* openAudioModule(std::string& error) {
  // The library stays loaded for the life of the process.
  return static_cast<const AudioModule*>(openSiblingLibrary("libmillsim_audio.so", "MILLSIM_AUDIO_LIBRARY",
                                                            "millsim_audio_module", kAudioAbiVersion, "audio",
                                                            "live sound needs SDL2: Debian package libsdl2-2.0-0",
                                                            error));
}

}  // namespace

const AudioModule& loadAudioModule() {
  static std::mutex mutex;
  static const AudioModule* module = nullptr;
  static std::string error;
  std::lock_guard lock(mutex);
  if (!module && error.empty()) module = openAudioModule(error);
  if (!module) throw std::runtime_error(error);
  return *module;
}

}  // namespace millsim
