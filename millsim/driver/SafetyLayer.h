#pragma once
// SafetyLayer: the last thing between a renderer's wrench and any device,
// simulated or real. Every frame's output passes through filter():
//  - NaN or Inf anywhere → zero output, and the soft start begins again;
//  - a late frame (the loop or the device sample older than the watchdog
//    timeout) → zero output, and the soft start begins again;
//  - soft start: the output is scaled by a ramp from 0 to 1 over
//    softStartTime after the run starts and after every trip, so the hand
//    never feels a step when forces resume;
//  - the magnitudes are clamped to forceLimit and torqueLimit.
// It runs on the haptic thread: no allocation, no locks.
#include <cstdint>

#include <glm/vec3.hpp>

namespace millsim {

struct SafetyLimits {
  double forceLimit = 10.0;       // N
  double torqueLimit = 0.5;       // N·m
  double softStartTime = 0.25;    // s; 0 = no ramp
  double watchdogTimeout = 0.005; // s; frames or samples older than this zero the output
};

// What the layer did to a frame, as bits (also written to the log's flags column).
enum SafetyEvent : std::uint32_t {
  kSafetyNonFinite = 1u << 8,
  kSafetyWatchdog = 1u << 9,
  kSafetyClamped = 1u << 10,
  kSafetyRamping = 1u << 11,
  // The loop's last row: the device was stopped and its output zeroed.
  kSafetyStopped = 1u << 12,
};

struct SafeWrench {
  glm::dvec3 force{0.0};
  glm::dvec3 torque{0.0};
  std::uint32_t events = 0;
};

// Frames affected, per cause (a 20 ms stall at 1 kHz counts ~15 watchdog frames).
struct SafetyCounters {
  std::uint64_t nonFinite = 0, watchdogTrips = 0, clamped = 0;
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
  SafetyLimits limits_;
  SafetyCounters counters_;
  double rampStart_ = 0.0;     // time the current ramp began
  double previousFrame_ = 0.0;
  bool started_ = false;
};

}  // namespace millsim
