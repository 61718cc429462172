#include "millsim/std/Coordinate.h"

namespace millsim {

const NodeType& Coordinate::type() {
  static const NodeType t = makeNodeType<Coordinate>("Coordinate", "coord", "Rendering", "Vertex positions of a mesh.");
  return t;
}

}  // namespace millsim
