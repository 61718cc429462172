#include "millsim/std/IndexedTriangleSet.h"

#include <string>

#include "millsim/core/Diagnostics.h"
#include "millsim/std/Coordinate.h"

namespace millsim {

const NodeType& IndexedTriangleSet::type() {
  static const NodeType t = makeNodeType<IndexedTriangleSet>("IndexedTriangleSet", "geometry", "Rendering",
                                                             "A mesh of triangles indexed into a Coordinate.");
  return t;
}

void IndexedTriangleSet::initialize(DiagnosticSink& sink) {
  const auto* c = dynamic_cast<const Coordinate*>(coord.get().get());
  checkIndices(sink, *this, index, c ? c->point.get().size() : 0, "Coordinate", false);
  if (index.get().size() % 3 != 0)
    sink.warning(location(), "IndexedTriangleSet field 'index' has " + std::to_string(index.get().size()) +
                                 " entries, not a multiple of 3: the last " + std::to_string(index.get().size() % 3) +
                                 " are ignored");
}

}  // namespace millsim
