#pragma once
// TrajectoryDevice: a simulated device that plays a recorded or scripted
// trajectory (the replay CSV format: t,x,y,z,qw,qx,qy,qz,button), open loop.
#include "millsim/haptics/HapticsDevice.h"

namespace millsim {

class TrajectoryDevice : public HapticsDevice {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InitializeOnly, {},
               "Trajectory CSV (t,x,y,z,qw,qx,qy,qz,button), relative to the scene file."};
  SFBool loop{this, "loop", Access::InitializeOnly, false, "Start again at the end of the trajectory."};
};

}  // namespace millsim
