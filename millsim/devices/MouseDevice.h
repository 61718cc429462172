#pragma once
// MouseDevice: the mouse as a simulated 6-DOF device, for a person without
// haptic hardware (as H3DAPI's mouse haptics device). In the window of
// `millsim run` the burr follows the cursor on the plane through it parallel
// to the screen, Ctrl+wheel moves it in depth, a right-drag turns the tool,
// and the left button (or Space) is the milling switch. It has no force
// output: the window draws the renderer's tool and the device's pose (a green
// wire ghost) apart, and the HUD shows the force the hand would feel.
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/MousePointer.h"

namespace millsim {

class MouseDevice : public HapticsDevice, public MousePointerFields {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  MouseDevice() : MousePointerFields(this) {}

  // Needs DriverOptions::pointer (the window of `millsim run`); throws DeviceError without it.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  std::optional<PointerStart> pointerStart() const override { return PointerStart{startPose(), depthStep.get()}; }
};

}  // namespace millsim
