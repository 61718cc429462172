#include "millsim/devices/AnyDevice.h"

#include "millsim/driver/AresProtocol.h"
#include "millsim/driver/DeviceDriver.h"
#include "millsim/driver/ForceDimensionDriver.h"
#include "millsim/driver/OpenHapticsDriver.h"

namespace millsim {

const NodeType& AnyDevice::type() {
  static const NodeType t = makeNodeType<AnyDevice>(
      "AnyDevice", "children", "MillSim devices",
      "H3DAPI's AnyDevice: an attached ARES, else a Force Dimension device or Falcon, else an OpenHaptics device, "
      "else the mouse in the window of millsim run, else an error.");
  return t;
}

double AnyDevice::outputHoldTime() const { return ares::kDeviceWatchdogSeconds; }

std::unique_ptr<DeviceDriver> AnyDevice::openDriver(const DriverOptions& options) const {
  // The order H3DAPI's AnyDevice has, for the devices MillSim opens: the
  // ARES, a Force Dimension device (omega, sigma, delta, Falcon), an
  // OpenHaptics device (Touch, Phantom), then the window's mouse.
  std::string aresProblem, forceDimensionProblem, openHapticsProblem;
  try {
    auto driver = openAres(forceLimit.get(), torqueLimit.get());  // it clamps to the node's limits too
    opened_ = Opened::Ares;
    return driver;
  } catch (const DeviceError& e) {
    aresProblem = e.what();
  }
  try {
    auto driver = std::make_unique<ForceDimensionDriver>(ForceDimensionSelector{});
    opened_ = Opened::ForceDimension;
    what_ = driver->describe();
    return driver;
  } catch (const DeviceError& e) {
    forceDimensionProblem = e.what();
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
  throw DeviceError("AnyDevice found no device to open: no ARES (" + aresProblem + "), no Force Dimension device (" +
                    forceDimensionProblem + "), no OpenHaptics device (" + openHapticsProblem +
                    "), and no window for the mouse (no DISPLAY, or --no-window); use a HandDevice or "
                    "TrajectoryDevice to run without either");
}

std::optional<DeviceProbe> AnyDevice::probe() const {
  DeviceProbe ares = probeAres();
  if (ares.opens) return ares;
  DeviceProbe fd = probeForceDimensionDevice(ForceDimensionSelector{});
  if (fd.opens) return fd;
  DeviceProbe hd = probeOpenHapticsDevice("");
  if (hd.opens) return hd;
  DeviceProbe mouse;
  mouse.opens = true;
  mouse.what = "no ARES, Force Dimension or OpenHaptics device here: millsim run follows the mouse in its window";
  return mouse;
}

std::string AnyDevice::noteOpened() {
  switch (opened_) {
    case Opened::Ares:
      openedDevice.set("AresDevice");
      return "AnyDevice: opened the ARES";
    case Opened::ForceDimension:
      openedDevice.set("ForceDimensionDevice");
      return "AnyDevice: no ARES found; opened " + what_;
    case Opened::OpenHaptics:
      openedDevice.set("PhantomDevice");
      return "AnyDevice: no ARES or Force Dimension device found; opened the OpenHaptics device";
    case Opened::Mouse:
      openedDevice.set("MouseDevice");
      return "AnyDevice: no ARES, Force Dimension or OpenHaptics device found; following the mouse";
    case Opened::Nothing:
      break;
  }
  return {};
}

}  // namespace millsim
