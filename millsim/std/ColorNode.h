#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// X3D's Color node: colours of mesh geometry, per vertex or per face. (The
// class is ColorNode because Color is the SFColor value type.)
class ColorNode : public ColorKindNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFColor color{this, "color", Access::InputOutput, {}, "RGB colours.", Range::closed(0, 1)};
};

}  // namespace millsim
