#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// Base of nodes with children (X3DGroupingNode).
class GroupingNode : public ChildNode {
public:
  MFNodeOf<ChildNode> children{this, "children", Access::InputOutput, "Nodes grouped under this one."};
  SFVec3f bboxCenter{this, "bboxCenter", Access::InitializeOnly, glm::vec3(0.f),
                     "Centre of a bounding box hint (m); unused by MillSim.", Range::closed(-1e4, 1e4).in(quantity::length)};
  SFVec3f bboxSize{this, "bboxSize", Access::InitializeOnly, glm::vec3(-1.f),
                   "Size of a bounding box hint (m); -1 -1 -1 means none.", Range::closed(-1, 1e4).in(quantity::lengthOrNone)};
  SFBool bboxDisplay{this, "bboxDisplay", Access::InputOutput, false, "Whether to draw the bounding box. Accepted; not acted on by MillSim."};
  SFBool visible{this, "visible", Access::InputOutput, true, "Whether to draw the children. Accepted; not acted on by MillSim."};
};

// Groups child nodes without changing their frame.
class Group : public GroupingNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
};

}  // namespace millsim
