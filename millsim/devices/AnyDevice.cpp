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

AnyDevice::AnyDevice() : ares_(std::make_unique<AresDevice>()), mouse_(std::make_unique<MouseDevice>()) {}

AnyDevice::~AnyDevice() = default;

const MouseDevice& AnyDevice::mouse() const {
  mouse_->position.set(position.get());
  mouse_->orientation.set(orientation.get());
  mouse_->depthStep.set(depthStep.get());
  return *mouse_;
}

double AnyDevice::outputHoldTime() const { return ares::kDeviceWatchdogSeconds; }

std::unique_ptr<DeviceDriver> AnyDevice::openDriver(const DriverOptions& options) const {
  // The ARES driver clamps to its own limits too: the same as this node's.
  ares_->vendorId.set(vendorId.get());
  ares_->productId.set(productId.get());
  ares_->serialNumber.set(serialNumber.get());
  ares_->forceLimit.set(forceLimit.get());
  ares_->torqueLimit.set(torqueLimit.get());
  std::string aresProblem;
  try {
    auto driver = ares_->openDriver(options);
    followsMouse_ = false;
    return driver;
  } catch (const DeviceError& e) {
    aresProblem = e.what();
  }
  if (options.pointer) {
    followsMouse_ = true;
    return mouse().openDriver(options);
  }
  throw DeviceError("AnyDevice found no device to open: no ARES (" + aresProblem +
                    "), and no window for the mouse (no DISPLAY, or --no-window); use a HandDevice or "
                    "TrajectoryDevice to run without either");
}

}  // namespace millsim
