#include "millsim/audio/WavFile.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <algorithm>

namespace millsim {

namespace {

constexpr std::uint64_t kHeaderBytes = 44;
constexpr std::uint64_t kMaxDataBytes = 0xFFFFFFFFull - (kHeaderBytes - 8);

void put16(unsigned char* p, std::uint32_t v) {
  p[0] = static_cast<unsigned char>(v & 0xFF);
  p[1] = static_cast<unsigned char>((v >> 8) & 0xFF);
}
void put32(unsigned char* p, std::uint32_t v) {
  put16(p, v & 0xFFFF);
  put16(p + 2, v >> 16);
}

// The canonical 44-byte header: RIFF, WAVE, a 16-byte fmt chunk (PCM, mono, 16 bit), data.
void header(unsigned char* h, int sampleRate, std::uint32_t dataBytes) {
  std::memcpy(h, "RIFF", 4);
  put32(h + 4, std::uint32_t(kHeaderBytes - 8) + dataBytes);
  std::memcpy(h + 8, "WAVEfmt ", 8);
  put32(h + 16, 16);                          // fmt chunk size
  put16(h + 20, 1);                           // PCM
  put16(h + 22, 1);                           // channels
  put32(h + 24, std::uint32_t(sampleRate));   // samples per second
  put32(h + 28, std::uint32_t(sampleRate) * 2);  // bytes per second
  put16(h + 32, 2);                           // block align
  put16(h + 34, 16);                          // bits per sample
  std::memcpy(h + 36, "data", 4);
  put32(h + 40, dataBytes);
}

std::string why() { return errno ? std::strerror(errno) : "unknown error"; }

}  // namespace

WavWriter::WavWriter(const std::string& path, int sampleRate) : path_(path), sampleRate_(sampleRate) {
  if (sampleRate <= 0) throw std::invalid_argument(path + ": WAV sample rate must be positive");
  errno = 0;
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot write the WAV file: " + why());
  unsigned char h[kHeaderBytes];
  header(h, sampleRate_, 0);
  if (std::fwrite(h, 1, sizeof h, file_) != sizeof h) {
    const std::string reason = why();
    std::fclose(file_);
    file_ = nullptr;
    throw std::runtime_error(path + ": writing the WAV file failed: " + reason);
  }
}

WavWriter::~WavWriter() {
  try {
    close();
  } catch (...) {
  }
}

void WavWriter::write(const std::int16_t* samples, std::size_t count) {
  if (!file_) throw std::logic_error(path_ + ": the WAV file is closed");
  if (count == 0) return;
  if ((samples_ + count) * 2 > kMaxDataBytes)
    throw std::runtime_error(path_ + ": the sound is longer than a WAV file can hold (4 GiB)");
  // Little-endian on disk whatever the host is.
  unsigned char buffer[4096];
  std::size_t done = 0;
  while (done < count) {
    const std::size_t n = std::min<std::size_t>(count - done, sizeof buffer / 2);
    for (std::size_t i = 0; i < n; ++i) put16(buffer + 2 * i, std::uint16_t(samples[done + i]));
    errno = 0;
    if (std::fwrite(buffer, 2, n, file_) != n) throw std::runtime_error(path_ + ": writing the WAV file failed: " + why());
    done += n;
  }
  samples_ += count;
}

void WavWriter::close() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  unsigned char h[kHeaderBytes];
  header(h, sampleRate_, std::uint32_t(samples_ * 2));
  errno = 0;
  const bool ok = std::fseek(f, 0, SEEK_SET) == 0 && std::fwrite(h, 1, sizeof h, f) == sizeof h && std::fflush(f) == 0;
  const std::string reason = ok ? "" : why();
  if (std::fclose(f) != 0 || !ok)
    throw std::runtime_error(path_ + ": writing the WAV file failed: " + (ok ? why() : reason));
}

}  // namespace millsim
