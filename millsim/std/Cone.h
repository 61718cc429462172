#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// A cone along local +Y, centred on the origin, apex up (X3D convention).
class Cone : public GeometryNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat bottomRadius{this, "bottomRadius", Access::InitializeOnly, 1.f, "Radius of the base (m).",
                       Range::openClosed(0, 1e4).in(quantity::length)};
  SFFloat height{this, "height", Access::InitializeOnly, 2.f, "Length along Y (m).", Range::openClosed(0, 1e4).in(quantity::length)};
  SFBool side{this, "side", Access::InputOutput, true, "Whether the side is drawn."};
  SFBool bottom{this, "bottom", Access::InputOutput, true, "Whether the base is drawn."};
  SFBool solid{this, "solid", Access::InputOutput, true, "Whether back faces may be culled. Accepted; MillSim draws both sides."};
};

}  // namespace millsim
