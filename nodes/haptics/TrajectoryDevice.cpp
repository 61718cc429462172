#include "millsim/haptics/TrajectoryDevice.h"

namespace millsim {

const NodeType& TrajectoryDevice::type() {
  static const NodeType t = makeNodeType<TrajectoryDevice>(
      "TrajectoryDevice", "children", "MillSim devices", "A simulated device that plays a trajectory CSV, open loop.");
  return t;
}

}  // namespace millsim
