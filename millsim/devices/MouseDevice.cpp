#include "millsim/devices/MouseDevice.h"

namespace millsim {

namespace {

class MouseDriver final : public DeviceDriver {
public:
  explicit MouseDriver(PointerInput& input) : input_(input) {}
  DeviceReading read(double, double) override { return input_.read(); }
  void write(const glm::dvec3&, const glm::dvec3&) override {}  // a mouse pushes nothing back

private:
  PointerInput& input_;
};

}  // namespace

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
  return std::make_unique<MouseDriver>(*options.pointer);
}

Pose MouseDevice::startPose() const {
  Pose p;
  p.position = glm::dvec3(position.get());
  p.orientation = glm::dquat(orientation.get().quat());
  return p;
}

}  // namespace millsim
