#pragma once
// A device trajectory: the replay CSV format
//   t,x,y,z,qw,qx,qy,qz,button
// t in seconds (strictly increasing), the burr centre in metres (the device's
// frame: the device node's calibration places it in the world, the identity by default;
// a header of x_mm,y_mm,z_mm — or _cm, _um, _m — says the file's unit instead),
// a unit quaternion (w first), button 0/1 (milling on). Poses between rows are
// interpolated (linear position, slerp orientation); the button holds the
// value of the row at or before t. A run's frame log (RecordedRun.h) is read
// as a trajectory of the poses and button it recorded.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "millsim/math/Pose.h"

namespace millsim {

// A malformed trajectory: the message names the file and line.
struct TrajectoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct TrajectorySample {
  double t = 0.0;
  Pose pose;
  bool button = false;
};

// The text of a trajectory (or frame log) file: a regular file of at most
// 1 GiB, so that a FIFO, a device or a huge file is a clear error, not a hang.
std::string readTrajectoryText(const std::filesystem::path& file);

class Trajectory {
public:
  // What a trajectory may hold: times in [0, kMaxTime] s (a day: a replay
  // steps through every frame of it), positions within kMaxPosition m of the
  // origin, at most kMaxRows rows (about 3 h of 1 kHz samples).
  static constexpr double kMaxTime = 86400.0;
  static constexpr double kMaxPosition = 10.0;
  static constexpr std::size_t kMaxRows = 10'000'000;

  // Throws TrajectoryError, prefixed by `where` ("file:line: "), unless a row
  // holds what a trajectory may: a time in [0, kMaxTime] s after
  // `previousTime` (NaN for the first row), a position within kMaxPosition m,
  // a unit quaternion (within 1e-3). Returns the quaternion's length.
  static double checkRow(const std::string& where, double t, const glm::dvec3& position, const glm::dquat& q,
                         double previousTime);

  static Trajectory load(const std::filesystem::path& file);
  static Trajectory parse(const std::string& text, const std::string& fileLabel);
  explicit Trajectory(std::vector<TrajectorySample> samples);

  double startTime() const { return samples_.front().t; }
  double endTime() const { return samples_.back().t; }
  TrajectorySample at(double t) const;
  const std::vector<TrajectorySample>& samples() const { return samples_; }

  // Writes the CSV format (shortest round-trip numbers).
  std::string toCsv() const;

private:
  std::vector<TrajectorySample> samples_;
};

}  // namespace millsim
