#pragma once
// A run's frame log (millsim/run/FrameLog.h) read back for review: for every haptic frame,
// the world device pose, the milling switch, the time and the period, exactly
// as the renderer got them (the log's numbers are shortest round-trip text).
// `millsim replay --trajectory RUN.csv` steps a scene through them with
// HapticLoop::stepRecorded, so a run made with a real device, the mouse or the
// hand model replays to the same forces and the same removed volume.
#include <filesystem>
#include <string>
#include <vector>

#include "millsim/haptics/MillTool.h"
#include "millsim/math/Pose.h"

namespace millsim {

struct RecordedFrame {
  double t = 0.0;         // s since the run started
  double periodUs = 0.0;  // time since the previous frame started
  Pose device;            // world frame, calibration applied
  bool button = false;
  int renderer = -1;      // index into RecordedRun::renderers(), -1 if the log has no renderer column
  int tool = -1;          // index into RecordedRun::tools(), -1 if the log has no tool column
};

class RecordedRun {
public:
  // True if `text` starts (after an optional byte-order mark) with a frame
  // log's header rather than a trajectory's.
  static bool isFrameLog(const std::string& text);
  // Throws TrajectoryError (Trajectory.h) naming the file and line.
  static RecordedRun load(const std::filesystem::path& file);
  static RecordedRun parse(const std::string& text, const std::string& fileLabel);

  const std::vector<RecordedFrame>& frames() const { return frames_; }
  // The renderer type names the log mentions, in order of first appearance.
  const std::vector<std::string>& renderers() const { return renderers_; }
  // The burrs the log mentions (its tool column), in order of first appearance.
  const std::vector<ToolGeometry>& tools() const { return tools_; }
  // True when a frame's flags say the device could not output its torque
  // (kSafetyTorqueNotOutput): the run's device applied force only, and a
  // review flags the same frames.
  bool torqueNotOutput() const { return torqueNotOutput_; }

private:
  std::vector<RecordedFrame> frames_;
  std::vector<std::string> renderers_;
  std::vector<ToolGeometry> tools_;
  bool torqueNotOutput_ = false;
};

}  // namespace millsim
