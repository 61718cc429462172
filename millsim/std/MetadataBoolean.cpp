#include "millsim/std/MetadataBoolean.h"

namespace millsim {

const NodeType& MetadataBoolean::type() {
  static const NodeType t = makeNodeType<MetadataBoolean>(
      "MetadataBoolean", "metadata", "Core",
      "Metadata (booleans) about the node that holds it; kept with the scene, not acted on by MillSim.");
  return t;
}

}  // namespace millsim
