#include "millsim/devices/AresDevice.h"

#include "millsim/driver/AresDriver.h"
#include "millsim/driver/AresProtocol.h"
#include "millsim/driver/UsbTransport.h"

namespace millsim {

const NodeType& AresDevice::type() {
  static const NodeType t = makeNodeType<AresDevice>(
      "AresDevice", "children", "MillSim devices",
      "The ARES 6-DOF haptic device on USB (libusb-1.0; protocol in docs/ares-protocol.md).");
  return t;
}

double AresDevice::outputHoldTime() const { return ares::kDeviceWatchdogSeconds; }

std::unique_ptr<DeviceDriver> AresDevice::openDriver(const DriverOptions&) const {
  UsbMatch m;
  m.vendorId = static_cast<std::uint16_t>(vendorId.get());
  m.productId = static_cast<std::uint16_t>(productId.get());
  m.serialNumber = serialNumber.get();
  m.deviceName = "ARES device";
  m.interfaceNumber = ares::kInterfaceNumber;
  m.endpointIn = ares::kEndpointIn;
  m.endpointOut = ares::kEndpointOut;
  AresDriverOptions o;
  o.forceLimit = forceLimit.get();
  o.torqueLimit = torqueLimit.get();
  return std::make_unique<AresDriver>(UsbTransport::open(m), o);
}

}  // namespace millsim
