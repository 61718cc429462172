#pragma once
// MouseDevice: the mouse as a simulated 6-DOF device, for a person without
// haptic hardware (as H3DAPI's mouse haptics device). In the window of
// `millsim run` the burr follows the cursor on the plane through it parallel
// to the screen, Ctrl+wheel moves it in depth, a right-drag turns the tool,
// and the left button (or Space) is the milling switch. It has no force
// output: the window draws the renderer's tool and the device's pose (a green
// wire ghost) apart, and the HUD shows the force the hand would feel.
#include "millsim/devices/HapticsDevice.h"
#include "millsim/driver/TripleBuffer.h"

namespace millsim {

// The hand-off from the window thread (the mouse) to the haptic thread (the
// MouseDevice's driver): the newest pose, wait-free for both.
class PointerInput {
public:
  explicit PointerInput(const Pose& start = {}) {
    buffer_.back() = DeviceReading{start, false, true};
    buffer_.publish();
  }
  // Window thread.
  void set(const Pose& pose, bool button) {
    buffer_.back() = DeviceReading{pose, button, true};
    buffer_.publish();
  }
  // Haptic thread.
  DeviceReading read() { return buffer_.read(); }

private:
  TripleBuffer<DeviceReading> buffer_;
};

class MouseDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f position{this, "position", Access::InitializeOnly, glm::vec3(0.f),
                   "Where the burr starts (m, world), until the mouse first moves; (0, 0, 0): just above the "
                   "middle of the scene.",
                   Range::closed(-10, 10).in(quantity::length)};
  SFRotation orientation{this, "orientation", Access::InitializeOnly, Rotation{},
                         "How the tool starts (default: shaft up, +Y)."};
  SFFloat depthStep{this, "depthStep", Access::InputOutput, 2e-4f,
                    "How far one Ctrl+wheel notch moves the burr along the line of sight (m).",
                    Range::closed(1e-6, 0.01).in(quantity::length)};

  // Needs DriverOptions::pointer (the window of `millsim run`); throws DeviceError without it.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  Pose startPose() const;
};

}  // namespace millsim
