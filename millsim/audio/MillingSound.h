#pragma once
// The milling sound (paper §7): a deterministic synthesizer of a spinning burr.
// It is fed one BurrState per haptic frame, in order, and writes mono 16-bit
// samples for the time each frame covers, so a run of T seconds gives
// round(T · sampleRate) samples. The burr whines quietly while it spins in air,
// is silent while the milling switch is off, and when it cuts the motor slows
// under load (lower pitch) and a louder band of grinding noise comes in, both
// following the removal rate and the contact force (docs/algorithms.md,
// "The milling sound").
//
// Bit-reproducible: no wall clock, a seeded generator, and all state advances
// per sample or per frame, so how frames or samples are batched by the caller
// changes nothing. Runs on the scene thread (or a replay's), never on the
// haptic one; it allocates only when the caller's output vector grows.
#include <cstdint>
#include <vector>

namespace millsim {

struct FrameRecord;

// What the sound needs of one haptic frame.
struct BurrState {
  double t = 0.0;              // s since the run started (the frame's start)
  bool spinning = false;       // the milling switch (FrameRecord::button)
  double removedVolume = 0.0;  // m³ milled so far (cumulative)
  double force = 0.0;          // N, |force| sent to the device
  int contacts = 0;
  double hardness = 1.0;       // of the tissue the burr cuts (HapticOutput::cutHardness)
};
BurrState burrStateOf(const FrameRecord& record);

// How the burr's material sounds; each frame's tissue (BurrState::hardness)
// scales both by √hardness, so enamel grinds louder, brighter and slows the
// motor more than dentin, and the pulp is nearly silent.
struct BurrMaterial {
  double hardness = 1.0;    // scales the grinding noise and how much the motor slows under load
  double brightness = 1.0;  // scales the centre frequency of the grinding noise
};

struct MillingSoundParameters {
  int sampleRate = 44100;            // Hz
  double whineFrequency = 900.0;     // Hz: the unloaded motor's fundamental (a ~54 000 rpm contra-angle)
  double airLevel = 0.06;            // full scale: the whine's peak amplitude spinning in air
  double loadedToneGain = 2.0;       // the whine grows by 1 + this · load when cutting
  double noiseLevel = 0.3;           // full scale: the grinding noise at load 1
  double noiseFrequency = 3200.0;    // Hz: the grinding noise's band centre (band-pass, Q ≈ 1.2)
  double pitchDrop = 0.3;            // the motor's speed falls by this fraction at load 1
  double referenceRemovalRate = 1e-9;  // m³/s (1 mm³/s) that, alone, gives load 1/2
  double referenceForce = 2.0;         // N that, alone, gives load 1/2
  double removalSmoothing = 0.02;      // s: time constant of the removal-rate estimate
  double spinUp = 0.03, spinDown = 0.08;   // s: motor envelope (attack, release)
  double loadAttack = 0.005, loadRelease = 0.03;  // s: cutting envelope
  std::uint64_t seed = 0x4d696c6c53696dULL;  // the noise generator's seed ("MillSim")
  BurrMaterial material;
};

class MillingSound {
public:
  explicit MillingSound(const MillingSoundParameters& parameters = {});

  // The frame starting at state.t: first appends the samples up to state.t
  // (from the previous frame's state; silence before the first frame), then
  // holds this state until the next call. Frames must come in time order.
  void addFrame(const BurrState& state, std::vector<std::int16_t>& out);
  // Appends the samples up to endTime (the end of the last frame: its t plus
  // one period) and stops. Later calls append nothing.
  void finish(double endTime, std::vector<std::int16_t>& out);

  std::int64_t samples() const { return written_; }
  const MillingSoundParameters& parameters() const { return p_; }
  // The load (0…1) the last frame asked for: smoothed removal rate and force.
  double targetLoad() const { return targetLoad_; }

private:
  void render(double untilTime, std::vector<std::int16_t>& out);
  double nextNoise();

  MillingSoundParameters p_;
  std::int64_t written_ = 0;
  bool finished_ = false;
  bool haveFrame_ = false;
  BurrState last_;
  double removalRate_ = 0.0;  // m³/s, smoothed per frame
  double targetSpin_ = 0.0, targetLoad_ = 0.0;
  double tissue_ = 1.0;  // √ of the cut tissue's hardness, clamped to [0.2, 3]
  // Per-sample state.
  double spin_ = 0.0, load_ = 0.0;
  double phase_ = 0.0, wobblePhase_ = 0.0;
  double bandLow_ = 0.0, bandBand_ = 0.0;  // state-variable filter
  std::uint64_t rng_;
  double spinUpCoef_, spinDownCoef_, loadAttackCoef_, loadReleaseCoef_;
};

}  // namespace millsim
