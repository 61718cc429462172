#include "millsim/std/TextureCoordinate.h"

namespace millsim {

const NodeType& TextureCoordinate::type() {
  static const NodeType t =
      makeNodeType<TextureCoordinate>("TextureCoordinate", "texCoord", "Texturing", "Texture coordinates of a mesh's vertices.");
  return t;
}

}  // namespace millsim
