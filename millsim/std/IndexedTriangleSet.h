#pragma once
#include "millsim/std/ComposedGeometry.h"

namespace millsim {

// A mesh of triangles: every three entries of index are one triangle's
// vertices; normals, colours and texture coordinates are indexed alike.
class IndexedTriangleSet : public ComposedGeometry {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFInt32 index{this, "index", Access::InitializeOnly, {}, "Vertex indices into coord, three per triangle.",
                Range::closed(0, 2147483647)};
  MFInt32 set_index{this, "set_index", Access::InputOnly, {}, "Replaces index. Accepted; not acted on by MillSim.",
                    Range::closed(0, 2147483647)};

  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
