#pragma once
// A run's milling sound: frame records in, samples out to a WAV file and/or to
// whoever plays them live. Used by `millsim replay` (simulated time, so the
// WAV is reproducible byte for byte) and `millsim run` (apps/RunSound), on the
// thread that drains the frame log — never on the haptic thread.
//
//   SoundTrack track("out.wav");                 // opens the file now (throws, naming it)
//   for each record: track.add(record);          // synthesizes up to record.t
//   play(track.flush());                         // writes what is pending; returns it
//   track.finish(lastRecord.t + 1 / rate);       // the rest, then closes the file
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "millsim/audio/MillingSound.h"
#include "millsim/audio/WavFile.h"

namespace millsim {

class SoundTrack {
public:
  // wavPath empty: no file, samples are only handed out by flush().
  explicit SoundTrack(const std::string& wavPath, const MillingSoundParameters& parameters = {});

  void add(const FrameRecord& record);
  // Writes the samples made since the last flush to the WAV file and returns
  // them (valid until the next add or flush). Throws on a write error.
  const std::vector<std::int16_t>& flush();
  std::size_t pendingSamples() const { return pending_.size(); }
  // Synthesizes up to endTime (the run's end), writes and closes the file.
  // Returns the last samples, as flush() does.
  const std::vector<std::int16_t>& finish(double endTime);

  int sampleRate() const { return sound_.parameters().sampleRate; }
  std::int64_t samples() const { return sound_.samples(); }
  double seconds() const { return double(samples()) / sampleRate(); }
  double rms() const;  // of every sample flushed so far, full scale = 1
  const std::string& wavPath() const { return wavPath_; }

private:
  std::string wavPath_;
  MillingSound sound_;
  std::unique_ptr<WavWriter> wav_;
  std::vector<std::int16_t> pending_, handedOut_;
  double sumSquares_ = 0.0;
  std::uint64_t flushedSamples_ = 0;
};

}  // namespace millsim
