#pragma once
#include <cstdint>
#include <limits>

#include "millsim/std/MetadataSet.h"

namespace millsim {

// X3D's MetadataFloat: information (numbers) about the node whose metadata field
// holds it, or an item of a MetadataSet. Kept with the scene; not acted on.
class MetadataFloat : public MetadataNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFFloat value{this, "value", Access::InputOutput, {}, "The metadata's numbers.",
                Range::closed(-std::numeric_limits<float>::max(), std::numeric_limits<float>::max())};
};

}  // namespace millsim
