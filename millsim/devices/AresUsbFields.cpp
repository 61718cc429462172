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

namespace {
UsbMatch matchOf(const AresUsbFields& f) {
  UsbMatch m;
  m.vendorId = static_cast<std::uint16_t>(f.vendorId.get());
  m.productId = static_cast<std::uint16_t>(f.productId.get());
  m.serialNumber = f.serialNumber.get();
  m.deviceName = "ARES device";
  m.interfaceNumber = ares::kInterfaceNumber;
  m.endpointIn = ares::kEndpointIn;
  m.endpointOut = ares::kEndpointOut;
  return m;
}
}  // namespace

std::unique_ptr<DeviceDriver> AresUsbFields::openAres(double forceLimit, double torqueLimit) const {
  AresDriverOptions o;
  o.forceLimit = forceLimit;
  o.torqueLimit = torqueLimit;
  return std::make_unique<AresDriver>(UsbTransport::open(matchOf(*this)), o);
}

void AresUsbFields::findAres() const { (void)UsbTransport::open(matchOf(*this)); }

DeviceProbe AresUsbFields::probeAres() const {
  DeviceProbe p;
  try {
    findAres();
    p.opens = true;
    p.what = "an ARES (its USB interface can be claimed)";
  } catch (const DeviceError& e) {
    p.what = e.what();
  }
  return p;
}

}  // namespace millsim
