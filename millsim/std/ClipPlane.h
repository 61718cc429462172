#pragma once
#include <glm/vec4.hpp>

#include "millsim/core/NodeKinds.h"

namespace millsim {

// A cut-plane (X3D ClipPlane): hides the geometry on the negative side of the
// plane a·x + b·y + c·z + d = 0. As in X3D it clips its siblings and their
// descendants, and the plane is in its parent's coordinate system. MillSim
// draws the tool unclipped: a cut-plane is for looking into the tooth, and a
// volume it cuts is capped with its section (millsim/graphics/CutSection.h).
class ClipPlane : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec4f plane{this, "plane", Access::InputOutput, glm::vec4(0.f, 1.f, 0.f, 0.f),
                "Plane equation (a b c d) in the parent's frame; points with a·x + b·y + c·z + d >= 0 stay "
                "visible. (a b c) need not be unit length but must not be zero; d is in metres when it is.",
                Range::closed(-1e4, 1e4).in({.length = 1, .lastOnly = true})};
  SFBool enabled{this, "enabled", Access::InputOutput, true, "Whether the plane clips."};

  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
