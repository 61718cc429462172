#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// A cylinder along local +Y, centred on the origin (X3D convention).
class Cylinder : public GeometryNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat radius{this, "radius", Access::InitializeOnly, 1.f, "Radius (m).", Range::openClosed(0, 1e4).in(quantity::length)};
  SFFloat height{this, "height", Access::InitializeOnly, 2.f, "Length along Y (m).", Range::openClosed(0, 1e4).in(quantity::length)};
  SFBool top{this, "top", Access::InitializeOnly, true, "Whether the top cap is drawn."};
  SFBool bottom{this, "bottom", Access::InitializeOnly, true, "Whether the bottom cap is drawn."};
  SFBool side{this, "side", Access::InitializeOnly, true, "Whether the side is drawn."};
  SFBool solid{this, "solid", Access::InitializeOnly, true, "Whether back faces may be culled."};
};

}  // namespace millsim
