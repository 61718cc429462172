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
  return std::make_unique<OpenHapticsDriver>(deviceName.get());
}

}  // namespace millsim
