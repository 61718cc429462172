#pragma once
// HandDevice: a simulated hand holding a simulated device, closed loop. The
// hand's reference follows a trajectory (the replay CSV); a spring–damper (the
// grip) pulls the handle towards it; the handle and hand masses move under
// the grip, the device's own damping, and the rendered force and torque,
// which act back on them one frame late (zero-order hold, as on hardware).
// The grip and damping are integrated by the trapezoidal rule, so the hand
// model is stable at any rate and its spring neither adds nor removes energy;
// the rendered force is explicit, so the renderer's stability is tested as it
// would be on a real device (docs/algorithms.md).
#include "millsim/devices/HapticsDevice.h"

namespace millsim {

// The hand and device model, in SI units.
struct HandModel {
  double handMass = 0.55, handDamping = 10.0, handStiffness = 500.0;  // kg, N·s/m, N/m
  double handInertia = 3e-4, handAngularDamping = 0.02, handAngularStiffness = 0.3;  // kg·m², N·m·s/rad, N·m/rad
  double deviceMass = 0.15, deviceDamping = 1.0;                      // kg, N·s/m
  double deviceInertia = 1e-4, deviceAngularDamping = 0.002;         // kg·m², N·m·s/rad
  double releaseTime = -1.0;  // s; from then on the hand has let go (negative: never)
  // s; the device applies a wrench this long after it was sent, then drops it
  // (ARES's watchdog, docs/ares-protocol.md); infinite: until the next one.
  double outputHold = 0.010;
};

class HandDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InitializeOnly, {},
               "Trajectory CSV the hand's reference follows (t,x,y,z,qw,qx,qy,qz,button), relative to the scene."};
  SFBool loop{this, "loop", Access::InitializeOnly, false, "Start again at the end of the trajectory."};
  SFFloat handMass{this, "handMass", Access::InitializeOnly, 0.55f, "Mass of the hand and arm moving with the handle (kg).",
                   Range::closed(0, 10).in(quantity::mass)};
  SFFloat handDamping{this, "handDamping", Access::InitializeOnly, 10.f, "Grip damping towards the reference (N·s/m).",
                      Range::closed(0, 1e4).in(quantity::linearDamping)};
  SFFloat handStiffness{this, "handStiffness", Access::InitializeOnly, 500.f,
                        "Grip stiffness towards the reference (N/m).", Range::closed(0, 1e6).in(quantity::linearStiffness)};
  SFFloat handInertia{this, "handInertia", Access::InitializeOnly, 3e-4f,
                      "Rotational inertia of the hand about the burr centre (kg·m²).", Range::closed(0, 1).in(quantity::inertia)};
  SFFloat handAngularDamping{this, "handAngularDamping", Access::InitializeOnly, 0.02f,
                             "Grip rotational damping (N·m·s/rad).", Range::closed(0, 100).in(quantity::angularDamping)};
  SFFloat handAngularStiffness{this, "handAngularStiffness", Access::InitializeOnly, 0.3f,
                               "Grip rotational stiffness (N·m/rad).", Range::closed(0, 1000).in(quantity::angularStiffness)};
  SFFloat deviceMass{this, "deviceMass", Access::InitializeOnly, 0.15f, "Moving mass of the device (kg).",
                     Range::openClosed(0, 10).in(quantity::mass)};
  SFFloat deviceDamping{this, "deviceDamping", Access::InitializeOnly, 1.f, "Device friction as damping (N·s/m).",
                        Range::closed(0, 1e4).in(quantity::linearDamping)};
  SFFloat deviceInertia{this, "deviceInertia", Access::InitializeOnly, 1e-4f,
                        "Rotational inertia of the device about the burr centre (kg·m²).", Range::openClosed(0, 1).in(quantity::inertia)};
  SFFloat deviceAngularDamping{this, "deviceAngularDamping", Access::InitializeOnly, 0.002f,
                               "Device rotational friction as damping (N·m·s/rad).", Range::closed(0, 100).in(quantity::angularDamping)};
  SFFloat releaseTime{this, "releaseTime", Access::InitializeOnly, -1.f,
                      "Time (s) at which the hand lets go of the handle; negative: never.", Range::closed(-1, 1e6)};
  SFFloat outputHold{this, "outputHold", Access::InitializeOnly, 0.01f,
                     "How long (s) the simulated device applies a wrench when no new one arrives, then drops it "
                     "(the ARES firmware: 0.01).",
                     Range::closed(0.001, 10)};

  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  bool followsTrajectory() const override { return true; }
  std::shared_ptr<const Trajectory> trajectory() const override { return trajectory_; }
  void initialize(DiagnosticSink& sink) override;

  HandModel model() const;
  double outputHoldTime() const override { return double(outputHold.get()); }

private:
  std::shared_ptr<const Trajectory> trajectory_;
};

// The simulated hand and device following `trajectory` (tests and tools can
// use it without a scene).
std::unique_ptr<DeviceDriver> makeHandDriver(Trajectory trajectory, const HandModel& model, bool loop);

}  // namespace millsim
