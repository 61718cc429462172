#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// The vertex positions of mesh geometry (IndexedFaceSet, IndexedTriangleSet).
class Coordinate : public CoordinateNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFVec3f point{this, "point", Access::InputOutput, {}, "Vertex positions (m).", Range::closed(-1e4, 1e4).in(quantity::length)};
};

}  // namespace millsim
