#pragma once
// MillSim's simulated hand (millsim/devices/HandDevice.h) holding an emulated
// device, for the emulators of the vendor libraries. Its reference follows a
// trajectory written in scene coordinates; `map`, "s ox oy oz" (a scene's
// positionScale and positionCalibration), puts it in the device's at
// (p - o) / s. Throws std::runtime_error saying what is wrong.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "millsim/devices/HandDevice.h"
#include "millsim/devices/Trajectory.h"

namespace millsim::test {

inline std::unique_ptr<DeviceDriver> emulatedHand(const char* trajectoryFile, const char* map, const char* mapVariable) {
  Trajectory trajectory = Trajectory::load(trajectoryFile);
  if (map && *map) {
    double s = 0.0;
    glm::dvec3 o(0.0);
    if (std::sscanf(map, "%lf %lf %lf %lf", &s, &o.x, &o.y, &o.z) != 4 || !(s > 0.0))
      throw std::runtime_error(std::string(mapVariable) + " is not \"s ox oy oz\" with s > 0: " + map);
    std::vector<TrajectorySample> samples = trajectory.samples();
    for (TrajectorySample& sample : samples) sample.pose.position = (sample.pose.position - o) / s;
    trajectory = Trajectory(std::move(samples));
  }
  return makeHandDriver(std::move(trajectory), HandModel{}, false);
}

}  // namespace millsim::test
