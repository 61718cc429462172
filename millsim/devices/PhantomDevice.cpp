#include "millsim/devices/PhantomDevice.h"

#include "millsim/driver/OpenHapticsDriver.h"

namespace millsim {

const NodeType& PhantomDevice::type() {
  static const NodeType t = makeNodeType<PhantomDevice>(
      "PhantomDevice", "children", "MillSim devices",
      "A 3D Systems Touch, Touch X or Phantom through OpenHaptics (libHD.so, loaded at run time).");
  return t;
}

std::unique_ptr<DeviceDriver> PhantomDevice::openDriver(const DriverOptions&) const {
  auto driver = std::make_unique<OpenHapticsDriver>(deviceName.get());
  opened_ = driver->describe();
  return driver;
}

std::optional<DeviceProbe> PhantomDevice::probe() const { return probeOpenHapticsDevice(deviceName.get()); }

std::string PhantomDevice::noteOpened() { return opened_.empty() ? std::string() : "PhantomDevice: opened " + opened_; }

}  // namespace millsim
