#include "millsim/volume/Tissue.h"

namespace millsim {

const NodeType& Tissue::type() {
  static const NodeType t = makeNodeType<Tissue>(
      "Tissue", "tissues", "MillSim volumes",
      "A material of a VolumeObject, chosen by density or label, with its hardness and colour.");
  return t;
}

void Tissue::initialize(DiagnosticSink& sink) {
  const glm::vec2 r = densityRange.get();
  const bool byLabel = label.get() >= 0;
  const std::string who = "Tissue '" + name.get() + "'";
  if (name.get().empty()) sink.error(location(), "Tissue has no name (reports and regions refer to tissues by name)");
  if (r.x > r.y)
    sink.error(location(), who + " densityRange " + densityRange.toString() + " is empty; expected min < max");
  else if (byDensity() && byLabel)
    sink.error(location(), who + " has both densityRange " + densityRange.toString() + " and label " +
                               std::to_string(label.get()) + "; give one (or neither, for a mesh part of its name)");
}

}  // namespace millsim
