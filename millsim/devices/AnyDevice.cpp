#include "millsim/devices/AnyDevice.h"

#include "millsim/driver/AresProtocol.h"
#include "millsim/driver/DeviceDriver.h"
#include "millsim/driver/OpenHapticsDriver.h"

namespace millsim {

const NodeType& AnyDevice::type() {
  static const NodeType t = makeNodeType<AnyDevice>(
      "AnyDevice", "children", "MillSim devices",
      "H3DAPI's AnyDevice: an attached ARES, else an OpenHaptics device, else the mouse in the window of "
      "millsim run, else an error.");
  return t;
}

double AnyDevice::outputHoldTime() const { return ares::kDeviceWatchdogSeconds; }

std::unique_ptr<DeviceDriver> AnyDevice::openDriver(const DriverOptions& options) const {
  // The order H3DAPI's AnyDevice has, for the devices MillSim opens: the
  // ARES, an OpenHaptics device (Touch, Phantom), then the window's mouse.
  std::string aresProblem, openHapticsProblem;
  try {
    auto driver = openAres(forceLimit.get(), torqueLimit.get());  // it clamps to the node's limits too
    opened_ = Opened::Ares;
    return driver;
  } catch (const DeviceError& e) {
    aresProblem = e.what();
  }
  try {
    auto driver = std::make_unique<OpenHapticsDriver>(std::string());
    opened_ = Opened::OpenHaptics;
    return driver;
  } catch (const DeviceError& e) {
    openHapticsProblem = e.what();
  }
  if (options.pointer) {
    opened_ = Opened::Mouse;
    return followPointer(*options.pointer);
  }
  throw DeviceError("AnyDevice found no device to open: no ARES (" + aresProblem + "), no OpenHaptics device (" +
                    openHapticsProblem +
                    "), and no window for the mouse (no DISPLAY, or --no-window); use a HandDevice or "
                    "TrajectoryDevice to run without either");
}

std::string AnyDevice::noteOpened() {
  switch (opened_) {
    case Opened::Ares:
      openedDevice.set("AresDevice");
      return "AnyDevice: opened the ARES";
    case Opened::OpenHaptics:
      openedDevice.set("PhantomDevice");
      return "AnyDevice: no ARES found; opened the OpenHaptics device";
    case Opened::Mouse:
      openedDevice.set("MouseDevice");
      return "AnyDevice: no ARES or OpenHaptics device found; following the mouse";
    case Opened::Nothing:
      break;
  }
  return {};
}

}  // namespace millsim
