#pragma once
// The one walk over a scene that knows where things are: every node under the
// root, depth first in document order (into every node field, Inline contents
// included; a USEd node once per use), with its accumulated Transform (or
// MatrixTransform) and the ClipPlanes and lights in scope. The haptic scene
// and the graphics scene view both walk with it, so they see the same
// volumes in the same order.
#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace millsim {

class Node;
class Scene;

struct WalkFrame {
  glm::dmat4 localToWorld{1.0};
  // World-space planes (a, b, c, d) with unit normals; a point p stays when
  // dot(plane, (p, 1)) >= 0. A ClipPlane clips its siblings and their descendants.
  const std::vector<glm::dvec4>* clipPlanes = nullptr;
  // False under a node whose showsDescendants() is false, in a node field its
  // node does not show (showsField: a Collision's proxy), or under a Switch
  // child other than the chosen one: not to be drawn.
  bool shown = true;
  // True under a node whose showsDescendantsTranslucent() is true (a visible assessment region).
  bool translucent = false;
  // The lights with global FALSE that light this node: those among the
  // siblings of it or of an ancestor (X3D's scoping; the others light all).
  const std::vector<const Node*>* scopedLights = nullptr;
};

void walkScene(const Scene& scene, const std::function<void(Node&, const WalkFrame&)>& visit);

}  // namespace millsim
