#include "millsim/std/MetadataSet.h"

namespace millsim {

const NodeType& MetadataSet::type() {
  static const NodeType t = makeNodeType<MetadataSet>(
      "MetadataSet", "metadata", "Core",
      "A named set of metadata nodes about the node that holds it; kept with the scene, not acted on by MillSim.");
  return t;
}

}  // namespace millsim
