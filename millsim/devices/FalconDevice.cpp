#include "millsim/devices/FalconDevice.h"

#include "millsim/driver/ForceDimensionDriver.h"

namespace millsim {

const NodeType& FalconDevice::type() {
  static const NodeType t = makeNodeType<FalconDevice>(
      "FalconDevice", "children", "MillSim devices",
      "A Novint Falcon through Force Dimension's DHD library (libdhd.so, loaded at run time): force out, no torque.");
  return t;
}

std::unique_ptr<DeviceDriver> FalconDevice::openDriver(const DriverOptions&) const {
  auto driver = std::make_unique<ForceDimensionDriver>(ForceDimensionSelector{-1, true});
  opened_ = driver->describe();
  return driver;
}

std::optional<DeviceProbe> FalconDevice::probe() const { return probeForceDimensionDevice(ForceDimensionSelector{-1, true}); }

std::string FalconDevice::noteOpened() { return opened_.empty() ? std::string() : "FalconDevice: opened " + opened_; }

}  // namespace millsim
