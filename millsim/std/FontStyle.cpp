#include "millsim/std/FontStyle.h"

#include <string>

#include "millsim/core/Diagnostics.h"

namespace millsim {

const NodeType& FontStyle::type() {
  static const NodeType t = makeNodeType<FontStyle>("FontStyle", "fontStyle", "Text", "Font, size and alignment of a Text.");
  return t;
}

void FontStyle::initialize(DiagnosticSink& sink) {
  const std::string& s = style.get();
  if (s != "PLAIN" && s != "BOLD" && s != "ITALIC" && s != "BOLDITALIC")
    sink.error(location(), "FontStyle field 'style': '" + s + "' is not one of PLAIN, BOLD, ITALIC, BOLDITALIC");
  if (justify.get().size() > 2)
    sink.error(location(), "FontStyle field 'justify' has " + std::to_string(justify.get().size()) +
                               " values; expected at most 2 (major, minor)");
  for (const std::string& j : justify.get())
    if (j != "BEGIN" && j != "FIRST" && j != "MIDDLE" && j != "END")
      sink.error(location(), "FontStyle field 'justify': '" + j + "' is not one of BEGIN, FIRST, MIDDLE, END");
}

}  // namespace millsim
