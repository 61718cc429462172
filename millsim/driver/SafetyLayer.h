#pragma once
// SafetyLayer: the last thing between a renderer's wrench and any device,
// simulated or real. Every frame's output passes through filter():
//  - NaN or Inf anywhere → zero output, then the whole soft start;
//  - a stale device sample (older than the watchdog timeout) or a loop stall
//    longer than the device's hold → zero output (where the device is, or
//    what it did meanwhile, is unknown; it has dropped the wrench itself),
//    then a ramp from zero lasting T²/recoveryScale for an outage T, at most
//    softStartTime;
//  - a hiccup: a loop frame later than the timeout but within the device's
//    hold (deviceHold; ARES holds the last wrench for 10 ms), on a fresh
//    sample. The device has applied the last wrench meanwhile, so the output
//    blends from it to the new one over as long as the stall instead of
//    dropping: a 6 ms preemption neither takes the wall away nor steps it;
//  - soft start: the output is scaled by a ramp from 0 to 1 over
//    softStartTime after the run starts, so the hand never feels a step when
//    forces begin;
//  - the magnitudes are clamped to forceLimit and torqueLimit.
// They are counted as non-finite frames, watchdog trips and hiccups.
// It runs on the haptic thread: no allocation, no locks.
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace millsim {

struct SafetyLimits {
  double forceLimit = 10.0;       // N
  double torqueLimit = 0.5;       // N·m
  double softStartTime = 0.25;    // s; 0 = no ramp
  double watchdogTimeout = 0.005; // s; older samples and longer stalls trip the watchdog
  // s; after an outage T (the time since the last frame with output) the
  // ramp back from zero lasts T²/recoveryScale, at most softStartTime. A
  // pressing hand falls in until the force is back, by about T², and so does
  // the kick a ramp softens: short outages come back almost at once (26 ms:
  // 7 ms), long ones gently (0.1 s: 0.1 s). Measured against other rules in
  // docs/algorithms.md (Safety layer).
  double recoveryScale = 0.1;
  // How long (s) the device keeps applying the last wrench without a new one
  // (HapticsDevice::outputHoldTime; 0: unknown). Late frames within it are hiccups.
  double deviceHold = 0.0;
};

// What the layer did to a frame, as bits (also written to the log's flags column).
enum SafetyEvent : std::uint32_t {
  kSafetyNonFinite = 1u << 8,
  kSafetyWatchdog = 1u << 9,
  kSafetyClamped = 1u << 10,
  kSafetyRamping = 1u << 11,
  // The loop's last row: the device was stopped and its output zeroed.
  kSafetyStopped = 1u << 12,
  // A late frame on a fresh pose whose output was blended from the held
  // wrench, not zeroed (a hiccup; kSafetyWatchdog marks zeroed frames).
  kSafetyHiccup = 1u << 13,
  // The device outputs force only (a Touch, an omega.6, a Falcon): the
  // frame's torque went through the layer and into the log, not to the device.
  kSafetyTorqueNotOutput = 1u << 14,
};

struct SafeWrench {
  glm::dvec3 force{0.0};
  glm::dvec3 torque{0.0};
  std::uint32_t events = 0;
};

// Frames affected, per cause (a 20 ms stall at 1 kHz counts ~15 watchdog
// frames). watchdogTrips: frames zeroed for a stale pose or a long stall;
// hiccups: late frames blended from the held wrench instead.
struct SafetyCounters {
  std::uint64_t nonFinite = 0, watchdogTrips = 0, clamped = 0, hiccups = 0;
};

class SafetyLayer {
public:
  // Throws std::invalid_argument for limits that are not finite and positive.
  explicit SafetyLayer(const SafetyLimits& limits);

  // t: this frame's time (s); sampleTime: when the device pose used for this
  // frame was read (s, same clock). Time must not run backwards.
  SafeWrench filter(const glm::dvec3& force, const glm::dvec3& torque, double t, double sampleTime);

  const SafetyLimits& limits() const { return limits_; }
  const SafetyCounters& counters() const { return counters_; }
  // New force and torque limits from the next frame on (a live field change).
  // Values that are not finite and positive are ignored: the old limits stay.
  void setLimits(double forceLimit, double torqueLimit);

private:
  // A frame without output; `full`: the next ramp is the whole soft start.
  SafeWrench trip(double t, std::uint32_t event, bool full);

  SafetyLimits limits_;
  SafetyCounters counters_;
  double rampStart_ = 0.0;   // time the current ramp from zero began (the last frame without output)
  double rampLength_ = 0.0;  // s; the current ramp's length
  double lastOutput_ = 0.0;  // time of the last frame that had output
  double previousFrame_ = 0.0;
  glm::dvec3 sentForce_{0.0}, sentTorque_{0.0};  // the last frame's output, which the device holds
  glm::dvec3 blendForce_{0.0}, blendTorque_{0.0};  // a hiccup's blend starts from these
  double blendStart_ = 0.0, blendLength_ = 0.0;    // s
  bool started_ = false;
  bool tripped_ = false;          // frames without output since lastOutput_
  bool fullRamp_ = false;         // ... one of them asks for the whole soft start
  // ... and the end of the ramp they cut short (-inf: none). The ramp after
  // them ends no earlier: a trip never shortens a ramp under way, nor, as a
  // whole new ramp each time would, makes frequent trips an endless ramp.
  double interruptedEnd_ = -std::numeric_limits<double>::infinity();
};

}  // namespace millsim
