#pragma once
#include "millsim/std/Group.h"

namespace millsim {

// X3D's Collision: a group whose children are drawn and placed as a Group's.
// Its proxy is only for navigation collision, which MillSim does not do:
// the proxy is walked (so it is a scene node like any other) but not shown.
class Collision : public GroupingNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString description{this, "description", Access::InputOutput, "", "Text describing the node. Not acted on by MillSim."};
  SFBool enabled{this, "enabled", Access::InputOutput, true,
                 "Whether the viewer collides with the children. Accepted; not acted on by MillSim."};
  SFNodeOf<ChildNode> proxy{this, "proxy", Access::InitializeOnly,
                            "Geometry to collide with instead of the children; never drawn."};
  SFTime collideTime{this, "collideTime", Access::OutputOnly, Time{},
                     "When the viewer collided. Accepted; not acted on by MillSim (never sent)."};
  SFBool isActive{this, "isActive", Access::OutputOnly, false,
                  "Whether collision is on. Accepted; not acted on by MillSim (never sent)."};

  bool showsField(const Field& f) const override { return &f != &proxy; }
};

}  // namespace millsim
