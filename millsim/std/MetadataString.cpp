#include "millsim/std/MetadataString.h"

namespace millsim {

const NodeType& MetadataString::type() {
  static const NodeType t = makeNodeType<MetadataString>(
      "MetadataString", "metadata", "Core",
      "Metadata (strings) about the node that holds it; kept with the scene, not acted on by MillSim.");
  return t;
}

}  // namespace millsim
