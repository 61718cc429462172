#pragma once
#include <numbers>

#include "millsim/core/NodeKinds.h"

namespace millsim {

// A camera: where the scene is seen from.
class Viewpoint : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f position{this, "position", Access::InputOutput, glm::vec3(0.f, 0.f, 10.f), "Camera position (m).", Range::closed(-1e4, 1e4).in(quantity::length)};
  SFRotation orientation{this, "orientation", Access::InputOutput, Rotation{},
                         "Camera orientation; the camera looks along its local -Z with +Y up."};
  SFFloat fieldOfView{this, "fieldOfView", Access::InputOutput, float(std::numbers::pi / 4),
                      "Smaller of the horizontal and vertical view angles (radians).",
                      Range{0.0, std::numbers::pi, true, true}.in(quantity::angle)};
  SFVec3f centerOfRotation{this, "centerOfRotation", Access::InputOutput, glm::vec3(0.f),
                           "Point the viewer orbits about (m).", Range::closed(-1e4, 1e4).in(quantity::length)};
  SFString description{this, "description", Access::InputOutput, "", "Text shown to the user."};
  SFBool jump{this, "jump", Access::InputOutput, true, "Whether binding moves the viewer to this viewpoint."};
  SFFloat nearDistance{this, "nearDistance", Access::InputOutput, -1.f,
                       "Near clipping distance (m); -1 = the browser's choice. Accepted; not acted on by MillSim.", Range::closed(-1, 1e7).in(quantity::lengthOrNone)};
  SFFloat farDistance{this, "farDistance", Access::InputOutput, -1.f,
                      "Far clipping distance (m); -1 = the browser's choice. Accepted; not acted on by MillSim.", Range::closed(-1, 1e7).in(quantity::lengthOrNone)};
  SFBool retainUserOffsets{this, "retainUserOffsets", Access::InputOutput, false,
                           "Whether navigation offsets are kept when the viewpoint is re-bound. Accepted; not acted on by MillSim."};
  SFBool viewAll{this, "viewAll", Access::InputOutput, false, "Whether to fit the whole scene into view. Accepted; not acted on by MillSim."};
  // X3D's binding events (MillSim keeps no binding stack: the first node of the type is used).
  SFBool set_bind{this, "set_bind", Access::InputOnly, false, "true binds this node, false unbinds it. Accepted; not acted on by MillSim."};
  SFTime bindTime{this, "bindTime", Access::OutputOnly, Time{0}, "When the node was bound or unbound. Accepted; not acted on by MillSim."};
  SFBool isBound{this, "isBound", Access::OutputOnly, false, "Whether the node is bound. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
