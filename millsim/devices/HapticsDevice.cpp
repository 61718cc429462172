#include "millsim/devices/HapticsDevice.h"

namespace millsim {

Pose HapticsDevice::calibrate(const Pose& raw) const {
  const glm::dquat q = glm::dquat(orientationCalibration.get().quat());
  return {double(positionScale.get()) * (q * raw.position) + glm::dvec3(positionCalibration.get()),
          q * raw.orientation};
}

// Both are warnings, not errors: the scene still loads, draws and replays
// (`--renderer` supplies an algorithm), and the warning says what will happen.
void HapticsDevice::initialize(DiagnosticSink& sink) {
  if (!tool.get()) {
    const MillTool defaults;
    sink.warning(location(), typeName() + " has no MillTool: runs use the default burr (tipRadius " +
                                 formatNumber(defaults.tipRadius.get()) + " m, shaftRadius " +
                                 formatNumber(defaults.shaftRadius.get()) + " m, shaftLength " +
                                 formatNumber(defaults.shaftLength.get()) +
                                 " m); add <MillTool/> inside it to say which tool it holds");
  }
  if (stylus.get())
    sink.warning(stylus.get()->location(),
                 typeName() + "'s stylus (what H3DAPI draws at the device) is not drawn: MillSim draws the MillTool's "
                              "burr and shaft at the device; the stylus is kept only so that the scene also loads in H3DAPI");
  if (!hapticsRenderer.get())
    sink.warning(location(), typeName() + " has no haptics renderer: `millsim run`, `replay` and `render` refuse it "
                                          "unless given --renderer TYPE (add e.g. <SurfacePointRenderer/> inside it)");
}

}  // namespace millsim
