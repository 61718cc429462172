#pragma once
#include "millsim/std/MetadataSet.h"

namespace millsim {

// X3D's MetadataBoolean: information (booleans) about the node whose metadata field
// holds it, or an item of a MetadataSet. Kept with the scene; not acted on.
class MetadataBoolean : public MetadataNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFBool value{this, "value", Access::InputOutput, {}, "The metadata's booleans."};
};

}  // namespace millsim
