#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

class Box : public GeometryNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f size{this, "size", Access::InitializeOnly, glm::vec3(2.f), "Edge lengths along X, Y, Z (m).",
               Range::openClosed(0, 1e4).in(quantity::length)};
  SFBool solid{this, "solid", Access::InitializeOnly, true, "Whether back faces may be culled."};
};

}  // namespace millsim
