#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

class Appearance : public AppearanceNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFNodeOf<MaterialNode> material{this, "material", Access::InputOutput, "Surface colour and shininess."};
};

}  // namespace millsim
