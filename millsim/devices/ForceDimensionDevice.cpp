#include "millsim/devices/ForceDimensionDevice.h"

#include "millsim/driver/ForceDimensionDriver.h"

namespace millsim {

const NodeType& ForceDimensionDevice::type() {
  static const NodeType t = makeNodeType<ForceDimensionDevice>(
      "ForceDimensionDevice", "children", "MillSim devices",
      "A Force Dimension omega, sigma or delta through the DHD library (libdhd.so, loaded at run time).");
  return t;
}

std::unique_ptr<DeviceDriver> ForceDimensionDevice::openDriver(const DriverOptions&) const {
  auto driver = std::make_unique<ForceDimensionDriver>(ForceDimensionSelector{deviceIndex.get(), false});
  opened_ = driver->describe();
  model_ = driver->capabilities().model;
  return driver;
}

std::optional<DeviceProbe> ForceDimensionDevice::probe() const { return probeForceDimensionDevice(ForceDimensionSelector{deviceIndex.get(), false}); }

std::string ForceDimensionDevice::noteOpened() {
  if (opened_.empty()) return {};
  deviceModel.set(model_);
  return "ForceDimensionDevice: opened " + opened_;
}

}  // namespace millsim
