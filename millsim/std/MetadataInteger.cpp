#include "millsim/std/MetadataInteger.h"

namespace millsim {

const NodeType& MetadataInteger::type() {
  static const NodeType t = makeNodeType<MetadataInteger>(
      "MetadataInteger", "metadata", "Core",
      "Metadata (integers) about the node that holds it; kept with the scene, not acted on by MillSim.");
  return t;
}

}  // namespace millsim
