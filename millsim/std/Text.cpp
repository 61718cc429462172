#include "millsim/std/Text.h"

namespace millsim {

const NodeType& Text::type() {
  static const NodeType t = makeNodeType<Text>("Text", "geometry", "Text", "Lines of text (labels, instructions, live values).");
  return t;
}

}  // namespace millsim
