#pragma once
// X3DComposedGeometryNode: the fields IndexedFaceSet and IndexedTriangleSet
// share — vertex data in child nodes, and how it applies (per vertex or per
// face, winding).
#include "millsim/std/ShapeKinds.h"

namespace millsim {

class ComposedGeometry : public GeometryNode {
public:
  SFNodeOf<CoordinateNode> coord{this, "coord", Access::InputOutput, "Vertex positions (a Coordinate)."};
  SFNodeOf<NormalNode> normal{this, "normal", Access::InputOutput,
                              "Normals (a Normal); without one, MillSim computes them from the faces."};
  SFNodeOf<ColorKindNode> color{this, "color", Access::InputOutput, "Colours (a Color); they replace the Material's diffuseColor."};
  SFNodeOf<TextureCoordinateNode> texCoord{this, "texCoord", Access::InputOutput,
                                           "Texture coordinates (a TextureCoordinate); without one, the bounding box maps the texture."};
  SFBool ccw{this, "ccw", Access::InitializeOnly, true, "Whether faces wind counter-clockwise seen from the front."};
  SFBool colorPerVertex{this, "colorPerVertex", Access::InitializeOnly, true, "Colours per vertex (true) or per face."};
  SFBool normalPerVertex{this, "normalPerVertex", Access::InitializeOnly, true, "Normals per vertex (true) or per face."};
  SFBool solid{this, "solid", Access::InputOutput, true, "Whether back faces may be culled. Accepted; MillSim draws both sides."};

protected:
  // Reports an index in `indices` (−1 separators allowed when `separators`)
  // that is not below `count`, naming the field: a mesh that points past its
  // data would draw garbage.
  static void checkIndices(DiagnosticSink& sink, const Node& node, const MFInt32& indices, std::size_t count,
                           std::string_view what, bool separators);
};

}  // namespace millsim
