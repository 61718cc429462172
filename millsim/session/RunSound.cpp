#include "millsim/session/RunSound.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <thread>
#include <vector>

#include "millsim/run/HapticLoop.h"

namespace millsim {

namespace {

// Live queue bounds: start (and restart after the device ran dry) with this much
// silence so that the scene thread's 20 ms batches never leave the device
// empty, and drop a batch rather than let the queue (the latency) grow past
// the limit after a stall.
constexpr double kPrimeSeconds = 0.06;
constexpr double kMaxQueuedSeconds = 0.25;
constexpr double kDrainWaitSeconds = 0.3;

}  // namespace

RunSound::RunSound(const RunSoundOptions& options, std::ostream& notices) : options_(options) {
  if (options_.live) {
    try {
      output_ = loadAudioModule().openOutput(MillingSoundParameters{}.sampleRate);
      device_ = output_->description();
    } catch (const std::exception& e) {
      notices << "millsim run: notice: no live sound (" << e.what() << "); running silent\n";
    }
  }
  if (!options_.wavPath.empty() || output_) track_ = std::make_unique<SoundTrack>(options_.wavPath);
}

RunSound::~RunSound() = default;

void RunSound::add(const FrameRecord& record) {
  if (!track_) return;
  track_->add(record);
  haveRecord_ = true;
  lastT_ = record.t;
}

void RunSound::fail(const std::exception& e) {
  error_ = e.what();
  track_.reset();  // no more synthesis; the live device goes quiet
  output_.reset();
}

void RunSound::take(const std::vector<std::int16_t>& samples) {
  if (!output_ || samples.empty()) return;
  // The first batch, and the first after the device ran dry (a stall, or a
  // device clock faster than the haptic one), go behind a cushion of silence.
  const bool dry = output_->queuedSeconds() <= 0.0;
  if (primed_ && dry) ++underruns_;
  if (!primed_ || dry) {
    const std::vector<std::int16_t> silence(std::size_t(kPrimeSeconds * track_->sampleRate()), 0);
    output_->queue(silence.data(), silence.size());
    primed_ = true;
  }
  if (output_->queuedSeconds() > kMaxQueuedSeconds) {
    droppedSeconds_ += double(samples.size()) / track_->sampleRate();
    return;
  }
  output_->queue(samples.data(), samples.size());
}

void RunSound::pump() {
  if (!track_) return;
  try {
    take(track_->flush());
  } catch (const std::exception& e) {
    fail(e);
  }
}

void RunSound::finish(std::optional<double> end) {
  if (track_) {
    try {
      take(track_->finish(end ? *end : haveRecord_ ? lastT_ + 1.0 / options_.hapticRate : 0.0));
    } catch (const std::exception& e) {
      fail(e);
    }
  }
  if (output_) {  // let the device play what is queued (bounded), then close it
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(kDrainWaitSeconds);
    while (output_->queuedSeconds() > 0.0 && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    output_.reset();
  }
}

void RunSound::printSummary(std::ostream& os) const {
  if (!track_) return;
  // The length as it is (a replay's is exactly frames / rate: "4.801 s").
  os << "  sound: " << track_->seconds() << " s at " << track_->sampleRate() << " Hz, RMS " << std::fixed
     << std::setprecision(1) << 20.0 * std::log10(std::max(track_->rms(), 1e-9)) << " dBFS";
  if (!track_->wavPath().empty()) os << ", written to " << track_->wavPath();
  if (!device_.empty())
    os << "; played live on " << device_ << " (underruns " << underruns_ << ", dropped " << std::setprecision(2)
       << droppedSeconds_ << " s)";
  os << "\n";
  os.unsetf(std::ios::fixed);
}

}  // namespace millsim
