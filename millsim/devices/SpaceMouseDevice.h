#pragma once
// SpaceMouseDevice: a 3Dconnexion 3D mouse (SpaceNavigator, SpaceMouse)
// moving the burr, for a person without a haptic device: 6-DOF in, no force
// out, like MouseDevice but without the window. The puck is a rate control:
// its deflection sets the burr's velocity (translationSpeed at full
// deflection) and turning rate (rotationSpeed), integrated each haptic
// frame; button 0 held is the milling switch. Read through spacenavd and
// libspnav (millsim/driver/SpaceNav.h). The HUD shows the force a hand would
// feel; nothing is sent.
#include "millsim/devices/HapticsDevice.h"

namespace millsim {

class SpaceMouseDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f position{this, "position", Access::InitializeOnly, glm::vec3(0.f, 0.015f, 0.f),
                   "Where the burr starts (m, device frame).", Range::closed(-10, 10).in(quantity::length)};
  SFRotation orientation{this, "orientation", Access::InitializeOnly, Rotation{},
                         "How the tool starts (default: shaft up, +Y)."};
  SFFloat translationSpeed{this, "translationSpeed", Access::InitializeOnly, 0.005f,
                           "Burr speed at full deflection of the puck (m/s).",
                           Range::openClosed(0, 1).in(quantity::velocity)};
  SFFloat rotationSpeed{this, "rotationSpeed", Access::InitializeOnly, 1.f,
                        "Turning rate at full twist of the puck (rad/s).", Range::closed(0, 10).in(quantity::angularVelocity)};
  SFFloat deadZone{this, "deadZone", Access::InitializeOnly, 0.05f,
                   "Deflection, as a fraction of full scale, below which the puck counts as at rest.",
                   Range::closed(0, 0.9)};
  SFString deviceModel{this, "deviceModel", Access::OutputOnly, "",
                       "The 3D mouse the last run read, as spacenavd names it."};

  // Connects to spacenavd; DeviceError says what to install or start.
  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  std::string noteOpened() override;
  std::optional<DeviceProbe> probe() const override;

private:
  mutable std::string model_;
  mutable bool opened_ = false;
};

}  // namespace millsim
