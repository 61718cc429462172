#pragma once
// A --trajectory whose every position is out of the tool's reach of the
// scene's volumes (a millimetre file read as metres, most often): a warning on
// stderr naming the unit it would fit (millsim/devices/DeviceChecks.h).
#include <iostream>
#include <string>

#include "millsim/devices/DeviceChecks.h"

namespace millsim::app {

inline void warnOutOfReach(const Scene& scene, const Trajectory& trajectory, const std::string& file,
                           const char* verb) {
  const std::string warning = trajectoryReachWarning(scene, trajectory, file);
  if (!warning.empty()) std::cerr << "millsim " << verb << ": warning: " << warning << "\n";
}

}  // namespace millsim::app
