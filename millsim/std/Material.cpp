#include "millsim/std/Material.h"

namespace millsim {

const NodeType& Material::type() {
  static const NodeType t = makeNodeType<Material>("Material", "material", "Shape", "Surface colour of a Shape.");
  return t;
}

}  // namespace millsim
