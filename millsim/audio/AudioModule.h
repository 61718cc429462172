#pragma once
// Live sound, loaded at run time. The millsim command does not link
// libmillsim_audio (nor, through it, SDL2): `millsim run` loads it with
// loadAudioModule() when it plays sound, so every other verb runs without
// SDL2, and a run without an audio device or without the library goes on
// silently after a one-line notice.
//
//   const AudioModule& a = loadAudioModule();               // throws std::runtime_error
//   std::unique_ptr<AudioOutput> out = a.openOutput(44100);  // throws std::runtime_error
//   out->queue(samples.data(), samples.size());              // never waits for the device
//
// The device's own thread (SDL's audio thread) pulls the queued samples; they
// are made and queued on the scene thread, never on the haptic thread.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace millsim {

// One open output device: mono, 16-bit, at the rate it was opened with.
class AudioOutput {
public:
  virtual ~AudioOutput() = default;
  // Appends samples to the device's queue; returns at once (no waiting for the device).
  virtual void queue(const std::int16_t* samples, std::size_t count) = 0;
  // Seconds of sound queued and not yet played.
  virtual double queuedSeconds() const = 0;
  // e.g. "SDL pulseaudio, 44100 Hz"
  virtual std::string description() const = 0;
};

// Bumped whenever AudioOutput or this table change incompatibly.
inline constexpr int kAudioAbiVersion = 1;

struct AudioModule {
  int abiVersion;
  // Opens the default output device and starts it. Throws std::runtime_error
  // saying why there is no device (e.g. SDL's "No available audio device").
  std::unique_ptr<AudioOutput> (*openOutput)(int sampleRate);
};

// Opens the library once per process (MILLSIM_AUDIO_LIBRARY overrides its
// path; by default it is looked for next to libmillsim). Throws
// std::runtime_error with the loader's message.
const AudioModule& loadAudioModule();

}  // namespace millsim
