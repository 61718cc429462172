#include "millsim/graphics/SceneView.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "millsim/core/Scene.h"
#include "millsim/std/Appearance.h"
#include "millsim/std/Background.h"
#include "millsim/std/Box.h"
#include "millsim/std/Cylinder.h"
#include "millsim/std/Material.h"
#include "millsim/std/SceneWalk.h"
#include "millsim/std/Shape.h"
#include "millsim/std/Sphere.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/volume/PlacedVolumes.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

glm::dvec3 Camera::project(const glm::dvec3& world) const {
  const glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  return {(ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height, ndc.z * 0.5 + 0.5};
}

glm::dvec3 Camera::eye() const { return glm::dvec3(glm::inverse(view)[3]); }

Camera makeCamera(const ViewSpec& v, int width, int height, double nearDistance, double farDistance) {
  Camera c;
  c.width = width;
  c.height = height;
  const glm::dmat4 pose = glm::translate(glm::dmat4(1.0), v.position) * glm::mat4_cast(v.orientation);
  c.view = glm::inverse(pose);
  // X3D's fieldOfView is the smaller angle: vertical when the image is wide.
  const double aspect = double(width) / double(height);
  const double fovY = aspect >= 1.0 ? v.fieldOfView : 2.0 * std::atan(std::tan(v.fieldOfView / 2.0) / aspect);
  c.projection = glm::perspective(fovY, aspect, nearDistance, farDistance);
  return c;
}

namespace {

DrawMaterial materialOf(const Shape& shape) {
  DrawMaterial m;
  const auto* app = dynamic_cast<const Appearance*>(shape.appearance.get().get());
  const auto* mat = app ? dynamic_cast<const Material*>(app->material.get().get()) : nullptr;
  if (!mat) return m;
  m.diffuse = mat->diffuseColor.get().rgb;
  m.specular = mat->specularColor.get().rgb;
  m.emissive = mat->emissiveColor.get().rgb;
  m.ambient = mat->ambientIntensity.get();
  m.shininess = mat->shininess.get();
  return m;
}

void grow(SceneView& sv, bool& any, const glm::dmat4& m, const glm::dvec3& half) {
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1 ? 1 : -1) * half.x, (c & 2 ? 1 : -1) * half.y, (c & 4 ? 1 : -1) * half.z);
    const glm::dvec3 w(m * glm::dvec4(corner, 1.0));
    sv.boundsMin = any ? glm::min(sv.boundsMin, w) : w;
    sv.boundsMax = any ? glm::max(sv.boundsMax, w) : w;
    any = true;
  }
}

}  // namespace

SceneView readSceneView(const Scene& scene, const Node* viewpoint) {
  SceneView sv;
  bool haveView = false, haveBackground = false, haveBounds = false;
  walkScene(scene, [&](Node& n, const WalkFrame& at) {
    const glm::dmat4& m = at.localToWorld;
    if (auto* vp = dynamic_cast<Viewpoint*>(&n); vp && !haveView && (!viewpoint || viewpoint == vp)) {
      haveView = true;
      sv.view.position = glm::dvec3(m * glm::dvec4(glm::dvec3(vp->position.get()), 1.0));
      // Scale in the parent transform does not change where the camera looks.
      const glm::dquat parentRotation = glm::quat_cast(glm::dmat3(glm::normalize(glm::dvec3(m[0])),
                                                                  glm::normalize(glm::dvec3(m[1])),
                                                                  glm::normalize(glm::dvec3(m[2]))));
      sv.view.orientation = glm::normalize(parentRotation * glm::dquat(vp->orientation.get().quat()));
      sv.view.fieldOfView = vp->fieldOfView.get();
    }
    if (auto* bg = dynamic_cast<Background*>(&n); bg && !haveBackground && !bg->skyColor.get().empty()) {
      haveBackground = true;
      sv.background = bg->skyColor.get().front().rgb;
    }
    if (auto* shape = dynamic_cast<Shape*>(&n)) {
      Node* g = shape->geometry.get().get();
      DrawShape d{DrawShape::Kind::Sphere, m, materialOf(*shape), *at.clipPlanes};
      bool known = true;
      if (auto* s = dynamic_cast<Sphere*>(g))
        d.model = glm::scale(m, glm::dvec3(s->radius.get()));
      else if (auto* c = dynamic_cast<Cylinder*>(g))
        d.kind = DrawShape::Kind::Cylinder,
        d.model = glm::scale(m, glm::dvec3(c->radius.get(), c->height.get(), c->radius.get()));
      else if (auto* b = dynamic_cast<Box*>(g))
        d.kind = DrawShape::Kind::Box, d.model = glm::scale(m, glm::dvec3(b->size.get()));
      else
        known = false;  // no geometry, or one graphics does not draw
      if (known) {
        grow(sv, haveBounds, d.model, glm::dvec3(d.kind == DrawShape::Kind::Box ? 0.5 : 1.0));
        sv.shapes.push_back(std::move(d));
      }
    }
  });
  // Volumes from the list the haptic scene is built from: the same order by construction.
  for (const PlacedVolume& p : placedVolumes(scene)) {
    sv.volumes.push_back({p.node->volume(), p.localToWorld, double(p.node->isoValue.get()), p.clipPlanes});
    grow(sv, haveBounds, p.localToWorld, p.node->volume()->halfSize());
  }
  return sv;
}

}  // namespace millsim
