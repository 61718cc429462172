#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// A visible object: one geometry drawn with one appearance.
class Shape : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFNodeOf<AppearanceNode> appearance{this, "appearance", Access::InputOutput, "How the geometry looks."};
  SFNodeOf<GeometryNode> geometry{this, "geometry", Access::InputOutput, "What is drawn."};
};

}  // namespace millsim
