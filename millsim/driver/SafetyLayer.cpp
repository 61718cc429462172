#include "millsim/driver/SafetyLayer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace millsim {

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void requirePositive(double v, const char* name, bool allowZero) {
  if (!std::isfinite(v) || v < 0.0 || (!allowZero && v == 0.0))
    throw std::invalid_argument(std::string("safety limit ") + name + " = " + std::to_string(v) +
                                (allowZero ? " (expected a finite value ≥ 0)" : " (expected a finite value > 0)"));
}

// Scales v down to length `limit` if longer; true if it did.
bool clampTo(glm::dvec3& v, double limit) {
  // Scaled by the largest component first so that huge finite inputs (1e200 N)
  // are clamped along their direction instead of overflowing to a zero vector.
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (m == 0.0) return false;
  const double len = m * glm::length(v / m);
  if (len <= limit) return false;
  v *= limit / len;
  return true;
}

}  // namespace

SafetyLayer::SafetyLayer(const SafetyLimits& limits) : limits_(limits) {
  requirePositive(limits.forceLimit, "forceLimit", false);
  requirePositive(limits.torqueLimit, "torqueLimit", false);
  requirePositive(limits.softStartTime, "softStartTime", true);
  requirePositive(limits.watchdogTimeout, "watchdogTimeout", false);
  requirePositive(limits.recoveryScale, "recoveryScale", false);
  requirePositive(limits.deviceHold, "deviceHold", true);
}

void SafetyLayer::setLimits(double forceLimit, double torqueLimit) {
  if (std::isfinite(forceLimit) && forceLimit > 0.0) limits_.forceLimit = forceLimit;
  if (std::isfinite(torqueLimit) && torqueLimit > 0.0) limits_.torqueLimit = torqueLimit;
}

SafeWrench SafetyLayer::trip(double t, std::uint32_t event, bool full) {
  if (!tripped_) {
    tripped_ = true;
    interruptedEnd_ = lastOutput_ - rampStart_ < rampLength_ ? rampStart_ + rampLength_
                                                             : -std::numeric_limits<double>::infinity();
  }
  fullRamp_ = fullRamp_ || full;
  rampStart_ = t;
  blendLength_ = 0.0;
  sentForce_ = sentTorque_ = glm::dvec3(0.0);
  SafeWrench out;
  out.events = event;
  return out;
}

SafeWrench SafetyLayer::filter(const glm::dvec3& force, const glm::dvec3& torque, double t, double sampleTime) {
  // A non-finite clock is a late frame that must not become the reference for
  // the next watchdog check or ramp (NaN comparisons are all false: a NaN
  // rampStart_ would skip the soft start). Its outage cannot be measured, so
  // the whole soft start follows.
  if (!std::isfinite(t) || !std::isfinite(sampleTime)) {
    ++counters_.watchdogTrips;
    if (!std::isfinite(t)) {
      started_ = false;  // the next finite frame restarts the ramp from itself
      sentForce_ = sentTorque_ = glm::dvec3(0.0);
      SafeWrench out;
      out.events = kSafetyWatchdog;
      return out;
    }
    started_ = true;
    previousFrame_ = t;
    return trip(t, kSafetyWatchdog, true);
  }
  if (!started_) {
    started_ = true;
    rampStart_ = lastOutput_ = previousFrame_ = t;
    rampLength_ = limits_.softStartTime;
    blendLength_ = 0.0;
    tripped_ = fullRamp_ = false;
  }
  const double gap = t - previousFrame_, timeout = limits_.watchdogTimeout;
  previousFrame_ = t;
  const bool stale = t - sampleTime > timeout;
  const bool stalled = gap > timeout;
  const bool hiccup = stalled && !stale && !tripped_ && gap <= limits_.deviceHold;
  if (stale || (stalled && !hiccup)) {
    ++counters_.watchdogTrips;
    return trip(t, kSafetyWatchdog, false);
  }
  if (!finite(force) || !finite(torque)) {
    ++counters_.nonFinite;
    return trip(t, kSafetyNonFinite, true);
  }
  SafeWrench out;
  if (hiccup) {
    ++counters_.hiccups;
    out.events |= kSafetyHiccup;
    blendForce_ = sentForce_;
    blendTorque_ = sentTorque_;
    blendStart_ = t;
    blendLength_ = gap;
  }
  if (tripped_) {
    const double soft = limits_.softStartTime;
    const double kept = interruptedEnd_ - rampStart_;  // the interrupted ramp's end (header)
    const double outage = t - lastOutput_;
    rampLength_ = fullRamp_ ? soft : std::min(soft, std::max(outage * outage / limits_.recoveryScale, kept));
    tripped_ = fullRamp_ = false;
  }
  lastOutput_ = t;
  double gain = 1.0;
  if (t - rampStart_ < rampLength_) {
    gain = std::clamp((t - rampStart_) / rampLength_, 0.0, 1.0);
    out.events |= kSafetyRamping;
  }
  out.force = force * gain;
  out.torque = torque * gain;
  if (t - blendStart_ < blendLength_) {
    const double b = std::clamp((t - blendStart_) / blendLength_, 0.0, 1.0);
    out.force = blendForce_ + b * (out.force - blendForce_);
    out.torque = blendTorque_ + b * (out.torque - blendTorque_);
    out.events |= kSafetyRamping;
  }
  // Two clamps, counted once per frame.
  const bool f = clampTo(out.force, limits_.forceLimit);
  const bool q = clampTo(out.torque, limits_.torqueLimit);
  if (f || q) {
    ++counters_.clamped;
    out.events |= kSafetyClamped;
  }
  sentForce_ = out.force;
  sentTorque_ = out.torque;
  return out;
}

}  // namespace millsim
