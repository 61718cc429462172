#pragma once
// PhantomDevice: H3DAPI's node for a 3D Systems device (Touch, Touch X,
// Phantom Premium) through OpenHaptics' HD API, which MillSim loads at run
// time (millsim/driver/OpenHapticsApi.h: MILLSIM_OPENHAPTICS_LIBRARY, else
// libHD.so where OpenHaptics for Linux installs it). The library's scheduler
// owns the servo loop and calls MillSim's haptic frame once per tick. Force
// out; the renderer's torque is logged, not sent (OpenHapticsDriver.h).
#include "millsim/devices/HapticsDevice.h"

namespace millsim {

class PhantomDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString deviceName{this, "deviceName", Access::InitializeOnly, "",
                      "The OpenHaptics device configuration to open (as Touch_Setup names it); empty: the default "
                      "device."};

  // Loads libHD.so and opens the device; DeviceError says what was tried and
  // what to install or do (calibrate, plug in).
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  std::string noteOpened() override;
  std::optional<DeviceProbe> probe() const override;

private:
  mutable std::string opened_;
};

}  // namespace millsim
