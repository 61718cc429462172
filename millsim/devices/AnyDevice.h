#pragma once
// AnyDevice: H3DAPI's "whatever device there is", for scenes written for
// H3DAPI and for lessons that should run on any desk: an attached ARES
// (found as AresDevice finds it), else the mouse in the window of `millsim
// run` (as MouseDevice), else an error that says what was tried. Replay and
// render play its trajectory open loop, as for any hardware device.
#include <memory>
#include <string>

#include "millsim/devices/AresDevice.h"
#include "millsim/devices/MouseDevice.h"

namespace millsim {

class AnyDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  AnyDevice();
  ~AnyDevice() override;

  // The ARES to look for (AresDevice's fields and defaults).
  SFInt32 vendorId{this, "vendorId", Access::InitializeOnly, 0x1209, "USB vendor ID of the ARES to look for.",
                   Range::closed(0, 0xffff)};
  SFInt32 productId{this, "productId", Access::InitializeOnly, 0x0001, "USB product ID of the ARES to look for.",
                    Range::closed(0, 0xffff)};
  SFString serialNumber{this, "serialNumber", Access::InitializeOnly, "", "USB serial number; empty: the first ARES found."};
  // The mouse when there is no ARES (MouseDevice's fields and defaults).
  SFVec3f position{this, "position", Access::InitializeOnly, glm::vec3(0.f),
                   "With the mouse: where the burr starts (m, world); (0, 0, 0): just above the middle of the scene.",
                   Range::closed(-10, 10).in(quantity::length)};
  SFRotation orientation{this, "orientation", Access::InitializeOnly, Rotation{},
                         "With the mouse: how the tool starts (default: shaft up, +Y)."};
  SFFloat depthStep{this, "depthStep", Access::InputOutput, 2e-4f, "With the mouse: how far one Ctrl+wheel notch moves the burr (m).",
                    Range::closed(1e-6, 0.01).in(quantity::length)};
  SFString openedDevice{this, "openedDevice", Access::OutputOnly, "",
                        "Which device the last run opened: AresDevice or MouseDevice."};

  // Tries the ARES, then the mouse (options.pointer); DeviceError naming both otherwise.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  // The ARES's, whichever it opens: the mouse's output goes nowhere, and a
  // review of the run, which opens nothing, repeats the same decisions.
  double outputHoldTime() const override;
  // The mouse it falls back on, set up from its fields (the window needs its start pose).
  const MouseDevice& mouse() const;
  // After openDriver: whether it follows the mouse (no ARES was found).
  bool followsMouse() const { return followsMouse_; }

private:
  std::unique_ptr<AresDevice> ares_;
  std::unique_ptr<MouseDevice> mouse_;
  mutable bool followsMouse_ = false;
};

}  // namespace millsim
