#include "millsim/devices/AnyDevice.h"

#include "millsim/driver/AresProtocol.h"
#include "millsim/driver/DeviceDriver.h"

namespace millsim {

const NodeType& AnyDevice::type() {
  static const NodeType t = makeNodeType<AnyDevice>(
      "AnyDevice", "children", "MillSim devices",
      "H3DAPI's AnyDevice: an attached ARES, else the mouse in the window of millsim run, else an error.");
  return t;
}

double AnyDevice::outputHoldTime() const { return ares::kDeviceWatchdogSeconds; }

std::unique_ptr<DeviceDriver> AnyDevice::openDriver(const DriverOptions& options) const {
  std::string aresProblem;
  try {
    auto driver = openAres(forceLimit.get(), torqueLimit.get());  // it clamps to the node's limits too
    followsMouse_ = false;
    return driver;
  } catch (const DeviceError& e) {
    aresProblem = e.what();
  }
  if (options.pointer) {
    followsMouse_ = true;
    return followPointer(*options.pointer);
  }
  throw DeviceError("AnyDevice found no device to open: no ARES (" + aresProblem +
                    "), and no window for the mouse (no DISPLAY, or --no-window); use a HandDevice or "
                    "TrajectoryDevice to run without either");
}

std::string AnyDevice::noteOpened() {
  openedDevice.set(followsMouse_ ? "MouseDevice" : "AresDevice");
  return followsMouse_ ? "AnyDevice: no ARES found; following the mouse" : "AnyDevice: opened the ARES";
}

}  // namespace millsim
