#pragma once
// FalconDevice: H3DAPI's node for a Novint Falcon, opened here through Force
// Dimension's DHD library (which drives the Falcon; Novint's own HDAL is no
// longer distributed): the first Falcon the library finds. 3-DOF: position
// in, force out; the burr keeps the orientation orientationCalibration
// gives it, and the renderer's torque is logged, not sent.
#include <memory>
#include <string>

#include "millsim/devices/HapticsDevice.h"

namespace millsim {

class FalconDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  // Loads libdhd.so and opens the first Falcon; DeviceError says what was
  // tried and what to do (plug in, home the grip).
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  std::string noteOpened() override;
  std::optional<DeviceProbe> probe() const override;

private:
  mutable std::string opened_;
};

}  // namespace millsim
