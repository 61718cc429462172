#include "millsim/audio/MillingSound.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "millsim/run/HapticLoop.h"

namespace millsim {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// The whine's harmonics (fundamental first), normalised so that their peak sum stays below 1.
constexpr double kHarmonics[] = {1.0, 0.5, 0.25, 0.12};
constexpr double kHarmonicNorm = 1.0 / (1.0 + 0.5 + 0.25 + 0.12);
constexpr double kWobbleHz = 7.0;     // slow amplitude modulation of the whine (bearing, hand)
constexpr double kWobbleDepth = 0.08;
constexpr double kNoiseQ = 1.2;       // the grinding band's quality factor
// A band-passed uniform white noise of Q 1.2 near 3 kHz has an RMS of about a
// fifth of its input's peak; this brings the noise's RMS near noiseLevel · load.
constexpr double kNoiseGain = 3.0;

// A one-pole smoother's per-sample coefficient for a time constant tau.
double onePole(double tau, double sampleRate) { return tau > 0.0 ? 1.0 - std::exp(-1.0 / (tau * sampleRate)) : 1.0; }

}  // namespace

BurrState burrStateOf(const FrameRecord& r) {
  BurrState s;
  s.t = r.t;
  s.spinning = r.button;
  s.removedVolume = r.removedVolume;
  s.force = std::sqrt(r.force.x * r.force.x + r.force.y * r.force.y + r.force.z * r.force.z);
  s.contacts = r.out.contacts;
  s.hardness = r.out.cutHardness;
  return s;
}

MillingSound::MillingSound(const MillingSoundParameters& parameters) : p_(parameters), rng_(parameters.seed) {
  if (p_.sampleRate < 8000 || p_.sampleRate > 192000)
    throw std::invalid_argument("MillingSound: sample rate " + std::to_string(p_.sampleRate) +
                                " Hz is outside [8000, 192000] Hz");
  const double fs = p_.sampleRate;
  spinUpCoef_ = onePole(p_.spinUp, fs);
  spinDownCoef_ = onePole(p_.spinDown, fs);
  loadAttackCoef_ = onePole(p_.loadAttack, fs);
  loadReleaseCoef_ = onePole(p_.loadRelease, fs);
}

double MillingSound::nextNoise() {
  // splitmix64: a fixed, seeded sequence, identical on every run.
  std::uint64_t z = (rng_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return double(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;  // uniform in [-1, 1)
}

void MillingSound::render(double untilTime, std::vector<std::int16_t>& out) {
  if (!(untilTime > 0.0) || !std::isfinite(untilTime)) return;
  const std::int64_t target = std::llround(untilTime * p_.sampleRate);
  if (target <= written_) return;
  const double fs = p_.sampleRate;
  const BurrMaterial m{p_.material.hardness * tissue_, p_.material.brightness * tissue_};
  const double bandCentre = std::min(p_.noiseFrequency * m.brightness, fs / 8.0);
  const double svfF = 2.0 * std::sin(std::numbers::pi * bandCentre / fs);
  const double svfQ = 1.0 / kNoiseQ;
  for (; written_ < target; ++written_) {
    spin_ += (targetSpin_ - spin_) * (targetSpin_ > spin_ ? spinUpCoef_ : spinDownCoef_);
    if (targetSpin_ == 0.0 && spin_ < 1e-3) spin_ = 0.0;  // stopped: true silence, not a decaying tail
    const double wantLoad = targetLoad_ * targetSpin_;
    load_ += (wantLoad - load_) * (wantLoad > load_ ? loadAttackCoef_ : loadReleaseCoef_);

    // The motor: pitch glides up with its speed and falls under load.
    const double speed = (0.55 + 0.45 * spin_) * (1.0 - std::clamp(p_.pitchDrop * m.hardness, 0.0, 0.9) * load_);
    phase_ += p_.whineFrequency * speed / fs;
    phase_ -= std::floor(phase_);
    wobblePhase_ += kWobbleHz / fs;
    wobblePhase_ -= std::floor(wobblePhase_);
    double tone = 0.0;
    for (int h = 0; h < 4; ++h) tone += kHarmonics[h] * std::sin(kTwoPi * double(h + 1) * phase_);
    tone *= kHarmonicNorm;
    const double toneAmp =
        p_.airLevel * spin_ * (1.0 + p_.loadedToneGain * load_) * (1.0 + kWobbleDepth * std::sin(kTwoPi * wobblePhase_));

    // The grinding: band-passed white noise (Chamberlin state-variable filter),
    // chopped once per revolution as the flutes bite.
    const double white = nextNoise();
    bandLow_ += svfF * bandBand_;
    const double high = white - bandLow_ - svfQ * bandBand_;
    bandBand_ += svfF * high;
    const double chop = 0.6 + 0.4 * std::sin(kTwoPi * phase_);
    const double noiseAmp = p_.noiseLevel * m.hardness * load_ * spin_ * kNoiseGain;

    const double s = toneAmp * tone + noiseAmp * bandBand_ * chop;
    out.push_back(std::int16_t(std::lround(std::clamp(s, -1.0, 1.0) * 32767.0)));
  }
}

void MillingSound::addFrame(const BurrState& state, std::vector<std::int16_t>& out) {
  if (finished_) return;
  render(state.t, out);
  // The removal rate, smoothed per frame with the frames' own time steps.
  if (haveFrame_) {
    const double dt = state.t - last_.t;
    if (dt > 0.0) {
      const double rate = std::max(0.0, state.removedVolume - last_.removedVolume) / dt;
      const double a = p_.removalSmoothing > 0.0 ? 1.0 - std::exp(-dt / p_.removalSmoothing) : 1.0;
      removalRate_ += (rate - removalRate_) * a;
    }
  }
  haveFrame_ = true;
  last_ = state;
  targetSpin_ = state.spinning ? 1.0 : 0.0;
  tissue_ = std::isfinite(state.hardness) ? std::clamp(std::sqrt(std::max(state.hardness, 0.0)), 0.2, 3.0) : 1.0;
  double x = 0.0;
  if (p_.referenceRemovalRate > 0.0) x += removalRate_ / p_.referenceRemovalRate;
  if (state.contacts > 0 && p_.referenceForce > 0.0 && std::isfinite(state.force)) x += state.force / p_.referenceForce;
  targetLoad_ = state.spinning && std::isfinite(x) ? x / (1.0 + x) : 0.0;
}

void MillingSound::finish(double endTime, std::vector<std::int16_t>& out) {
  if (finished_) return;
  render(endTime, out);
  finished_ = true;
}

}  // namespace millsim
