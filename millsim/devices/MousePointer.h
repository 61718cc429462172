#pragma once
// The window's mouse as a device: the hand-off of its pose to the haptic
// thread (PointerInput), and where the tool starts and how it moves in depth
// — the fields of MouseDevice and of AnyDevice (for the mouse it falls back
// on), declared once here. A device node derives from MousePointerFields and
// passes itself as the fields' owner.
#include <memory>

#include "millsim/core/Node.h"
#include "millsim/core/Quantity.h"
#include "millsim/driver/DeviceDriver.h"
#include "millsim/driver/TripleBuffer.h"
#include "millsim/math/Pose.h"

namespace millsim {

class Node;

// The hand-off from the window thread (the mouse) to the haptic thread (the
// mouse's driver): the newest pose, wait-free for both.
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

class MousePointerFields {
public:
  explicit MousePointerFields(Node* owner);
  SFVec3f position;
  SFRotation orientation;
  SFFloat depthStep;

  Pose startPose() const;
  // A driver that reads `input` and sends nothing (a mouse pushes nothing back).
  static std::unique_ptr<DeviceDriver> followPointer(PointerInput& input);
};

}  // namespace millsim
