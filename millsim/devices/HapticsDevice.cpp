#include "millsim/devices/HapticsDevice.h"

namespace millsim {

Pose HapticsDevice::calibrate(const Pose& raw) const {
  const glm::dquat q = glm::dquat(orientationCalibration.get().quat());
  return {q * raw.position + glm::dvec3(positionCalibration.get()), q * raw.orientation};
}

void HapticsDevice::initialize(DiagnosticSink& sink) {
  if (!hapticsRenderer.get())
    sink.warning(location(), typeName() + " has no haptics renderer: no force will be rendered "
                                          "(add e.g. <LineProxyRenderer/> inside it)");
}

}  // namespace millsim
