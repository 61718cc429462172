#include "millsim/graphics/SceneView.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "millsim/core/Scene.h"
#include "millsim/graphics/ShapeMeshes.h"
#include "millsim/std/Appearance.h"
#include "millsim/std/Background.h"
#include "millsim/std/Box.h"
#include "millsim/std/Cone.h"
#include "millsim/std/Cylinder.h"
#include "millsim/std/DirectionalLight.h"
#include "millsim/std/FontStyle.h"
#include "millsim/std/ImageTexture.h"
#include "millsim/std/IndexedFaceSet.h"
#include "millsim/std/IndexedTriangleSet.h"
#include "millsim/std/Material.h"
#include "millsim/std/NavigationInfo.h"
#include "millsim/std/PointLight.h"
#include "millsim/std/SpotLight.h"
#include "millsim/std/Text.h"
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
  m.transparency = mat->transparency.get();
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

ViewSpec viewOf(const Viewpoint& vp, const glm::dmat4& m) {
  ViewSpec v;
  v.position = glm::dvec3(m * glm::dvec4(glm::dvec3(vp.position.get()), 1.0));
  // Scale in the parent transform does not change where the camera looks.
  const glm::dquat parentRotation = glm::quat_cast(glm::dmat3(
      glm::normalize(glm::dvec3(m[0])), glm::normalize(glm::dvec3(m[1])), glm::normalize(glm::dvec3(m[2]))));
  v.orientation = glm::normalize(parentRotation * glm::dquat(vp.orientation.get().quat()));
  v.fieldOfView = vp.fieldOfView.get();
  return v;
}

// Index of `plane` in the cut-plane list, added if new (a USEd ClipPlane is one plane).
int cutIndex(SceneView& sv, const glm::dvec4& plane) {
  for (std::size_t i = 0; i < sv.cutPlanes.size(); ++i)
    if (sv.cutPlanes[i].plane == plane) return int(i);
  sv.cutPlanes.push_back({plane, true, "ClipPlane " + std::to_string(sv.cutPlanes.size() + 1), false});
  return int(sv.cutPlanes.size() - 1);
}

std::vector<int> cutsOf(SceneView& sv, const ClipPlanes& planes) {
  std::vector<int> out;
  for (const glm::dvec4& p : planes) out.push_back(cutIndex(sv, p));
  return out;
}

DrawTexture textureOf(const Shape& shape) {
  const auto* app = dynamic_cast<const Appearance*>(shape.appearance.get().get());
  const auto* tex = app ? dynamic_cast<const ImageTexture*>(app->texture.get().get()) : nullptr;
  if (!tex) return {};
  return {tex->imageFile(), tex->repeatS.get(), tex->repeatT.get()};
}

DrawText textOf(const Text& t) {
  DrawText d;
  d.lines = t.string.get();
  d.lengths = t.length.get();
  d.maxExtent = t.maxExtent.get();
  if (const auto* f = dynamic_cast<const FontStyle*>(t.fontStyle.get().get())) {
    if (!f->family.get().empty()) d.family = f->family.get();
    d.style = f->style.get();
    d.size = f->size.get();
    d.spacing = f->spacing.get();
    if (!f->justify.get().empty()) d.justifyMajor = f->justify.get()[0];
    if (f->justify.get().size() > 1) d.justifyMinor = f->justify.get()[1];
    d.topToBottom = f->topToBottom.get();
  }
  return d;
}

// A Text's extent in its local frame, estimated without the font (framing
// the view and the depth range need only a fair box): glyphs about 0.6 em wide.
void textBox(const DrawText& t, glm::dvec3& lo, glm::dvec3& hi) {
  std::size_t widest = 0;
  for (const std::string& l : t.lines) widest = std::max(widest, l.size());
  double width = 0.6 * t.size * double(widest);
  if (t.maxExtent > 0.f) width = std::min(width, double(t.maxExtent));
  for (float l : t.lengths) width = std::max(width, double(l));
  const double height = t.size * (1.0 + t.spacing * double(t.lines.empty() ? 0 : t.lines.size() - 1));
  lo = glm::dvec3(-width, -height, 0.0);
  hi = glm::dvec3(width, height, 0.0);
}

glm::dvec3 directionIn(const glm::dmat4& m, const glm::vec3& d) {
  const glm::dvec3 w = glm::dmat3(m) * glm::dvec3(d);
  const double len = glm::length(w);
  return len > 0.0 && std::isfinite(len) ? w / len : glm::dvec3(0.0, 0.0, -1.0);
}

// A length in the local frame as a world length (the frame's mean scale).
double lengthIn(const glm::dmat4& m, double l) {
  const glm::dmat3 a(m);
  return l * (glm::length(a[0]) + glm::length(a[1]) + glm::length(a[2])) / 3.0;
}

void readLight(SceneView& sv, Node& n, const glm::dmat4& m, std::vector<const Node*>& nodes) {
  const auto* base = dynamic_cast<const LightNode*>(&n);
  if (!base || !base->on.get() || int(sv.lights.size()) >= kMaxLights) return;
  DrawLight l;
  l.global = base->lightsEverything();
  l.colour = base->color.get().rgb * base->intensity.get();
  l.ambient = base->color.get().rgb * base->ambientIntensity.get();
  if (const auto* d = dynamic_cast<const DirectionalLight*>(&n)) {
    l.kind = DrawLight::Kind::Directional;
    l.direction = directionIn(m, d->direction.get());
  } else if (const auto* p = dynamic_cast<const PointLight*>(&n)) {
    l.kind = DrawLight::Kind::Point;
    l.position = glm::dvec3(m * glm::dvec4(glm::dvec3(p->location.get()), 1.0));
    l.attenuation = p->attenuation.get();
    l.radius = lengthIn(m, p->radius.get());
  } else if (const auto* s = dynamic_cast<const SpotLight*>(&n)) {
    l.kind = DrawLight::Kind::Spot;
    l.position = glm::dvec3(m * glm::dvec4(glm::dvec3(s->location.get()), 1.0));
    l.direction = directionIn(m, s->direction.get());
    l.attenuation = s->attenuation.get();
    l.radius = lengthIn(m, s->radius.get());
    l.beamWidth = s->beamWidth.get();
    l.cutOffAngle = s->cutOffAngle.get();
  } else {
    return;
  }
  sv.lights.push_back(l);
  nodes.push_back(&n);
}

// Which of the view's lights light a node at `at`: every global one, and
// the scoped ones among its or its ancestors' siblings.
std::uint32_t lightsAt(const SceneView& sv, const std::vector<const Node*>& nodes, const WalkFrame& at) {
  std::uint32_t mask = 0;
  for (std::size_t i = 0; i < sv.lights.size(); ++i) {
    const bool scopedHere = at.scopedLights && std::find(at.scopedLights->begin(), at.scopedLights->end(), nodes[i]) !=
                                                   at.scopedLights->end();
    if (sv.lights[i].global || scopedHere) mask |= 1u << i;
  }
  return mask;
}

// The newest event among a node's fields and those of the nodes in its node fields.
std::uint64_t versionOf(const Node& n, int depth = 0) {
  std::uint64_t v = 0;
  for (const Field* f : n.fields()) {
    if (!f->upToDate()) return UINT64_MAX;  // a routed value not yet pulled: build anew
    v = std::max(v, f->lastEvent());
    if (const auto* nf = dynamic_cast<const NodeFieldBase*>(f); nf && depth < 1)
      for (const auto& child : nf->nodes()) v = std::max(v, versionOf(*child, depth + 1));
  }
  return v;
}

TriangleMesh buildMesh(const Node& g) {
  if (const auto* f = dynamic_cast<const IndexedFaceSet*>(&g)) return millsim::meshOf(*f);
  if (const auto* t = dynamic_cast<const IndexedTriangleSet*>(&g)) return millsim::meshOf(*t);
  return millsim::meshOf(dynamic_cast<const Cone&>(g));
}

// The unit primitives with texture coordinates, built once.
std::shared_ptr<const TriangleMesh> texturedPrimitive(DrawShape::Kind kind) {
  static const auto sphere = std::make_shared<const TriangleMesh>(texturedSphere());
  static const auto cylinder = std::make_shared<const TriangleMesh>(texturedCylinder());
  static const auto box = std::make_shared<const TriangleMesh>(texturedBox());
  return kind == DrawShape::Kind::Sphere ? sphere : kind == DrawShape::Kind::Cylinder ? cylinder : box;
}

}  // namespace

ViewSpec frameBounds(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dquat& orientation, double fieldOfView) {
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6);
  const double fov = std::clamp(fieldOfView, 1e-3, 3.1);
  // The bounding sphere fills the smaller image side, with 10 % to spare.
  const double distance = 1.1 * radius / std::sin(0.5 * fov);
  ViewSpec v;
  v.orientation = glm::normalize(orientation);
  v.position = centre + (glm::mat3_cast(v.orientation) * glm::dvec3(0.0, 0.0, 1.0)) * distance;
  v.fieldOfView = fov;
  return v;
}

std::shared_ptr<const TriangleMesh> ShapeMeshCache::meshOf(const Node& geometry) {
  const std::uint64_t version = versionOf(geometry);
  Entry& e = entries_[&geometry];
  if (!e.mesh || version == UINT64_MAX || version != e.version) {
    e.mesh = std::make_shared<const TriangleMesh>(buildMesh(geometry));
    e.version = versionOf(geometry);  // reading pulled any routed values in
  }
  return e.mesh;
}

int SceneView::addUserCut(const glm::dvec3& towards) {
  for (std::size_t i = 0; i < cutPlanes.size(); ++i)
    if (cutPlanes[i].user) return int(i);
  const glm::dvec3 n = glm::length(towards) > 0.0 ? glm::normalize(towards) : glm::dvec3(0.0, 0.0, 1.0);
  // Keeps the far half (n points at the viewer): the cut opens the volume towards them.
  cutPlanes.push_back({glm::dvec4(-n, glm::dot(n, centre())), false, "user cut", true});
  const int index = int(cutPlanes.size() - 1);
  for (DrawVolume& v : volumes) v.cuts.push_back(index);
  return index;
}

SceneView readSceneView(const Scene& scene, const Node* viewpoint, ShapeMeshCache* meshes) {
  SceneView sv;
  bool haveView = false, haveBackground = false, haveBounds = false, haveNavigation = false;
  // Lights first: a scoped light lights its siblings before it in the file too.
  std::vector<const Node*> lightNodes;
  walkScene(scene, [&](Node& n, const WalkFrame& at) {
    if (at.shown) readLight(sv, n, at.localToWorld, lightNodes);
  });
  // A scoped light among the scene's top-level nodes lights the whole scene,
  // the tool too (it belongs to the top-level device).
  for (std::size_t i = 0; i < lightNodes.size(); ++i)
    for (const auto& top : scene.root->children.get())
      if (top.get() == lightNodes[i]) sv.lights[i].global = true;
  std::vector<std::uint32_t> volumeLights;  // of each placed volume, in walk order
  walkScene(scene, [&](Node& n, const WalkFrame& at) {
    const glm::dmat4& m = at.localToWorld;
    if (auto* vp = dynamic_cast<Viewpoint*>(&n)) {
      NamedView named{vp->description.get(), viewOf(*vp, m), glm::dvec3(m * glm::dvec4(glm::dvec3(vp->centerOfRotation.get()), 1.0)),
                      vp->centerOfRotation.get() != glm::vec3(0.f)};
      if (named.name.empty()) named.name = vp->defName();
      if (named.name.empty()) named.name = "Viewpoint " + std::to_string(sv.viewpoints.size() + 1);
      sv.viewpoints.push_back(named);
      if (!haveView && (!viewpoint || viewpoint == vp)) {
        haveView = true;
        sv.view = named.view;
      }
    }
    if (auto* nav = dynamic_cast<NavigationInfo*>(&n); nav && !haveNavigation) {
      haveNavigation = true;
      if (!nav->navType.get().empty()) sv.navigation = nav->navType.get().front();
      sv.headlight = nav->headlight.get();
    }
    if (auto* vo = dynamic_cast<VolumeObject*>(&n); vo && vo->volume())  // as placedVolumes() lists them
      volumeLights.push_back(lightsAt(sv, lightNodes, at));
    if (auto* bg = dynamic_cast<Background*>(&n); bg && !haveBackground && !bg->skyColor.get().empty()) {
      haveBackground = true;
      sv.background = bg->skyColor.get().front().rgb;
    }
    if (auto* shape = dynamic_cast<Shape*>(&n); shape && at.shown) {
      Node* g = shape->geometry.get().get();
      DrawShape d;
      d.kind = DrawShape::Kind::Sphere, d.model = m, d.material = materialOf(*shape), d.clipPlanes = *at.clipPlanes;
      if (at.translucent) {
        d.material.transparency = std::max(d.material.transparency, kRegionTransparency);
        d.overlay = true;
      }
      bool known = true;
      glm::dvec3 half(1.0), centre(0.0);  // the local box grow() takes, about `centre`
      if (auto* s = dynamic_cast<Sphere*>(g))
        d.model = glm::scale(m, glm::dvec3(s->radius.get()));
      else if (auto* c = dynamic_cast<Cylinder*>(g))
        d.kind = DrawShape::Kind::Cylinder,
        d.model = glm::scale(m, glm::dvec3(c->radius.get(), c->height.get(), c->radius.get()));
      else if (auto* b = dynamic_cast<Box*>(g))
        d.kind = DrawShape::Kind::Box, d.model = glm::scale(m, glm::dvec3(b->size.get())), half = glm::dvec3(0.5);
      else if (dynamic_cast<Cone*>(g) || dynamic_cast<IndexedFaceSet*>(g) || dynamic_cast<IndexedTriangleSet*>(g)) {
        d.kind = DrawShape::Kind::Mesh;
        d.mesh = meshes ? meshes->meshOf(*g) : std::make_shared<const TriangleMesh>(buildMesh(*g));
        half = 0.5 * glm::dvec3(d.mesh->boundsMax - d.mesh->boundsMin);
        centre = 0.5 * glm::dvec3(d.mesh->boundsMax + d.mesh->boundsMin);
        known = !d.mesh->positions.empty();
      } else if (auto* t = dynamic_cast<Text*>(g)) {
        d.kind = DrawShape::Kind::Text;
        d.text = std::make_shared<const DrawText>(textOf(*t));
        glm::dvec3 lo, hi;
        textBox(*d.text, lo, hi);
        half = 0.5 * (hi - lo), centre = 0.5 * (hi + lo);
        known = !d.text->lines.empty();
      } else {
        known = false;  // no geometry, or one graphics does not draw
      }
      if (known) {
        d.lights = lightsAt(sv, lightNodes, at);
        d.texture = textureOf(*shape);
        if (!d.texture.file.empty() && d.kind != DrawShape::Kind::Mesh && d.kind != DrawShape::Kind::Text) {
          d.mesh = texturedPrimitive(d.kind);  // the same solid, with texture coordinates
          d.kind = DrawShape::Kind::Mesh;
        }
        d.cuts = cutsOf(sv, d.clipPlanes);
        grow(sv, haveBounds, glm::translate(d.model, centre), half);
        sv.shapes.push_back(std::move(d));
      }
    }
  });
  // Volumes from the list the haptic scene is built from: the same order by construction.
  for (const PlacedVolume& p : placedVolumes(scene)) {
    sv.volumes.push_back(
        {p.node->volume(), p.localToWorld, double(p.node->isoValue.get()), p.clipPlanes, cutsOf(sv, p.clipPlanes),
         p.node->tissueMap(), volumeLights.at(sv.volumes.size())});
    grow(sv, haveBounds, p.localToWorld, p.node->volume()->halfSize());
  }
  if (!haveView && haveBounds) {
    sv.view = frameBounds(sv.boundsMin, sv.boundsMax, sv.view.orientation, sv.view.fieldOfView);
    sv.framed = true;
  }
  return sv;
}

}  // namespace millsim
