#pragma once
// The length units a trajectory CSV's header may name on its positions
// (t,x_mm,y_mm,z_mm,...), with metres per unit: read by Trajectory::parse,
// and tried, in this order (the likeliest slip first), by the reach warning
// to name the unit a file would fit.
#include <string_view>

namespace millsim {

struct TrajectoryLengthUnit {
  std::string_view name;
  double metres;
};

inline constexpr TrajectoryLengthUnit kTrajectoryLengthUnits[] = {{"m", 1.0}, {"mm", 1e-3}, {"cm", 1e-2}, {"um", 1e-6}};

}  // namespace millsim
