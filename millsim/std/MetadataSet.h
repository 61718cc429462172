#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// The fields every X3D metadata node has (X3DMetadataObject).
class MetadataNode : public MetadataObject {
public:
  SFString name{this, "name", Access::InputOutput, "", "What the metadata is (the key)."};
  SFString reference{this, "reference", Access::InputOutput, "",
                     "The standard or reference that defines the name (e.g. a URL)."};
};

// X3D's MetadataSet: a named collection of metadata nodes. Inside it, a
// metadata node fills `value` unless it says containerField="metadata".
class MetadataSet : public MetadataNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFNodeOf<MetadataObject> value{this, "value", Access::InputOutput, "The metadata nodes of the set."};
};

}  // namespace millsim
