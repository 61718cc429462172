#pragma once
// Which ARES to open on USB, and opening it: the fields of AresDevice and of
// AnyDevice (for the ARES it looks for first), declared once here. A device
// node derives from this group and passes itself as the fields' owner, so
// the fields are in the node's one table (the parser, docs/nodes.md).
#include <memory>

#include "millsim/core/Node.h"
#include "millsim/driver/DeviceDriver.h"

namespace millsim {

class Node;

class AresUsbFields {
public:
  explicit AresUsbFields(Node* owner);
  // Defaults: the pid.codes test VID:PID 1209:0001 used for development.
  SFInt32 vendorId;
  SFInt32 productId;
  SFString serialNumber;

  // Opens and claims the device (its firmware clamps to these limits too);
  // DeviceError says what was looked for and which USB devices were seen
  // when none matches.
  std::unique_ptr<DeviceDriver> openAres(double forceLimit, double torqueLimit) const;
  // Finds and claims the USB interface only, sending nothing, then lets it
  // go (`millsim devices`); DeviceError as openAres.
  void findAres() const;
  // findAres as `millsim check` says it.
  DeviceProbe probeAres() const;
};

}  // namespace millsim
