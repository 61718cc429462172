#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// Normal vectors of mesh geometry, per vertex or per face.
class Normal : public NormalNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFVec3f vector{this, "vector", Access::InputOutput, {}, "Normal directions (made unit length when drawn).",
                 Range::closed(-1e4, 1e4)};
};

}  // namespace millsim
