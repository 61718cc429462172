#pragma once
// X3DLightNode: what every light has. MillSim lights Shapes and volumes with
// every light that is on — one with global FALSE only its siblings and their
// descendants, as X3D scopes it — together with the headlight that
// NavigationInfo's `headlight` switches.
#include "millsim/core/NodeKinds.h"

namespace millsim {

class LightNode : public ChildNode {
public:
  SFBool on{this, "on", Access::InputOutput, true, "Whether the light shines."};
  SFColor color{this, "color", Access::InputOutput, Color{glm::vec3(1.f)}, "The light's colour.", Range::closed(0, 1)};
  SFFloat intensity{this, "intensity", Access::InputOutput, 1.f, "Brightness of direct light (1 = full).", Range::closed(0, 1e4)};
  SFFloat ambientIntensity{this, "ambientIntensity", Access::InputOutput, 0.f, "How much the light adds to ambient light.",
                           Range::closed(0, 1)};
  SFBool shadows{this, "shadows", Access::InputOutput, false, "Whether it casts shadows. Accepted; not acted on by MillSim."};
  SFFloat shadowIntensity{this, "shadowIntensity", Access::InputOutput, 1.f, "How dark its shadows are. Accepted; not acted on by MillSim.",
                          Range::closed(0, 1)};

  // X3D's `global` (each light type has its own default).
  virtual bool lightsEverything() const = 0;
};

}  // namespace millsim
