#pragma once
// AnyDevice: H3DAPI's "whatever device there is", for scenes written for
// H3DAPI and for lessons that should run on any desk: an attached ARES
// (found as AresDevice finds it), else a Force Dimension device or Falcon
// (as ForceDimensionDevice opens the first one), else an OpenHaptics device
// (as PhantomDevice opens the default one), else the mouse in the window of
// `millsim run` (as MouseDevice), else an error that says what was tried. Replay and
// render play its trajectory open loop, as for any hardware device. Its
// fields are AresDevice's (AresUsbFields) and MouseDevice's
// (MousePointerFields), each group declared once and opened by the same code.
#include <memory>
#include <optional>
#include <string>

#include "millsim/devices/AresUsbFields.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/MousePointer.h"

namespace millsim {

class AnyDevice : public HapticsDevice, public AresUsbFields, public MousePointerFields {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  AnyDevice() : AresUsbFields(this), MousePointerFields(this) {}

  SFString openedDevice{this, "openedDevice", Access::OutputOnly, "",
                        "Which device the last run opened: AresDevice, ForceDimensionDevice, PhantomDevice or MouseDevice."};

  // Tries the ARES, Force Dimension, OpenHaptics, then the mouse (options.pointer); DeviceError naming each otherwise.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  // The ARES's, whichever it opens: the mouse's output goes nowhere, and a
  // review of the run, which opens nothing, repeats the same decisions.
  double outputHoldTime() const override;
  std::optional<PointerStart> pointerStart() const override { return PointerStart{startPose(), depthStep.get()}; }
  // After openDriver: whether it follows the mouse (no other device was found).
  bool followsPointer() const override { return opened_ == Opened::Mouse; }
  // Sets openedDevice and says which device it found.
  std::string noteOpened() override;
  // The first of the devices it tries that would open, or what `millsim run` does without one.
  std::optional<DeviceProbe> probe() const override;

private:
  enum class Opened { Nothing, Ares, ForceDimension, OpenHaptics, Mouse };
  mutable Opened opened_ = Opened::Nothing;
  mutable std::string what_;  // the Force Dimension model it opened
};

}  // namespace millsim
