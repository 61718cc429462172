#pragma once
#include <cstdint>
#include <limits>

#include "millsim/std/MetadataSet.h"

namespace millsim {

// X3D's MetadataInteger: information (integers) about the node whose metadata field
// holds it, or an item of a MetadataSet. Kept with the scene; not acted on.
class MetadataInteger : public MetadataNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFInt32 value{this, "value", Access::InputOutput, {}, "The metadata's integers.",
                Range::closed(std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max())};
};

}  // namespace millsim
