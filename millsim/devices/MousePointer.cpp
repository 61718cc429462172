#include "millsim/devices/MousePointer.h"

namespace millsim {

namespace {

class MouseDriver final : public DeviceDriver {
public:
  explicit MouseDriver(PointerInput& input) : input_(input) {}
  DeviceReading read(double, double) override { return input_.read(); }
  void write(const glm::dvec3&, const glm::dvec3&) override {}

private:
  PointerInput& input_;
};

}  // namespace

MousePointerFields::MousePointerFields(Node* owner)
    : position{owner, "position", Access::InitializeOnly, glm::vec3(0.f),
               "Where the mouse's burr starts (m, world), until the mouse first moves; (0, 0, 0): just above the "
               "middle of the scene.",
               Range::closed(-10, 10).in(quantity::length)},
      orientation{owner, "orientation", Access::InitializeOnly, Rotation{},
                  "How the mouse's tool starts (default: shaft up, +Y)."},
      depthStep{owner, "depthStep", Access::InputOutput, 2e-4f,
                "How far one Ctrl+wheel notch moves the mouse's burr along the line of sight (m).",
                Range::closed(1e-6, 0.01).in(quantity::length)} {}

Pose MousePointerFields::startPose() const {
  Pose p;
  p.position = glm::dvec3(position.get());
  p.orientation = glm::dquat(orientation.get().quat());
  return p;
}

std::unique_ptr<DeviceDriver> MousePointerFields::followPointer(PointerInput& input) {
  return std::make_unique<MouseDriver>(input);
}

}  // namespace millsim
