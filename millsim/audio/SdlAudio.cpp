// libmillsim_audio: live sound through SDL2's audio subsystem. The scene
// thread queues samples with SDL_QueueAudio (a short lock inside SDL, never
// a wait for the device); SDL's own audio thread pulls them. The table
// loadAudioModule() finds is at the end.
#include <SDL.h>
#include <dlfcn.h>

#include <stdexcept>
#include <string>

#include "millsim/audio/AudioModule.h"

extern "C" {
// ALSA's error handler type (alsa/error.h), declared here so that neither the
// headers nor the library are needed at build time.
using AlsaErrorHandler = void (*)(const char* file, int line, const char* function, int err, const char* fmt, ...);
static void quietAlsa(const char*, int, const char*, int, const char*, ...) {}
}

namespace millsim {

namespace {

// Without a sound card, ALSA prints eight lines to stderr while SDL probes it;
// SDL's own error says the same in one ("ALSA: Couldn't open audio device …"),
// which becomes the run's one-line notice. So silence ALSA's printer when ALSA
// is installed (SDL dlopens the same library later; it stays loaded).
void silenceAlsa() {
  static bool done = false;
  if (done) return;
  done = true;
  void* alsa = dlopen("libasound.so.2", RTLD_LAZY | RTLD_LOCAL);
  if (!alsa) return;
  using SetHandler = int (*)(AlsaErrorHandler);
  if (auto set = reinterpret_cast<SetHandler>(dlsym(alsa, "snd_lib_error_set_handler"))) set(&quietAlsa);
}

class SdlAudioOutput final : public AudioOutput {
public:
  explicit SdlAudioOutput(int sampleRate) {
    silenceAlsa();
    if (SDL_InitSubSystem(SDL_INIT_AUDIO) != 0)
      throw std::runtime_error(std::string("SDL audio: ") + SDL_GetError());
    SDL_AudioSpec want{}, have{};
    want.freq = sampleRate;
    want.format = AUDIO_S16SYS;
    want.channels = 1;
    want.samples = 512;  // ~12 ms per device period at 44.1 kHz
    want.callback = nullptr;  // queued: SDL_QueueAudio
    device_ = SDL_OpenAudioDevice(nullptr, 0, &want, &have, 0);  // SDL converts if the device differs
    if (device_ == 0) {
      const std::string why = SDL_GetError();
      SDL_QuitSubSystem(SDL_INIT_AUDIO);
      throw std::runtime_error("SDL audio: " + why);
    }
    const char* driver = SDL_GetCurrentAudioDriver();
    description_ = std::string("SDL ") + (driver ? driver : "?") + ", " + std::to_string(sampleRate) + " Hz";
    bytesPerSecond_ = double(sampleRate) * 2.0;
    SDL_PauseAudioDevice(device_, 0);
  }
  ~SdlAudioOutput() override {
    SDL_CloseAudioDevice(device_);
    SDL_QuitSubSystem(SDL_INIT_AUDIO);
  }
  void queue(const std::int16_t* samples, std::size_t count) override {
    if (count) SDL_QueueAudio(device_, samples, Uint32(count * sizeof(std::int16_t)));
  }
  double queuedSeconds() const override { return double(SDL_GetQueuedAudioSize(device_)) / bytesPerSecond_; }
  std::string description() const override { return description_; }

private:
  SDL_AudioDeviceID device_ = 0;
  std::string description_;
  double bytesPerSecond_ = 88200.0;
};

std::unique_ptr<AudioOutput> openOutput(int sampleRate) { return std::make_unique<SdlAudioOutput>(sampleRate); }

const AudioModule kModule{kAudioAbiVersion, &openOutput};

}  // namespace

}  // namespace millsim

// Typed as the loader calls it (SiblingLibrary: const void* (*)()): a call through
// another function type is undefined behaviour (clang's -fsanitize=function).
extern "C" __attribute__((visibility("default"))) const void* millsim_audio_module() {
  return &millsim::kModule;
}
