#include "millsim/audio/SoundTrack.h"

#include <cmath>

namespace millsim {

SoundTrack::SoundTrack(const std::string& wavPath, const MillingSoundParameters& parameters)
    : wavPath_(wavPath), sound_(parameters) {
  if (!wavPath_.empty()) wav_ = std::make_unique<WavWriter>(wavPath_, parameters.sampleRate);
}

void SoundTrack::add(const FrameRecord& record) { sound_.addFrame(burrStateOf(record), pending_); }

const std::vector<std::int16_t>& SoundTrack::flush() {
  for (std::int16_t s : pending_) sumSquares_ += double(s) * double(s);
  flushedSamples_ += pending_.size();
  if (wav_) wav_->write(pending_.data(), pending_.size());
  handedOut_.swap(pending_);
  pending_.clear();
  return handedOut_;
}

const std::vector<std::int16_t>& SoundTrack::finish(double endTime) {
  sound_.finish(endTime, pending_);
  const std::vector<std::int16_t>& last = flush();
  if (wav_) wav_->close();
  return last;
}

double SoundTrack::rms() const {
  return flushedSamples_ > 0 ? std::sqrt(sumSquares_ / double(flushedSamples_)) / 32768.0 : 0.0;
}

}  // namespace millsim
