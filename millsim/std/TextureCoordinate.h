#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// Where each vertex of a mesh samples its texture: (s, t), 0..1 across the image.
class TextureCoordinate : public TextureCoordinateNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFVec2f point{this, "point", Access::InputOutput, {}, "Texture coordinates (s, t).", Range::closed(-1e6, 1e6)};
  SFString mapping{this, "mapping", Access::InputOutput, "", "Which texture of a multi-texture it maps. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
