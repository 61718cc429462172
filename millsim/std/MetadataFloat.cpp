#include "millsim/std/MetadataFloat.h"

namespace millsim {

const NodeType& MetadataFloat::type() {
  static const NodeType t = makeNodeType<MetadataFloat>(
      "MetadataFloat", "metadata", "Core",
      "Metadata (numbers) about the node that holds it; kept with the scene, not acted on by MillSim.");
  return t;
}

}  // namespace millsim
