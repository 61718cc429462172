#pragma once
// DeviceDriver: the haptic thread's side of a device. A device node
// (TrajectoryDevice, HandDevice, AresDevice, or a plugin's) opens one driver
// per run on the scene thread; from then on only the haptic thread calls it,
// once per frame: read(), the renderer steps, write().
//
// Poses and wrenches here are the device's raw frame; the loop applies the
// node's calibration (HapticsDevice::positionCalibration/orientationCalibration)
// on the way in and its inverse rotation on the way out.
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/vec3.hpp>

#include "millsim/math/Pose.h"

namespace millsim {

// A device that cannot be opened or failed; the message is for the user.
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DeviceReading {
  Pose pose;            // raw burr-centre pose (m, unit quaternion)
  bool button = false;  // milling switch
  bool valid = true;    // false: no fresh sample this frame (the loop holds the last pose)
};

// What `millsim check` says of a device without running it: whether it can
// be opened here (asked of its library, no force enabled) and what it can
// render, where the library tells.
struct DeviceProbe {
  bool opens = false;
  std::string what;           // what would open ("Touch (...), 3-DOF force output"), or why nothing would
  double maxStiffness = 0.0;  // N/m the device renders stably (its library's nominal figure); 0: not told
  double maxForce = 0.0;      // N; 0: not told
};

// Counters a driver keeps for the log and the run summary.
struct DeviceCounters {
  std::uint64_t framesSent = 0;
  std::uint64_t framesReceived = 0;
  std::uint64_t sequenceGaps = 0;    // device frames missing between two received ones
  std::uint64_t checksumErrors = 0;  // corrupt device frames dropped
  std::uint64_t transferErrors = 0;  // failed or timed-out transfers
};

class DeviceDriver {
public:
  virtual ~DeviceDriver() = default;

  // The state for the frame at loop time t (s since the run started; dt is the
  // nominal frame period). Simulated devices compute it; hardware reads it.
  // Never blocks longer than one frame period.
  virtual DeviceReading read(double t, double dt) = 0;
  // Sends the frame's wrench: finite and already clamped by the safety layer.
  // Force in N, torque in N·m about the burr centre, both in the raw frame.
  virtual void write(const glm::dvec3& force, const glm::dvec3& torque) = 0;

  // True once the device is gone (unplugged, fatal transfer error); the loop
  // then stops. failure() says what happened, for the user.
  virtual bool failed() const { return false; }
  virtual std::string failure() const { return {}; }
  // How long the device has something to do (s): a trajectory's length, or
  // infinity for a device a person holds.
  virtual double naturalDuration() const { return std::numeric_limits<double>::infinity(); }
  // Zeroes the output and releases the device. Called once, after the last
  // frame, on the thread that ran the loop; must be safe after a failure.
  virtual void stop() {}
  virtual DeviceCounters counters() const { return {}; }
  // Whether the device applies torque. A force-only device (Touch, omega.6,
  // Falcon) gets a zero torque every frame; the loop logs the renderer's
  // torque and flags it not output (kSafetyTorqueNotOutput). Known once open.
  virtual bool outputsTorque() const { return true; }

  // A device whose library runs the servo loop itself (OpenHaptics'
  // scheduler calls back once per device tick): the haptic loop then starts
  // no thread of its own but hands `frame` to startServo. `frame` is one
  // haptic frame (read, step, write) and returns false when the run is over;
  // the driver then unschedules it. stopServo (scene thread, after the last
  // frame or when the library stopped calling) stops the library's loop and
  // releases the device; idempotent. Devices MillSim polls (ARES, the
  // simulated ones) keep the defaults.
  virtual bool ownsServoLoop() const { return false; }
  virtual void startServo(std::function<bool()> frame) { (void)frame; }
  virtual void stopServo() {}
};

}  // namespace millsim
