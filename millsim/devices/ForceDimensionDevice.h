#pragma once
// ForceDimensionDevice: H3DAPI's node for a Force Dimension device (omega.x,
// sigma.x, delta.x) through the vendor's DHD library, which MillSim loads at
// run time (millsim/driver/ForceDimensionApi.h: MILLSIM_FORCEDIMENSION_LIBRARY,
// else libdhd.so where the SDK is installed). MillSim's real-time thread
// polls it. Force out on every model; torque only where the wrist is active
// (sigma.7, delta.6), else logged, not sent.
#include <memory>
#include <string>

#include "millsim/devices/HapticsDevice.h"

namespace millsim {

class ForceDimensionDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFInt32 deviceIndex{this, "deviceIndex", Access::InitializeOnly, -1,
                      "Which device of those the DHD library finds (0, 1, ...); -1: the first available one.",
                      Range::closed(-1, 31)};
  SFString deviceModel{this, "deviceModel", Access::OutputOnly, "",
                       "The model the last run opened, as the library names it (omega.6, sigma.7, ...)."};

  // Loads libdhd.so and opens the device; DeviceError says what was tried
  // and what to install or do.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  // Sets deviceModel and says what was opened and whether torque goes out.
  std::string noteOpened() override;
  std::optional<DeviceProbe> probe() const override;

private:
  mutable std::string opened_, model_;
};

}  // namespace millsim
