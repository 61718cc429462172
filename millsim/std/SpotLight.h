#pragma once
#include "millsim/std/LightNode.h"

namespace millsim {

// A light at a point, shining a cone along `direction`.
class SpotLight : public LightNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFVec3f location{this, "location", Access::InputOutput, glm::vec3(0.f), "Where the light is (m, local frame).",
                   Range::closed(-1e4, 1e4).in(quantity::length)};
  SFVec3f direction{this, "direction", Access::InputOutput, glm::vec3(0.f, 0.f, -1.f), "The cone's axis (local frame).",
                    Range::closed(-1e4, 1e4)};
  SFVec3f attenuation{this, "attenuation", Access::InputOutput, glm::vec3(1.f, 0.f, 0.f),
                      "Fall-off 1 / max(a0 + a1·d + a2·d², 1) with the distance d (SI); the coefficients are read as written, not converted by a <unit> statement.",
                      Range::closed(0, 1e9)};
  SFFloat radius{this, "radius", Access::InitializeOnly, 100.f, "Beyond this distance it lights nothing (m).",
                 Range::closed(0, 1e6).in(quantity::length)};
  SFFloat beamWidth{this, "beamWidth", Access::InputOutput, 0.589049f,
                    "Half-angle of full brightness (radians); it fades from here to cutOffAngle.",
                    Range::openClosed(0, 1.5707963267948966).in(quantity::angle)};
  SFFloat cutOffAngle{this, "cutOffAngle", Access::InputOutput, 1.570796f, "Half-angle beyond which it lights nothing (radians).",
                      Range::openClosed(0, 1.5707963267948966).in(quantity::angle)};
  SFBool global{this, "global", Access::InputOutput, true, "Whether it lights the whole scene (true) or only its siblings and their descendants (false)."};

  bool lightsEverything() const override { return global.get(); }
};

}  // namespace millsim
