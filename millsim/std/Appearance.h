#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

class Appearance : public AppearanceNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFNodeOf<MaterialNode> material{this, "material", Access::InputOutput, "Surface colour and shininess."};
  SFNodeOf<TextureNode> texture{this, "texture", Access::InputOutput, "An image on the geometry (an ImageTexture)."};
  SFFloat alphaCutoff{this, "alphaCutoff", Access::InputOutput, 0.5f, "Alpha threshold for alphaMode MASK. Accepted; not acted on by MillSim.",
                      Range::closed(0.0, 1.0)};
  SFString alphaMode{this, "alphaMode", Access::InputOutput, "AUTO", "AUTO, OPAQUE, MASK or BLEND. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
