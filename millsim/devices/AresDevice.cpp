#include "millsim/devices/AresDevice.h"

#include "millsim/driver/AresProtocol.h"

namespace millsim {

const NodeType& AresDevice::type() {
  static const NodeType t = makeNodeType<AresDevice>(
      "AresDevice", "children", "MillSim devices",
      "The ARES 6-DOF haptic device on USB (libusb-1.0; protocol in docs/ares-protocol.md).");
  return t;
}

double AresDevice::outputHoldTime() const { return ares::kDeviceWatchdogSeconds; }

std::optional<DeviceProbe> AresDevice::probe() const { return probeAres(); }

std::unique_ptr<DeviceDriver> AresDevice::openDriver(const DriverOptions&) const {
  return openAres(forceLimit.get(), torqueLimit.get());
}

}  // namespace millsim
