#pragma once
// AresDevice: the ARES 6-DOF parallel-kinematic haptic device on USB, found
// by vendorId/productId (and serialNumber when set), speaking the protocol of
// docs/ares-protocol.md through libusb-1.0.
#include "millsim/devices/AresUsbFields.h"
#include "millsim/devices/HapticsDevice.h"

namespace millsim {

class AresDevice : public HapticsDevice, public AresUsbFields {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  AresDevice() : AresUsbFields(this) {}

  // Opens and claims the device (AresUsbFields::openAres, at this node's limits).
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  // The firmware's watchdog (docs/ares-protocol.md, device rule 4).
  double outputHoldTime() const override;
  std::optional<DeviceProbe> probe() const override;
};

}  // namespace millsim
