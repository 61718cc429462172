#pragma once
// The milling sound of `millsim run` (issue 13, part 8): frame records from
// the log writer's hook are synthesized on the scene thread (MillingSound),
// written to --sound-out and queued to the live audio device
// (libmillsim_audio, SDL2), whose own thread plays them. Nothing here runs on
// the haptic thread or makes it wait. No audio device is a notice, not an error.
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "millsim/audio/AudioModule.h"
#include "millsim/audio/SoundTrack.h"

namespace millsim {

struct RunSoundOptions {
  std::string wavPath;     // --sound-out; empty: none
  bool live = true;        // play on the audio device (--no-sound: false)
  double hapticRate = 1000.0;  // Hz: the last frame lasts one period
};

class RunSound {
public:
  // Opens the WAV file (throws std::runtime_error naming it) and, when live,
  // the audio device; without one, prints a one-line notice to `notices`.
  RunSound(const RunSoundOptions& options, std::ostream& notices);
  ~RunSound();

  // FrameLogWriter's per-record hook (scene thread).
  void add(const FrameRecord& record);
  // After each drain: writes the new samples and queues them to the device.
  void pump();
  // After the last drain: the sound up to the run's end, the file closed, the
  // device given its last samples (a failed WAV write: error()). `end`: where
  // the sound ends (s); by default one haptic period after the last record
  // (a simulated run passes frames / rate, its exact length).
  void finish(std::optional<double> end = std::nullopt);
  // False when writing the WAV failed; error() says why.
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  void printSummary(std::ostream& os) const;

private:
  void take(const std::vector<std::int16_t>& samples);
  void fail(const std::exception& e);

  RunSoundOptions options_;
  std::unique_ptr<SoundTrack> track_;
  std::unique_ptr<AudioOutput> output_;
  bool haveRecord_ = false;
  double lastT_ = 0.0;
  bool primed_ = false;
  long underruns_ = 0;
  double droppedSeconds_ = 0.0;
  std::string device_;  // the live device's description; empty: none
  std::string error_;
};

}  // namespace millsim
