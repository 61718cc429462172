#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// How a viewer moves and lights the scene.
class NavigationInfo : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString navType{this, "type", Access::InputOutput, {"EXAMINE", "ANY"}, "Navigation modes, preferred first."};
  SFFloat speed{this, "speed", Access::InputOutput, 1.f, "Navigation speed (m/s).", Range::closed(0, 1e4).in(quantity::velocity)};
  SFBool headlight{this, "headlight", Access::InputOutput, true, "Whether a light shines from the viewer."};
  MFFloat avatarSize{this, "avatarSize", Access::InputOutput, {0.25f, 1.6f, 0.75f},
                     "Collision distance, eye height, step height (m).", Range::closed(0, 1e4).in(quantity::length)};
  SFFloat visibilityLimit{this, "visibilityLimit", Access::InputOutput, 0.f,
                          "Far clipping distance (m); 0 = unlimited.", Range::closed(0, 1e7).in(quantity::length)};
  SFTime transitionTime{this, "transitionTime", Access::InputOutput, Time{1.0},
                        "Seconds a viewpoint transition takes. Accepted; not acted on by MillSim.", Range::closed(0, 1e6)};
  MFString transitionType{this, "transitionType", Access::InputOutput, {"LINEAR"},
                          "TELEPORT, LINEAR or ANIMATE. Accepted; not acted on by MillSim."};
  // X3D's binding events (MillSim keeps no binding stack: the first node of the type is used).
  SFBool set_bind{this, "set_bind", Access::InputOnly, false, "true binds this node, false unbinds it. Accepted; not acted on by MillSim."};
  SFTime bindTime{this, "bindTime", Access::OutputOnly, Time{0}, "When the node was bound or unbound. Accepted; not acted on by MillSim."};
  SFBool isBound{this, "isBound", Access::OutputOnly, false, "Whether the node is bound. Accepted; not acted on by MillSim."};
  SFBool transitionComplete{this, "transitionComplete", Access::OutputOnly, false,
                            "Sent when a viewpoint transition ends. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
