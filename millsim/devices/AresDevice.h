#pragma once
// AresDevice: the ARES 6-DOF parallel-kinematic haptic device on USB, found
// by vendorId/productId (and serialNumber when set), speaking the protocol of
// docs/ares-protocol.md through libusb-1.0.
#include "millsim/devices/HapticsDevice.h"

namespace millsim {

class AresDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  // Defaults: the pid.codes test VID:PID 1209:0001 used for development.
  SFInt32 vendorId{this, "vendorId", Access::InitializeOnly, 0x1209, "USB vendor ID (0x1209: pid.codes).",
                   Range::closed(0, 0xffff)};
  SFInt32 productId{this, "productId", Access::InitializeOnly, 0x0001,
                    "USB product ID (0x0001: pid.codes test PID, development only).", Range::closed(0, 0xffff)};
  SFString serialNumber{this, "serialNumber", Access::InitializeOnly, "",
                        "USB serial number to open; empty opens the first matching device."};

  // Opens and claims the device; DeviceError says what was looked for and
  // which USB devices were seen when none matches.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  // The firmware's watchdog (docs/ares-protocol.md, device rule 4).
  double outputHoldTime() const override;
};

}  // namespace millsim
