#pragma once
// TrajectoryDevice: a simulated device that plays a recorded or scripted
// trajectory (the replay CSV format: t,x,y,z,qw,qx,qy,qz,button), open loop.
#include "millsim/devices/HapticsDevice.h"

namespace millsim {

// Loads the first readable trajectory of `urls`, relative to the folder of the
// node's scene file; reports failures at the node. Null when urls is empty or
// nothing loads. Shared by the simulated devices.
std::shared_ptr<const Trajectory> loadDeviceTrajectory(const Node& node, const std::vector<std::string>& urls,
                                                       DiagnosticSink& sink);

// Plays a trajectory open loop: the pose at time t is the trajectory's at
// start + t (wrapping when `loop`); the wrench sent is dropped.
std::unique_ptr<DeviceDriver> makeTrajectoryDriver(Trajectory trajectory, bool loop);

class TrajectoryDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InitializeOnly, {},
               "Trajectory CSV (t,x,y,z,qw,qx,qy,qz,button), relative to the scene file."};
  SFBool loop{this, "loop", Access::InitializeOnly, false, "Start again at the end of the trajectory."};

  std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const override;
  bool followsTrajectory() const override { return true; }
  void initialize(DiagnosticSink& sink) override;

  // The trajectory loaded from `url` at initialize(), or null if url is empty.
  std::shared_ptr<const Trajectory> trajectory() const override { return trajectory_; }

private:
  std::shared_ptr<const Trajectory> trajectory_;
};

}  // namespace millsim
