#include "millsim/std/ImportLibrary.h"

namespace millsim {

const NodeType& ImportLibrary::type() {
  static const NodeType t = makeNodeType<ImportLibrary>("ImportLibrary", "children", "Plugins", "Loads a library of extra node types.");
  return t;
}

}  // namespace millsim
