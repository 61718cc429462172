#include "millsim/driver/SafetyLayer.h"

#include <algorithm>
#include <cmath>
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
}

void SafetyLayer::setLimits(double forceLimit, double torqueLimit) {
  if (std::isfinite(forceLimit) && forceLimit > 0.0) limits_.forceLimit = forceLimit;
  if (std::isfinite(torqueLimit) && torqueLimit > 0.0) limits_.torqueLimit = torqueLimit;
}

SafeWrench SafetyLayer::filter(const glm::dvec3& force, const glm::dvec3& torque, double t, double sampleTime) {
  SafeWrench out;
  // A non-finite clock is a late frame that must not become the reference for
  // the next watchdog check or ramp (NaN comparisons are all false: a NaN
  // rampStart_ would skip the soft start).
  if (!std::isfinite(t) || !std::isfinite(sampleTime)) {
    ++counters_.watchdogTrips;
    out.events |= kSafetyWatchdog;
    if (std::isfinite(t)) {
      previousFrame_ = t;
      rampStart_ = t;
      started_ = true;
    } else {
      started_ = false;  // the next finite frame restarts the ramp from itself
    }
    return out;
  }
  if (!started_) {
    started_ = true;
    rampStart_ = t;
    previousFrame_ = t;
  }
  const bool late = t - previousFrame_ > limits_.watchdogTimeout || t - sampleTime > limits_.watchdogTimeout;
  previousFrame_ = t;
  if (late) {
    ++counters_.watchdogTrips;
    out.events |= kSafetyWatchdog;
    rampStart_ = t;
    return out;
  }
  if (!finite(force) || !finite(torque)) {
    ++counters_.nonFinite;
    out.events |= kSafetyNonFinite;
    rampStart_ = t;
    return out;
  }
  double gain = 1.0;
  if (limits_.softStartTime > 0.0 && t - rampStart_ < limits_.softStartTime) {
    gain = std::clamp((t - rampStart_) / limits_.softStartTime, 0.0, 1.0);
    out.events |= kSafetyRamping;
  }
  out.force = force * gain;
  out.torque = torque * gain;
  // Two clamps, counted once per frame.
  const bool f = clampTo(out.force, limits_.forceLimit);
  const bool q = clampTo(out.torque, limits_.torqueLimit);
  if (f || q) {
    ++counters_.clamped;
    out.events |= kSafetyClamped;
  }
  return out;
}

}  // namespace millsim
