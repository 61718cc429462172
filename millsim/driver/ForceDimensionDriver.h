#pragma once
// ForceDimensionDriver: a Force Dimension device (omega, sigma, delta) or a
// Novint Falcon through Force Dimension's DHD API, loaded at run time
// (ForceDimensionApi.h). The library has no servo thread: MillSim's
// real-time haptic thread polls it, one pose read and one wrench write per
// frame. DHD's frame (x towards the user, y right, z up) is turned into
// X3D's (x right, y up, z towards the user) on the way in and back on the
// way out; units are already SI. Torque goes out only on a device with an
// active wrist (sigma.7, delta.6); on the others the renderer's torque is
// logged, not sent (DeviceDriver::outputsTorque).
#include <string>

#include "millsim/driver/DeviceDriver.h"

namespace millsim {

namespace forcedimension {
struct Api;
}

struct ForceDimensionCapabilities {
  std::string model;         // dhdGetSystemName
  int systemType = 0;        // dhdGetSystemType (DHD_DEVICE_…)
  bool sensesOrientation = false;  // dhdHasWrist: 6-DOF in
  bool outputsTorque = false;      // dhdHasActiveWrist: 6-DOF out
  double maxForce = 0.0;     // N, dhdGetMaxForce where the library has it and a limit is set; 0: not told
};

// Which device to open: the first available (index -1), the one at an index
// of the library's list, or the first Falcon.
struct ForceDimensionSelector {
  int index = -1;
  bool falcon = false;
  std::string describe() const;
};

// What `millsim devices` and `millsim check` say of DHD: whether libdhd.so
// loads (and its version), how many devices it sees, and the one `which`
// selects with its capabilities, opened only to ask (force is not enabled).
struct ForceDimensionProbe {
  std::string library;  // where libdhd.so was loaded from; empty: not loaded
  std::string version;  // "SDK 3.17.0"
  std::string error;    // why the library or the device could not be opened; empty: both were
  int deviceCount = 0;
  bool device = false;
  ForceDimensionCapabilities capabilities;
};
ForceDimensionProbe probeForceDimension(const ForceDimensionSelector& which);
// The same, as `millsim check` says it of a scene's device.
DeviceProbe probeForceDimensionDevice(const ForceDimensionSelector& which);

class ForceDimensionDriver final : public DeviceDriver {
public:
  // Opens the device and enables its force output. Throws DeviceError with
  // what was tried and what to do (install the SDK, its udev rule, plug in).
  explicit ForceDimensionDriver(const ForceDimensionSelector& which);
  ~ForceDimensionDriver() override;

  DeviceReading read(double t, double dt) override;
  void write(const glm::dvec3& force, const glm::dvec3& torque) override;
  bool failed() const override { return failed_; }
  std::string failure() const override { return failure_; }
  void stop() override;
  DeviceCounters counters() const override { return counters_; }
  bool outputsTorque() const override { return caps_.outputsTorque; }

  const ForceDimensionCapabilities& capabilities() const { return caps_; }
  // "omega.6, SDK 3.17.0, force out (torque logged, not sent)", for the user.
  std::string describe() const;

private:
  void fail(const char* during);

  const forcedimension::Api* api_ = nullptr;
  char id_ = -1;
  bool open_ = false;
  bool failed_ = false;
  std::string failure_;
  DeviceCounters counters_;
  ForceDimensionCapabilities caps_;
};

}  // namespace millsim
