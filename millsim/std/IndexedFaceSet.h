#pragma once
#include "millsim/std/ComposedGeometry.h"

namespace millsim {

// A mesh of polygons: coordIndex lists each face's vertices, −1 ends a face.
// Faces are split into triangles as fans from their first vertex (exact for
// convex faces, which is X3D's default `convex TRUE`).
class IndexedFaceSet : public ComposedGeometry {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFInt32 coordIndex{this, "coordIndex", Access::InitializeOnly, {}, "Each face's vertex indices into coord, −1 after each face.",
                     Range::closed(-1, 2147483647)};
  MFInt32 normalIndex{this, "normalIndex", Access::InitializeOnly, {}, "Indices into normal, laid out as coordIndex (per vertex) or one per face.",
                      Range::closed(-1, 2147483647)};
  MFInt32 colorIndex{this, "colorIndex", Access::InitializeOnly, {}, "Indices into color, laid out as coordIndex (per vertex) or one per face.",
                     Range::closed(-1, 2147483647)};
  MFInt32 texCoordIndex{this, "texCoordIndex", Access::InitializeOnly, {}, "Indices into texCoord, laid out as coordIndex.",
                        Range::closed(-1, 2147483647)};
  MFInt32 set_coordIndex{this, "set_coordIndex", Access::InputOnly, {}, "Replaces coordIndex. Accepted; not acted on by MillSim.",
                         Range::closed(-1, 2147483647)};
  MFInt32 set_normalIndex{this, "set_normalIndex", Access::InputOnly, {}, "Replaces normalIndex. Accepted; not acted on by MillSim.",
                          Range::closed(-1, 2147483647)};
  MFInt32 set_colorIndex{this, "set_colorIndex", Access::InputOnly, {}, "Replaces colorIndex. Accepted; not acted on by MillSim.",
                         Range::closed(-1, 2147483647)};
  MFInt32 set_texCoordIndex{this, "set_texCoordIndex", Access::InputOnly, {},
                            "Replaces texCoordIndex. Accepted; not acted on by MillSim.", Range::closed(-1, 2147483647)};
  SFBool convex{this, "convex", Access::InitializeOnly, true,
                "Whether every face is convex. MillSim splits faces as fans, so a concave face may draw wrongly."};
  SFFloat creaseAngle{this, "creaseAngle", Access::InitializeOnly, 0.f,
                      "Computed normals are smoothed across edges whose faces meet at less than this angle (radians).",
                      Range::closed(0, 1e3).in(quantity::angle)};

  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
