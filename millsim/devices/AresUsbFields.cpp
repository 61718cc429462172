#include "millsim/devices/AresUsbFields.h"

#include "millsim/driver/AresDriver.h"
#include "millsim/driver/AresProtocol.h"
#include "millsim/driver/UsbTransport.h"

namespace millsim {

AresUsbFields::AresUsbFields(Node* owner)
    : vendorId{owner, "vendorId", Access::InitializeOnly, 0x1209, "USB vendor ID of the ARES (0x1209: pid.codes).",
               Range::closed(0, 0xffff)},
      productId{owner, "productId", Access::InitializeOnly, 0x0001,
                "USB product ID of the ARES (0x0001: pid.codes test PID, development only).", Range::closed(0, 0xffff)},
      serialNumber{owner, "serialNumber", Access::InitializeOnly, "",
                   "USB serial number of the ARES to open; empty opens the first matching device."} {}

std::unique_ptr<DeviceDriver> AresUsbFields::openAres(double forceLimit, double torqueLimit) const {
  UsbMatch m;
  m.vendorId = static_cast<std::uint16_t>(vendorId.get());
  m.productId = static_cast<std::uint16_t>(productId.get());
  m.serialNumber = serialNumber.get();
  m.deviceName = "ARES device";
  m.interfaceNumber = ares::kInterfaceNumber;
  m.endpointIn = ares::kEndpointIn;
  m.endpointOut = ares::kEndpointOut;
  AresDriverOptions o;
  o.forceLimit = forceLimit;
  o.torqueLimit = torqueLimit;
  return std::make_unique<AresDriver>(UsbTransport::open(m), o);
}

}  // namespace millsim
