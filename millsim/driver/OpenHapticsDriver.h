#pragma once
// OpenHapticsDriver: a 3D Systems device (Touch, Touch X, Phantom Premium)
// through OpenHaptics' HD API, loaded at run time (OpenHapticsApi.h). The
// library owns the servo loop: its scheduler thread calls MillSim's haptic
// frame once per device tick (DeviceDriver::ownsServoLoop). read() begins
// the device frame (pose, buttons), write() sets the force and ends it, which
// sends it. Positions come in millimetres and go to the loop in metres; the
// force goes out in newtons. Torque is not sent: a Touch outputs force only,
// and a 6-DOF Phantom's gimbal torques are joint torques that need the
// gimbal's kinematics (not done), so the renderer's torque is logged, not felt.
#include <functional>
#include <string>

#include "millsim/driver/DeviceDriver.h"

namespace millsim {

namespace openhaptics {
struct Api;
}

struct OpenHapticsCapabilities {
  std::string model;             // HD_DEVICE_MODEL_TYPE
  int outputDof = 3;             // HD_OUTPUT_DOF
  double maxForce = 0.0;         // N, HD_NOMINAL_MAX_FORCE
  double maxContinuousForce = 0.0;  // N
  double maxStiffness = 0.0;     // N/m (the library says N/mm)
};

// What `millsim devices` says of OpenHaptics: whether libHD.so loads, and
// the device `deviceName` (empty: the default) with its capabilities and
// calibration, opened only to ask (no force output is enabled).
struct OpenHapticsProbe {
  std::string library;     // where libHD.so was loaded from; empty: not loaded
  std::string error;       // why the library or the device could not be opened; empty: both were
  bool device = false;     // the device opened
  std::string calibration; // "OK", or what it needs
  OpenHapticsCapabilities capabilities;
};
OpenHapticsProbe probeOpenHaptics(const std::string& deviceName);
// The same, as `millsim check` says it of a scene's device.
DeviceProbe probeOpenHapticsDevice(const std::string& deviceName);

class OpenHapticsDriver final : public DeviceDriver {
public:
  // Opens the device named `deviceName` (empty: the default one), checks its
  // calibration (an update is made where the library can; a device that
  // needs the stylus in its inkwell is refused, saying so) and enables force
  // output. Throws DeviceError with what was tried and what to do.
  explicit OpenHapticsDriver(const std::string& deviceName);
  ~OpenHapticsDriver() override;

  DeviceReading read(double t, double dt) override;
  void write(const glm::dvec3& force, const glm::dvec3& torque) override;
  bool failed() const override { return failed_; }
  std::string failure() const override { return failure_; }
  void stop() override;
  DeviceCounters counters() const override { return counters_; }
  // Never: see the top of this file.
  bool outputsTorque() const override { return false; }

  bool ownsServoLoop() const override { return true; }
  void startServo(std::function<bool()> frame) override;
  void stopServo() override;

  const OpenHapticsCapabilities& capabilities() const { return caps_; }
  // "Touch, 3-DOF force output, ...", for the user.
  std::string describe() const;

private:
  static unsigned int servoTick(void* self);
  // The newest error on the library's stack, or empty; records a failure.
  bool checkError(const char* during);

  const openhaptics::Api* api_ = nullptr;
  unsigned int device_ = 0;
  bool inFrame_ = false;
  bool failed_ = false;
  std::string failure_;
  DeviceCounters counters_;
  OpenHapticsCapabilities caps_;
  std::function<bool()> frame_;
  unsigned long handle_ = 0;
  bool scheduled_ = false, servoStopped_ = false, disabled_ = false;
};

}  // namespace millsim
