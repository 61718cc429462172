#include "millsim/devices/TrajectoryDevice.h"

#include <cmath>
#include <filesystem>
#include <vector>

namespace millsim {

const NodeType& TrajectoryDevice::type() {
  static const NodeType t = makeNodeType<TrajectoryDevice>(
      "TrajectoryDevice", "children", "MillSim devices", "A simulated device that plays a trajectory CSV, open loop.");
  return t;
}

std::shared_ptr<const Trajectory> loadDeviceTrajectory(const Node& node, const std::vector<std::string>& urls,
                                                       DiagnosticSink& sink) {
  if (urls.empty()) {
    // A warning, not an error: `replay` and `render` take --trajectory for such a scene.
    sink.warning(node.location(), node.typeName() +
                                      " has no trajectory url: `millsim run` refuses it; `millsim replay` and "
                                      "`render` need --trajectory T.csv (set url='\"path/to/trajectory.csv\"')");
    return nullptr;
  }
  const std::filesystem::path base = node.location().file.empty()
                                         ? std::filesystem::path()
                                         : std::filesystem::path(node.location().file).parent_path();
  std::string failures;
  std::vector<std::string> failed;
  for (const std::string& u : urls) {
    try {
      auto loaded = std::make_shared<const Trajectory>(Trajectory::load(base / u));
      // A fallback url loaded: say why each earlier one did not.
      for (const std::string& f : failed)
        sink.note(node.location(), node.typeName() + " trajectory url failed, a later one was used: " + f);
      return loaded;
    } catch (const std::exception& e) {
      failures += std::string("\n  ") + e.what();
      failed.emplace_back(e.what());
    }
  }
  sink.error(node.location(), node.typeName() + " could not load any of its trajectory urls:" + failures);
  return nullptr;
}

void TrajectoryDevice::initialize(DiagnosticSink& sink) {
  HapticsDevice::initialize(sink);
  trajectory_ = loadDeviceTrajectory(*this, url.get(), sink);
}

namespace {

class TrajectoryDriver final : public DeviceDriver {
public:
  TrajectoryDriver(Trajectory trajectory, bool loop) : trajectory_(std::move(trajectory)), loop_(loop) {}

  DeviceReading read(double t, double) override {
    const double start = trajectory_.startTime(), length = trajectory_.endTime() - start;
    double local = t;
    if (loop_ && length > 0.0) local = std::fmod(std::max(t, 0.0), length);
    const TrajectorySample s = trajectory_.at(start + local);
    return {s.pose, s.button, true};
  }
  void write(const glm::dvec3&, const glm::dvec3&) override {}
  double naturalDuration() const override {
    return loop_ ? DeviceDriver::naturalDuration() : trajectory_.endTime() - trajectory_.startTime();
  }

private:
  Trajectory trajectory_;
  bool loop_;
};

}  // namespace

std::unique_ptr<DeviceDriver> makeTrajectoryDriver(Trajectory trajectory, bool loop) {
  return std::make_unique<TrajectoryDriver>(std::move(trajectory), loop);
}

std::unique_ptr<DeviceDriver> TrajectoryDevice::openDriver(const DriverOptions& options) const {
  if (options.trajectory) return makeTrajectoryDriver(*options.trajectory, loop.get());
  if (!trajectory_)
    throw DeviceError("TrajectoryDevice" + (defName().empty() ? std::string() : " '" + defName() + "'") +
                      " has no trajectory: set its url or pass --trajectory");
  return makeTrajectoryDriver(*trajectory_, loop.get());
}

}  // namespace millsim
