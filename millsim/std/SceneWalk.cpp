#include "millsim/std/SceneWalk.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "millsim/core/Scene.h"
#include "millsim/std/ClipPlane.h"
#include "millsim/std/LightNode.h"
#include "millsim/std/Switch.h"
#include "millsim/std/Transform.h"

namespace millsim {

namespace {

using Visit = std::function<void(Node&, const WalkFrame&)>;

using Lights = std::vector<const Node*>;

void walk(Node& n, const glm::dmat4& parent, const std::vector<glm::dvec4>& clips, const Lights& lights, bool shown,
          bool translucent, const Visit& visit);

// Every node field of n; a ClipPlane among a field's nodes clips its
// siblings, and a light that is not global lights them.
void walkChildren(Node& n, const glm::dmat4& m, const std::vector<glm::dvec4>& clips, const Lights& lights, bool shown,
                  bool translucent, const Visit& visit) {
  for (Field* f : n.fields()) {
    auto* nf = dynamic_cast<NodeFieldBase*>(f);
    if (!nf) continue;
    const auto children = nf->nodes();
    // A Switch's children other than the chosen one are walked (volumes keep
    // their order for the haptic side) but not shown, and do not clip.
    const auto* sw = dynamic_cast<const Switch*>(&n);
    const Node* chosen = sw && nf == &sw->children ? sw->chosen() : nullptr;
    auto showsChild = [&](const Node& child) { return !sw || nf != &sw->children || &child == chosen; };
    std::vector<glm::dvec4> scoped = clips;
    for (const auto& child : children)
      if (auto* cp = dynamic_cast<ClipPlane*>(child.get()); cp && cp->enabled.get() && showsChild(*cp) && n.showsField(*f)) {
        // Planes transform by the inverse transpose of the node's frame.
        const glm::dvec4 p = glm::transpose(glm::inverse(m)) * glm::dvec4(cp->plane.get());
        const double len = glm::length(glm::dvec3(p));
        if (len > 0.0 && std::isfinite(len)) scoped.push_back(p / len);
      }
    Lights scopedLights = lights;
    for (const auto& child : children)
      if (auto* l = dynamic_cast<LightNode*>(child.get()); l && !l->lightsEverything() && showsChild(*l))
        scopedLights.push_back(l);
    // A field the node does not show (a Collision's proxy) is walked, not shown.
    const bool fieldShown = shown && n.showsField(*f);
    for (const auto& child : children)
      walk(*child, m, scoped, scopedLights, fieldShown && showsChild(*child), translucent, visit);
  }
}

void walk(Node& n, const glm::dmat4& parent, const std::vector<glm::dvec4>& clips, const Lights& lights, bool shown,
          bool translucent, const Visit& visit) {
  glm::dmat4 m = parent;
  if (auto* t = dynamic_cast<TransformingNode*>(&n)) m = parent * glm::dmat4(t->localMatrix());
  visit(n, WalkFrame{m, &clips, shown, translucent, &lights});
  walkChildren(n, m, clips, lights, shown && n.showsDescendants(), translucent || n.showsDescendantsTranslucent(), visit);
}

}  // namespace

void walkScene(const Scene& scene, const Visit& visit) {
  walkChildren(*scene.root, glm::dmat4(1.0), {}, {}, true, false, visit);
}

}  // namespace millsim
