#include "millsim/graphics/DrawnFields.h"

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

FieldWatch drawnFields(const Scene& scene) {
  std::vector<Field*> fields;
  scene.forEachNode([&](Node& n) {
    if (dynamic_cast<TransformingNode*>(&n) || dynamic_cast<Switch*>(&n) || dynamic_cast<Material*>(&n) ||
        dynamic_cast<ClipPlane*>(&n) || dynamic_cast<Background*>(&n) || dynamic_cast<Text*>(&n) ||
        dynamic_cast<FontStyle*>(&n) || dynamic_cast<LightNode*>(&n) || dynamic_cast<NavigationInfo*>(&n) ||
        dynamic_cast<Coordinate*>(&n) || dynamic_cast<Normal*>(&n) || dynamic_cast<ColorNode*>(&n) ||
        dynamic_cast<TextureCoordinate*>(&n))
      for (Field* f : n.fields()) fields.push_back(f);
  });
  return FieldWatch(std::move(fields));
}

}  // namespace millsim
