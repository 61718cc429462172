#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// The colour behind everything else.
class Background : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFColor skyColor{this, "skyColor", Access::InputOutput, {Color{glm::vec3(0.f)}},
                   "Sky colours from the zenith down; the first is used as a flat background.", Range::closed(0, 1)};
  MFFloat skyAngle{this, "skyAngle", Access::InputOutput, {}, "Angles (radians) at which skyColor changes.",
                   Range::closed(0.0, 3.14159265358979323846).in(quantity::angle)};
  MFColor groundColor{this, "groundColor", Access::InputOutput, {}, "Ground colours from the nadir up.", Range::closed(0, 1)};
  MFFloat groundAngle{this, "groundAngle", Access::InputOutput, {}, "Angles (radians) at which groundColor changes.",
                      Range::closed(0.0, 1.57079632679489661923).in(quantity::angle)};
  SFFloat transparency{this, "transparency", Access::InputOutput, 0.f, "0 = opaque.", Range::closed(0.0, 1.0)};
  MFString backUrl{this, "backUrl", Access::InputOutput, {}, "Panorama image of the back side. Accepted; not acted on by MillSim."};
  MFString bottomUrl{this, "bottomUrl", Access::InputOutput, {}, "Panorama image of the bottom side. Accepted; not acted on by MillSim."};
  MFString frontUrl{this, "frontUrl", Access::InputOutput, {}, "Panorama image of the front side. Accepted; not acted on by MillSim."};
  MFString leftUrl{this, "leftUrl", Access::InputOutput, {}, "Panorama image of the left side. Accepted; not acted on by MillSim."};
  MFString rightUrl{this, "rightUrl", Access::InputOutput, {}, "Panorama image of the right side. Accepted; not acted on by MillSim."};
  MFString topUrl{this, "topUrl", Access::InputOutput, {}, "Panorama image of the top side. Accepted; not acted on by MillSim."};
  // X3D's binding events (MillSim keeps no binding stack: the first node of the type is used).
  SFBool set_bind{this, "set_bind", Access::InputOnly, false, "true binds this node, false unbinds it. Accepted; not acted on by MillSim."};
  SFTime bindTime{this, "bindTime", Access::OutputOnly, Time{0}, "When the node was bound or unbound. Accepted; not acted on by MillSim."};
  SFBool isBound{this, "isBound", Access::OutputOnly, false, "Whether the node is bound. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
