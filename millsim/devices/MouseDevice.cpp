#include "millsim/devices/MouseDevice.h"

namespace millsim {

const NodeType& MouseDevice::type() {
  static const NodeType t = makeNodeType<MouseDevice>(
      "MouseDevice", "children", "MillSim devices",
      "The mouse as a simulated 6-DOF device in the window of millsim run (no force output).");
  return t;
}

std::unique_ptr<DeviceDriver> MouseDevice::openDriver(const DriverOptions& options) const {
  if (!options.pointer)
    throw DeviceError("MouseDevice follows the mouse in the window of `millsim run`, and there is none (no DISPLAY, "
                      "or --no-window); use a HandDevice or TrajectoryDevice to run without a window");
  return followPointer(*options.pointer);
}

}  // namespace millsim
