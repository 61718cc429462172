#pragma once
#include "millsim/std/LightNode.h"

namespace millsim {

// A light from one direction (the sun), along `direction` in the local frame.
class DirectionalLight : public LightNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f direction{this, "direction", Access::InputOutput, glm::vec3(0.f, 0.f, -1.f), "Where the light travels (local frame).",
                    Range::closed(-1e4, 1e4)};
  SFBool global{this, "global", Access::InputOutput, false,
                "Whether it lights the whole scene (true) or only its siblings and their descendants (false)."};

  bool lightsEverything() const override { return global.get(); }
};

}  // namespace millsim
