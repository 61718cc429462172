#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// Lines of text in the local XY plane, facing +Z, drawn in the Shape's
// Material (its emissiveColor makes a label readable in any light). The
// string may change while running (a route from a NumberToText shows a live
// value).
class Text : public GeometryNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString string{this, "string", Access::InputOutput, {}, "The lines of text."};
  SFNodeOf<FontStyleNode> fontStyle{this, "fontStyle", Access::InputOutput, "Font, size and alignment (a FontStyle)."};
  MFFloat length{this, "length", Access::InputOutput, {}, "Width each line is stretched or squeezed to (m); 0 keeps its own.",
                 Range::closed(0, 1e4).in(quantity::length)};
  SFFloat maxExtent{this, "maxExtent", Access::InputOutput, 0.f, "Lines wider than this are squeezed to it (m); 0 means no limit.",
                    Range::closed(0, 1e4).in(quantity::length)};
  SFBool solid{this, "solid", Access::InputOutput, false, "Whether back faces may be culled. Accepted; MillSim draws both sides."};
  MFVec2f lineBounds{this, "lineBounds", Access::OutputOnly, {}, "Each line's extent. Accepted; not computed by MillSim."};
  SFVec3f origin{this, "origin", Access::OutputOnly, glm::vec3(0.f), "Where the first line starts. Accepted; not computed by MillSim."};
  SFVec2f textBounds{this, "textBounds", Access::OutputOnly, glm::vec2(0.f), "The text's extent. Accepted; not computed by MillSim."};
};

}  // namespace millsim
