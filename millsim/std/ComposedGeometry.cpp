#include "millsim/std/ComposedGeometry.h"

#include <string>

#include "millsim/core/Diagnostics.h"

namespace millsim {

void ComposedGeometry::checkIndices(DiagnosticSink& sink, const Node& node, const MFInt32& indices, std::size_t count,
                                    std::string_view what, bool separators) {
  const auto& v = indices.get();
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (separators && v[i] == -1) continue;
    if (v[i] < 0 || std::size_t(v[i]) >= count) {
      sink.error(node.location(), node.typeName() + " field '" + std::string(indices.name()) + "': index " +
                                      std::to_string(v[i]) + " at position " + std::to_string(i) + " is out of range: the " +
                                      std::string(what) + " has " + std::to_string(count) + " entries (expected 0.." +
                                      std::to_string(count == 0 ? 0 : count - 1) + (separators ? ", or -1 to end a face)" : ")"));
      return;
    }
  }
}

}  // namespace millsim
