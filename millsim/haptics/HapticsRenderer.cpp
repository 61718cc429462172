#include "millsim/haptics/HapticsRenderer.h"

namespace millsim {

void sanitize(HapticOutput& out, const Pose& device) {
  if (!isFinite(out.force) || !isFinite(out.torque)) {
    out.force = out.torque = glm::dvec3(0.0);
    out.flags |= kFlagNonFiniteSuppressed;
  }
  if (!isFinite(out.drawnTool)) out.drawnTool = isFinite(device) ? device : Pose{};
  if (!isFinite(out.intersection)) out.hasIntersection = false, out.intersection = glm::dvec3(0.0);
  if (!isFinite(out.proxy)) out.hasProxy = false, out.proxy = glm::dvec3(0.0);
  if (!isFinite(out.burrCentre)) out.burrCuts = false, out.burrCentre = glm::dvec3(0.0);
}

}  // namespace millsim
