#include "millsim/graphics/DrawnFields.h"

#include <algorithm>

#include "millsim/core/Scene.h"
#include "millsim/std/Background.h"
#include "millsim/std/ClipPlane.h"
#include "millsim/std/ColorNode.h"
#include "millsim/std/Coordinate.h"
#include "millsim/std/FontStyle.h"
#include "millsim/std/LightNode.h"
#include "millsim/std/Material.h"
#include "millsim/std/NavigationInfo.h"
#include "millsim/std/Normal.h"
#include "millsim/std/Text.h"
#include "millsim/std/TextureCoordinate.h"
#include "millsim/std/Switch.h"
#include "millsim/std/Transform.h"

namespace millsim {

DrawnFields::DrawnFields(const Scene& scene) {
  scene.forEachNode([&](Node& n) {
    if (dynamic_cast<TransformingNode*>(&n) || dynamic_cast<Switch*>(&n) || dynamic_cast<Material*>(&n) ||
        dynamic_cast<ClipPlane*>(&n) || dynamic_cast<Background*>(&n) || dynamic_cast<Text*>(&n) ||
        dynamic_cast<FontStyle*>(&n) || dynamic_cast<LightNode*>(&n) || dynamic_cast<NavigationInfo*>(&n) ||
        dynamic_cast<Coordinate*>(&n) || dynamic_cast<Normal*>(&n) || dynamic_cast<ColorNode*>(&n) ||
        dynamic_cast<TextureCoordinate*>(&n))
      for (Field* f : n.fields()) fields_.push_back(f);
  });
  mark();
}

bool DrawnFields::changed() const {
  // A routed field is stale until read; a field set directly has a newer event.
  return std::any_of(fields_.begin(), fields_.end(),
                     [&](const Field* f) { return !f->upToDate() || f->lastEvent() > newest_; });
}

void DrawnFields::mark() {
  for (Field* f : fields_) {
    if (!f->upToDate()) (void)f->toString();  // a read pulls the routed value in
    newest_ = std::max(newest_, f->lastEvent());
  }
}

}  // namespace millsim
