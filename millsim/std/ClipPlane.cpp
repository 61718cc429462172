#include "millsim/std/ClipPlane.h"

#include <cmath>

namespace millsim {

const NodeType& ClipPlane::type() {
  static const NodeType t = makeNodeType<ClipPlane>(
      "ClipPlane", "children", "Rendering",
      "A cut-plane: clips its siblings and their descendants (not the tool) to one side of a plane. MillSim "
      "caps a VolumeObject it cuts with the section, each tissue in its colour (soft tissue such as the pulp too).");
  return t;
}

void ClipPlane::initialize(DiagnosticSink& sink) {
  const glm::vec4 p = plane.get();
  if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w)) ||
      (p.x == 0.f && p.y == 0.f && p.z == 0.f))
    sink.error(location(), "ClipPlane plane " + plane.toString() + " has no normal; expected a non-zero (a b c)");
}

}  // namespace millsim
