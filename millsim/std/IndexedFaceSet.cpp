#include "millsim/std/IndexedFaceSet.h"

#include "millsim/std/ColorNode.h"
#include "millsim/std/Coordinate.h"
#include "millsim/std/Normal.h"
#include "millsim/std/TextureCoordinate.h"

namespace millsim {

const NodeType& IndexedFaceSet::type() {
  static const NodeType t = makeNodeType<IndexedFaceSet>(
      "IndexedFaceSet", "geometry", "Geometry3D", "A mesh of polygons indexed into a Coordinate (a jaw, a mesh exported from Blender).");
  return t;
}

void IndexedFaceSet::initialize(DiagnosticSink& sink) {
  const auto* c = dynamic_cast<const Coordinate*>(coord.get().get());
  checkIndices(sink, *this, coordIndex, c ? c->point.get().size() : 0, "Coordinate", true);
  if (const auto* n = dynamic_cast<const Normal*>(normal.get().get()))
    checkIndices(sink, *this, normalIndex, n->vector.get().size(), "Normal", true);
  if (const auto* k = dynamic_cast<const ColorNode*>(color.get().get()))
    checkIndices(sink, *this, colorIndex, k->color.get().size(), "Color", true);
  if (const auto* t = dynamic_cast<const TextureCoordinate*>(texCoord.get().get()))
    checkIndices(sink, *this, texCoordIndex, t->point.get().size(), "TextureCoordinate", true);
}

}  // namespace millsim
