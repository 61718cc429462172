// SafetyLayer: clamp, soft-start ramp, NaN/Inf zeroing, watchdog, hiccup
// blend and ramp restart, invalid limits. Times are synthetic: no clocks, no timing asserts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "millsim/driver/SafetyLayer.h"

using namespace millsim;

namespace {

constexpr double kDt = 0.001;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

SafetyLimits noRamp() {
  SafetyLimits l;
  l.forceLimit = 10.0;
  l.torqueLimit = 0.5;
  l.softStartTime = 0.0;
  l.watchdogTimeout = 0.005;
  return l;
}

// The defaults' soft start and ARES's 10 ms hold.
SafetyLimits aresLike() {
  SafetyLimits l = noRamp();
  l.softStartTime = 0.25;
  l.deviceHold = 0.010;
  return l;
}

}  // namespace

TEST(SafetyLayer, PassesSmallWrenchesUnchanged) {
  SafetyLayer s(noRamp());
  const SafeWrench w = s.filter({1.0, -2.0, 3.0}, {0.1, 0.0, -0.2}, 0.0, 0.0);
  EXPECT_EQ(w.force, glm::dvec3(1.0, -2.0, 3.0));
  EXPECT_EQ(w.torque, glm::dvec3(0.1, 0.0, -0.2));
  EXPECT_EQ(w.events, 0u);
}

TEST(SafetyLayer, ClampsMagnitudeKeepingDirection) {
  SafetyLayer s(noRamp());
  const SafeWrench w = s.filter({30.0, 40.0, 0.0}, {0.0, 0.0, -2.0}, 0.0, 0.0);
  EXPECT_NEAR(glm::length(w.force), 10.0, 1e-12);
  EXPECT_NEAR(w.force.x / w.force.y, 0.75, 1e-12);
  EXPECT_NEAR(glm::length(w.torque), 0.5, 1e-12);
  EXPECT_LT(w.torque.z, 0.0);
  EXPECT_TRUE(w.events & kSafetyClamped);
  EXPECT_EQ(s.counters().clamped, 1u);
  // Only the torque over its limit: still one clamped frame.
  const SafeWrench w2 = s.filter({1.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, kDt, kDt);
  EXPECT_EQ(w2.force, glm::dvec3(1.0, 0.0, 0.0));
  EXPECT_NEAR(w2.torque.y, 0.5, 1e-12);
  EXPECT_EQ(s.counters().clamped, 2u);
}

TEST(SafetyLayer, HugeFiniteForceIsClampedNotPassed) {
  SafetyLayer s(noRamp());
  const SafeWrench w = s.filter({1e300, 1e300, 0.0}, {0.0, 0.0, 0.0}, 0.0, 0.0);
  EXPECT_LE(glm::length(w.force), 10.0 + 1e-9);
  EXPECT_TRUE(std::isfinite(w.force.x));
}

TEST(SafetyLayer, SoftStartRampsLinearlyFromZero) {
  SafetyLimits l = noRamp();
  l.softStartTime = 0.1;
  SafetyLayer s(l);
  double previous = -1.0;
  for (int i = 0; i <= 120; ++i) {
    const double t = 5.0 + i * kDt;  // the run's clock need not start at zero
    const SafeWrench w = s.filter({0.0, 0.0, 4.0}, {0.0, 0.2, 0.0}, t, t);
    const double expected = 4.0 * std::min(1.0, i * kDt / 0.1);
    EXPECT_NEAR(w.force.z, expected, 1e-9) << "frame " << i;
    EXPECT_NEAR(w.torque.y, 0.2 * expected / 4.0, 1e-9) << "frame " << i;
    EXPECT_GE(w.force.z, previous);
    previous = w.force.z;
    if (i < 99 || i > 101) {
      EXPECT_EQ(bool(w.events & kSafetyRamping), i < 100) << "frame " << i;
    }
  }
}

TEST(SafetyLayer, RampHappensBeforeClamp) {
  SafetyLimits l = noRamp();
  l.softStartTime = 0.1;
  l.watchdogTimeout = 1.0;  // a 50 ms step between frames is not late here
  SafetyLayer s(l);
  s.filter({0, 0, 100.0}, {}, 0.0, 0.0);
  // Halfway through the ramp 100 N is scaled to 50 N, then clamped to 10 N.
  const SafeWrench w = s.filter({0, 0, 100.0}, {}, 0.05, 0.05);
  EXPECT_NEAR(w.force.z, 10.0, 1e-9);
  EXPECT_TRUE(w.events & kSafetyClamped);
  EXPECT_TRUE(w.events & kSafetyRamping);
}

TEST(SafetyLayer, NaNOrInfAnywhereZeroesTheFrameAndRestartsTheRamp) {
  SafetyLimits l = noRamp();
  l.softStartTime = 0.01;
  SafetyLayer s(l);
  double t = 0.0;
  for (int i = 0; i < 20; ++i, t += kDt) s.filter({0, 0, 1.0}, {}, t, t);  // ramp done
  EXPECT_NEAR(s.filter({0, 0, 1.0}, {}, t, t).force.z, 1.0, 1e-12);
  const glm::dvec3 bad[] = {{kNaN, 0, 0}, {0, kInf, 0}, {0, 0, -kInf}};
  std::uint64_t n = 0;
  for (const glm::dvec3& b : bad) {
    for (int which = 0; which < 2; ++which) {
      t += kDt;
      const SafeWrench w = which == 0 ? s.filter(b, {0.1, 0, 0}, t, t) : s.filter({1, 0, 0}, b, t, t);
      EXPECT_EQ(w.force, glm::dvec3(0.0));
      EXPECT_EQ(w.torque, glm::dvec3(0.0));
      EXPECT_TRUE(w.events & kSafetyNonFinite);
      EXPECT_EQ(s.counters().nonFinite, ++n);
    }
  }
  // The next good frame starts a new ramp from the last bad one.
  t += kDt;
  const SafeWrench w = s.filter({0, 0, 1.0}, {}, t, t);
  EXPECT_NEAR(w.force.z, 0.1, 1e-9);
  EXPECT_TRUE(w.events & kSafetyRamping);
}

TEST(SafetyLayer, LateFrameTripsTheWatchdogAndRestartsTheRamp) {
  SafetyLimits l = noRamp();
  l.softStartTime = 0.01;
  SafetyLayer s(l);
  double t = 0.0;
  for (int i = 0; i < 20; ++i, t += kDt) s.filter({0, 0, 2.0}, {}, t, t);
  // The loop stalls for 20 ms.
  t += 0.020;
  SafeWrench w = s.filter({0, 0, 2.0}, {0, 0.1, 0}, t, t);
  EXPECT_EQ(w.force, glm::dvec3(0.0));
  EXPECT_EQ(w.torque, glm::dvec3(0.0));
  EXPECT_TRUE(w.events & kSafetyWatchdog);
  EXPECT_EQ(s.counters().watchdogTrips, 1u);
  // On time again: ramps up from zero over the outage (22 ms since the last
  // output) squared over recoveryScale, 4.84 ms (at most softStartTime).
  t += kDt;
  w = s.filter({0, 0, 2.0}, {}, t, t);
  EXPECT_NEAR(w.force.z, 2.0 * kDt / (0.022 * 0.022 / 0.1), 1e-9);
  for (int i = 0; i < 10; ++i) t += kDt, w = s.filter({0, 0, 2.0}, {}, t, t);
  EXPECT_NEAR(w.force.z, 2.0, 1e-12);
  EXPECT_FALSE(w.events & kSafetyRamping);
}

// A preemption between 5 and 10 ms: the device held the last wrench, so the
// output blends from it to the new one over as long as the stall.
TEST(SafetyLayer, AHiccupBlendsFromTheHeldWrenchInsteadOfDropping) {
  SafetyLimits l = noRamp();
  l.deviceHold = 0.010;  // ARES
  SafetyLayer s(l);
  double t = 0.0;
  for (int i = 0; i < 20; ++i, t += kDt) s.filter({0, 0, 2.0}, {0.1, 0, 0}, t, t);
  t += 0.006 - kDt;  // 6 ms after the last frame
  SafeWrench w = s.filter({0, 0, 3.0}, {0.2, 0, 0}, t, t);
  EXPECT_EQ(w.force, glm::dvec3(0, 0, 2.0)) << "the late frame sends what the device held";
  EXPECT_EQ(w.torque, glm::dvec3(0.1, 0, 0));
  EXPECT_TRUE(w.events & kSafetyHiccup);
  EXPECT_FALSE(w.events & kSafetyWatchdog) << "a blended frame is not a zeroed one";
  EXPECT_EQ(s.counters().hiccups, 1u);
  EXPECT_EQ(s.counters().watchdogTrips, 0u);
  for (int i = 1; i <= 10; ++i) {
    t += kDt;
    w = s.filter({0, 0, 3.0}, {0.2, 0, 0}, t, t);
    const double b = std::min(1.0, i * kDt / 0.006);
    EXPECT_NEAR(w.force.z, 2.0 + b, 1e-9) << "frame " << i;
    EXPECT_NEAR(w.torque.x, 0.1 + 0.1 * b, 1e-9) << "frame " << i;
    if (i != 6) {
      EXPECT_EQ(bool(w.events & kSafetyRamping), i < 6) << "frame " << i;
    }
  }
  EXPECT_EQ(s.counters().hiccups, 1u);
  // Past the device's hold the device has dropped the wrench: zeroed.
  t += 0.011;
  w = s.filter({0, 0, 3.0}, {}, t, t);
  EXPECT_EQ(w.force, glm::dvec3(0.0));
  EXPECT_TRUE(w.events & kSafetyWatchdog);
}

// A device that does not say how long it holds a wrench: every late frame is zeroed.
TEST(SafetyLayer, WithoutAKnownDeviceHoldALateFrameIsZeroed) {
  SafetyLayer s(noRamp());
  double t = 0.0;
  for (int i = 0; i < 20; ++i, t += kDt) s.filter({0, 0, 2.0}, {}, t, t);
  t += 0.006 - kDt;
  const SafeWrench w = s.filter({0, 0, 2.0}, {}, t, t);
  EXPECT_EQ(w.force, glm::dvec3(0.0));
  EXPECT_TRUE(w.events & kSafetyWatchdog);
  EXPECT_EQ(s.counters().hiccups, 0u);
}

// Longer than the device's hold: the device has dropped the wrench (ARES
// does after 10 ms), so the output restarts from zero, over the outage
// squared over recoveryScale (0.1 s), and never over more than the soft start.
TEST(SafetyLayer, AStallZeroesTheOutputAndRampsBackTheSoonerTheShorterItWas) {
  for (const double stall : {0.020, 0.100}) {
    SafetyLayer s(aresLike());
    double t = 0.0;
    for (int i = 0; i < 300; ++i, t += kDt) s.filter({0, 0, 2.0}, {}, t, t);  // the soft start is over
    t += stall - kDt;
    const double lastOutput = t - stall;
    SafeWrench w = s.filter({0, 0, 2.0}, {}, t, t);
    EXPECT_EQ(w.force, glm::dvec3(0.0));
    EXPECT_TRUE(w.events & kSafetyWatchdog);
    const double tripped = t;
    const double outage = t + kDt - lastOutput;
    const double ramp = std::min(0.25, outage * outage / 0.1);
    for (int i = 1; i <= 300; ++i) {
      t += kDt;
      w = s.filter({0, 0, 2.0}, {}, t, t);
      EXPECT_NEAR(w.force.z, 2.0 * std::min(1.0, (t - tripped) / ramp), 1e-9) << stall << " s stall, frame " << i;
    }
  }
}

// The soft start protects a run that starts inside material: a hiccup or a
// stall during it must not end it early. The ramp after the stall rises from
// zero to end when the soft start would have: below the soft start's line.
TEST(SafetyLayer, AStallDuringTheSoftStartDoesNotShortenIt) {
  SafetyLayer s(aresLike());
  double t = 0.0;
  for (int i = 0; i < 50; ++i, t += kDt) s.filter({0, 0, 2.0}, {}, t, t);
  t += 0.020 - kDt;
  EXPECT_EQ(s.filter({0, 0, 2.0}, {}, t, t).force, glm::dvec3(0.0));
  const double tripped = t;
  t += kDt;
  EXPECT_NEAR(s.filter({0, 0, 2.0}, {}, t, t).force.z, 2.0 * kDt / (0.25 - tripped), 1e-9)
      << "a ramp to the soft start's end, not of 4.4 ms";
  // A hiccup during the new ramp blends from what was sent towards the ramped
  // wrench: still below the ramp's line, never a step.
  t += 0.007;
  const double sent = 2.0 * (t - 0.007 - tripped) / (0.25 - tripped);
  const SafeWrench w = s.filter({0, 0, 2.0}, {}, t, t);
  EXPECT_NEAR(w.force.z, sent, 1e-9);
  EXPECT_TRUE(w.events & kSafetyHiccup);
}

// A loaded host stalls again and again (CI: 92 trips in 5 s). Each stall
// restarting the whole soft start kept the output ramping all run long, at
// 55 % of the force at best; the ramps must still end with the soft start.
TEST(SafetyLayer, StallsOneAfterAnotherDoNotMakeTheSoftStartEndless) {
  SafetyLayer s(aresLike());
  double t = 0.0;
  SafeWrench w;
  for (int stall = 0; stall < 12; ++stall) {  // a 12 ms stall every 40 ms, for 0.48 s
    for (int i = 0; i < 28; ++i, t += kDt) w = s.filter({0, 0, 2.0}, {}, t, t);
    t += 0.012 - kDt;
    EXPECT_EQ(s.filter({0, 0, 2.0}, {}, t, t).force, glm::dvec3(0.0)) << "stall " << stall;
    t += kDt;
  }
  EXPECT_EQ(s.counters().watchdogTrips, 12u);
  for (int i = 0; i < 28; ++i, t += kDt) w = s.filter({0, 0, 2.0}, {}, t, t);
  // 28 ms after the last stall the output is whole: its own ramp, 1.7 ms, is long over.
  EXPECT_NEAR(w.force.z, 2.0, 1e-12);
  EXPECT_FALSE(w.events & kSafetyRamping);
}

TEST(SafetyLayer, StaleDeviceSampleTripsTheWatchdog) {
  SafetyLayer s(noRamp());
  double t = 0.0;
  const double sample = 0.0;  // the device stopped delivering at t = 0
  int zeroed = 0;
  for (int i = 0; i < 10; ++i, t += kDt) {
    const SafeWrench w = s.filter({1, 0, 0}, {}, t, sample);
    if (w.events & kSafetyWatchdog) {
      ++zeroed;
      EXPECT_EQ(w.force, glm::dvec3(0.0));
    } else {
      EXPECT_EQ(w.force.x, 1.0);
    }
    EXPECT_EQ(bool(w.events & kSafetyWatchdog), t - sample > 0.005 + 1e-12) << "t " << t;
  }
  EXPECT_EQ(zeroed, 4);  // t = 6..9 ms
  EXPECT_EQ(s.counters().watchdogTrips, 4u);
}

TEST(SafetyLayer, NonFiniteTimeTripsTheWatchdogAndDoesNotDisableTheRamp) {
  SafetyLimits l = noRamp();
  l.softStartTime = 0.1;
  SafetyLayer s(l);
  EXPECT_TRUE(s.filter({0, 0, 5.0}, {}, kNaN, 0.0).events & kSafetyWatchdog);
  // The first finite frame after a bad clock must still start from zero.
  const SafeWrench w = s.filter({0, 0, 5.0}, {}, 0.0, 0.0);
  EXPECT_EQ(w.force, glm::dvec3(0.0));
  EXPECT_NEAR(s.filter({0, 0, 5.0}, {}, 0.05, 0.05).force.z, 0.0, 1e-12) << "a 50 ms gap is late";
  EXPECT_TRUE(s.filter({0, 0, 5.0}, {}, 0.051, kNaN).events & kSafetyWatchdog);
  const SafeWrench after = s.filter({0, 0, 5.0}, {}, 0.052, 0.052);
  EXPECT_NEAR(after.force.z, 5.0 * 0.001 / 0.1, 1e-9);
}

TEST(SafetyLayer, RejectsInvalidLimitsNamingTheValue) {
  auto expectThrow = [](SafetyLimits l, const char* name) {
    try {
      SafetyLayer s(l);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  struct Limit {
    double SafetyLimits::*field;
    const char* name;
    bool zeroAllowed;
  };
  const Limit limits[] = {{&SafetyLimits::forceLimit, "forceLimit", false},
                          {&SafetyLimits::torqueLimit, "torqueLimit", false},
                          {&SafetyLimits::watchdogTimeout, "watchdogTimeout", false},
                          {&SafetyLimits::recoveryScale, "recoveryScale", false},
                          {&SafetyLimits::softStartTime, "softStartTime", true},
                          {&SafetyLimits::deviceHold, "deviceHold", true}};
  for (const Limit& limit : limits)
    for (double bad : {0.0, -0.1, -1.0, kNaN, kInf}) {
      if (bad == 0.0 && limit.zeroAllowed) continue;
      SafetyLimits l = noRamp();
      l.*limit.field = bad;
      expectThrow(l, limit.name);
    }
  SafetyLimits ok = noRamp();
  ok.softStartTime = 0.0;
  EXPECT_NO_THROW(SafetyLayer{ok});
}
