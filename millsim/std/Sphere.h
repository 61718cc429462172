#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

class Sphere : public GeometryNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat radius{this, "radius", Access::InitializeOnly, 1.f, "Radius (m).", Range::openClosed(0, 1e4).in(quantity::length)};
  SFBool solid{this, "solid", Access::InitializeOnly, true, "Whether back faces may be culled."};
};

}  // namespace millsim
