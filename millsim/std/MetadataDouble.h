#pragma once
#include <cstdint>
#include <limits>

#include "millsim/std/MetadataSet.h"

namespace millsim {

// X3D's MetadataDouble: information (double-precision numbers) about the node whose metadata field
// holds it, or an item of a MetadataSet. Kept with the scene; not acted on.
class MetadataDouble : public MetadataNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFDouble value{this, "value", Access::InputOutput, {}, "The metadata's double-precision numbers.",
                 Range::closed(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max())};
};

}  // namespace millsim
