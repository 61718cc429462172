#pragma once
// A streaming writer of 16-bit PCM mono RIFF/WAVE files: samples go to disk as
// they come, and the header's two sizes are patched when the file is closed,
// so a long run never holds its whole sound in memory.
#include <cstdint>
#include <cstdio>
#include <string>

namespace millsim {

class WavWriter {
public:
  // Creates (truncates) the file and writes a header for zero samples.
  // Throws std::runtime_error naming the path when it cannot.
  WavWriter(const std::string& path, int sampleRate);
  ~WavWriter();  // closes (errors are lost: call close() to see them)
  WavWriter(const WavWriter&) = delete;
  WavWriter& operator=(const WavWriter&) = delete;

  // Throws std::runtime_error naming the path on a write error, or when the
  // data would outgrow what a RIFF header can count (4 GiB, ~13.5 h at 44.1 kHz).
  void write(const std::int16_t* samples, std::size_t count);
  // Patches the header and closes; throws std::runtime_error naming the path on failure.
  void close();

  const std::string& path() const { return path_; }
  std::uint64_t samples() const { return samples_; }
  int sampleRate() const { return sampleRate_; }

private:
  std::string path_;
  int sampleRate_;
  std::FILE* file_ = nullptr;
  std::uint64_t samples_ = 0;
};

}  // namespace millsim
