#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// Title and notes for the scene; changes nothing in the simulation.
class WorldInfo : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString title{this, "title", Access::InitializeOnly, "", "Scene title."};
  MFString info{this, "info", Access::InitializeOnly, {}, "Free-form notes."};
};

}  // namespace millsim
