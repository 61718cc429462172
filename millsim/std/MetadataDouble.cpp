#include "millsim/std/MetadataDouble.h"

namespace millsim {

const NodeType& MetadataDouble::type() {
  static const NodeType t = makeNodeType<MetadataDouble>(
      "MetadataDouble", "metadata", "Core",
      "Metadata (double-precision numbers) about the node that holds it; kept with the scene, not acted on by MillSim.");
  return t;
}

}  // namespace millsim
