#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// A visible object: one geometry drawn with one appearance.
class Shape : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFNodeOf<AppearanceNode> appearance{this, "appearance", Access::InputOutput, "How the geometry looks."};
  SFNodeOf<GeometryNode> geometry{this, "geometry", Access::InputOutput, "What is drawn."};
  SFVec3f bboxCenter{this, "bboxCenter", Access::InitializeOnly, glm::vec3(0.f),
                     "Centre of a bounding box hint (m). Accepted; not acted on by MillSim.", Range::closed(-1e4, 1e4).in(quantity::length)};
  SFVec3f bboxSize{this, "bboxSize", Access::InitializeOnly, glm::vec3(-1.f),
                   "Size of a bounding box hint (m); -1 -1 -1 means none. Accepted; not acted on by MillSim.", Range::closed(-1, 1e4).in(quantity::lengthOrNone)};
  SFBool castShadow{this, "castShadow", Access::InputOutput, true, "Whether the shape casts shadows. Accepted; not acted on by MillSim."};
  SFBool bboxDisplay{this, "bboxDisplay", Access::InputOutput, false, "Whether to draw the bounding box. Accepted; not acted on by MillSim."};
  SFBool visible{this, "visible", Access::InputOutput, true, "Whether to draw the shape. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
